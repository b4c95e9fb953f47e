#pragma once
// What an equivalent-static pushover (pushover.hpp) runs: the direction of the body acceleration lambda g, the range
// and resolution of the bisection, and what counts as equilibrium and as collapse; and what it finds.

#include <functional>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/number_text.hpp"

namespace blockdem::analysis {

struct PushoverOptions {
  char axis = 'x';                   // the body acceleration acts along +x, +y (or -x, -y with a negative sign below)
  double sign = 1;                   // +1 or -1: the direction along the axis
  double upper = 1.0;                // the largest lambda tried: a structure standing there is reported as such
  double resolution = 0.002;         // the bisection stops when the bracket is this narrow
  double collapse_displacement = 0;  // m: a block or node moving farther means collapse (0: 2 % of the structure's height)
  double tolerance = 1e-5;           // unbalanced-force ratio of equilibrium
  long long max_steps = 400000;      // per trial; a trial that reaches it neither stood nor collapsed: it counts as collapsed
  std::string out_dir;               // pushover.csv, report.json, damage VTU of the last trial that stood and the first that fell
  bool progress = true;
  std::function<void()> poll;        // if set, called about every 1024 steps of a trial (Python's Ctrl-C is heard there)

  void validate() const {
    auto check = [](bool ok, const std::string& what) {
      if (!ok) throw InvalidArgument("pushover: " + what);
    };
    check(axis == 'x' || axis == 'y', std::string("the axis must be x or y (horizontal), got ") + axis);
    check(sign == 1 || sign == -1, "the direction must be +1 or -1");
    check(upper > 0 && upper <= 10, "the largest lambda must be in (0, 10], got " + num(upper));
    check(resolution >= 1e-5 && resolution < upper, "the resolution must be in [1e-5, upper), got " + num(resolution));
    check(collapse_displacement >= 0 && collapse_displacement <= 100, "the collapse displacement must be in [0, 100] m (0: 2 % of the height)");
    check(tolerance > 0 && tolerance <= 0.1, "the tolerance must be in (0, 0.1], got " + num(tolerance));
    check(max_steps >= 100, "the most steps per trial must be >= 100");
  }
};

/// One lambda tried.
struct PushoverTrial {
  double lambda = 0;
  bool stands = false;
  double max_displacement = 0;  // m, of any free block or node from where it was built
  double unbalanced_ratio = 0;
  long long steps = 0;
  double wall_seconds = 0;
};

struct PushoverResult {
  std::vector<PushoverTrial> trials;  // in the order run
  double collapse_multiplier = 0;     // the middle of the final bracket; 0 if it falls under its own weight; upper if it stands there
  double lower = 0, upper = 0;        // the final bracket: stands at lower, collapses at upper
  bool stands_at_upper = false, falls_under_weight = false;
  double collapse_displacement = 0;   // m, as used
  double wall_seconds = 0;
};

}  // namespace blockdem::analysis
