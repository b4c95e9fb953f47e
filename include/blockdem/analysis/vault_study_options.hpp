#pragma once
// What a cross-vault study runs (paper Sect. 5, 6.1): the study's options (study_options.hpp) and the vault's own,
// its geometry and materials (models::CrossVaultOptions) and how its blocks move (rigid, mixed, deformable).

#include <string>

#include "blockdem/analysis/study_options.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"
#include "blockdem/models/cross_vault.hpp"

namespace blockdem::analysis {

/// How the blocks move (paper Sect. 5, 6.1.1): all rigid; mixed (the steel frame rigid, every other free block
/// deformable); all deformable (constant-strain tetrahedra).
enum class VaultKinematics { rigid, mixed, deformable };
inline constexpr const char* name(VaultKinematics k) {
  switch (k) {
    case VaultKinematics::rigid: return "rigid";
    case VaultKinematics::mixed: return "mixed";
    case VaultKinematics::deformable: return "deformable";
  }
  return "?";
}

struct VaultStudyOptions : StudyOptions {
  models::CrossVaultOptions vault;
  VaultKinematics kinematics = VaultKinematics::rigid;
  double max_edge = 0.25;        // m, of the tetrahedra of masonry and concrete (Sect. 5)
  double steel_max_edge = 0.5;   // m, of the steel frame and the movable (steel) piers (Sect. 5)

  VaultStudyOptions() {
    context = "cross vault study";
    program = "blockdem cross_vault run";
  }

  void validate() const {
    auto check = [this](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument(context + ": " + what);
    };
    vault.validate();
    check(max_edge >= 0.01 && max_edge <= 10, "--max-edge must be in [0.01, 10] m, got " + num(max_edge));
    check(steel_max_edge >= 0.01 && steel_max_edge <= 10, "--steel-max-edge must be in [0.01, 10] m, got " + num(steel_max_edge));
    StudyOptions::validate();
  }
};

}  // namespace blockdem::analysis
