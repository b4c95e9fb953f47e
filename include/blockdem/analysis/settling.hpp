#pragma once
// How a structure comes to rest: inertial relaxation or local damping.

namespace blockdem::analysis {

/// How a structure is brought to rest under gravity before the levels (both with static mass scaling, DESIGN §4), and
/// each trial of the arch's analysis (arch.hpp) to equilibrium or collapse: inertial relaxation
/// (integrate/inertial_relaxation.hpp: no damping force, every velocity stopped when the model starts uphill) or
/// local damping (damping/local.hpp; 3DEC's, the paper's). Automatic: inertial relaxation for a model with deformable
/// blocks (half the steps of local damping on the deformable vault), local damping for one of rigid blocks only
/// (seconds there either way, and its settled state stays as before). Both stop at the same unbalanced-force ratio; where joints slip or
/// crack while settling, the path, and so the state reached, differs a little.
enum class Settling { automatic, inertial, local };
inline constexpr const char* name(Settling s) {
  switch (s) {
    case Settling::automatic: return "auto";
    case Settling::inertial: return "inertial";
    case Settling::local: return "local";
  }
  return "?";
}

/// The method `s` stands for on a model with or without deformable blocks: inertial or local, never automatic.
inline constexpr Settling resolved(Settling s, bool has_deformable_blocks) {
  if (s != Settling::automatic) return s;
  return has_deformable_blocks ? Settling::inertial : Settling::local;
}

}  // namespace blockdem::analysis
