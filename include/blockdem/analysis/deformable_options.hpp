#pragma once
// The options shared by the analyses that can mesh their blocks into constant-strain tetrahedra (arch, rocking
// block): the mesh, the elastic material and partial density scaling.

#include <string>

#include "blockdem/core/error.hpp"

namespace blockdem::analysis {

struct DeformableOptions {
  bool deformable = false;  // the free blocks meshed into constant-strain tetrahedra
  double max_edge = 0.25;   // m, of the tetrahedra
  double young = 5e9;       // Pa
  double poisson = 0.2;
  double target_dt = 0;     // s: partial density scaling to this timestep (0: none)

  /// Throws InvalidArgument naming the program, the option, its allowed range and the value given.
  void validate_deformable(const std::string& program) const {
    auto check = [&](bool ok, const std::string& what, double value) {
      if (!ok) throw InvalidArgument(program + ": " + what + ", got " + std::to_string(value));
    };
    check(max_edge > 0, "max edge must be > 0 m", max_edge);
    check(young > 0, "Young's modulus must be > 0 Pa", young);
    check(poisson > -1 && poisson < 0.5, "Poisson's ratio must be in (-1, 0.5)", poisson);
    check(target_dt >= 0, "target timestep must be >= 0 s (0: no density scaling)", target_dt);
  }
};

}  // namespace blockdem::analysis
