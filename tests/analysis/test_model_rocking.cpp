// A single block shaken by a half-sine pulse, written as a model file and run through the generic study, against
// the rocking analysis of `rocking_block` (analysis/rocking.hpp, itself checked against an independent ODE of the
// block on its springs): the same rocking history.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "blockdem/analysis/error_metrics.hpp"
#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/rocking.hpp"
#include "blockdem/analysis/study.hpp"

using namespace blockdem;

namespace test_model_rocking {

TEST_CASE("a single block shaken by a half-sine through the generic study rocks as rocking_block's analysis has it") {
  const auto dir = std::filesystem::temp_directory_path() / "blockdem_model_rocking";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // The pulse: 4 m/s^2 for 0.25 s (twice the static uplift g b / h = 1.96 m/s^2), then 1.25 s at rest; 1 ms samples.
  const double amplitude = 4.0, pulse = 0.25, duration = 1.5, dt = 1e-3;
  motion::Record record;
  record.dt = dt;
  {
    std::ofstream out(dir / "half_sine.txt");
    for (int k = 0; k * dt <= duration + 1e-12; ++k) {
      const double t = k * dt;
      const double a = t < pulse ? amplitude * std::sin(std::numbers::pi * t / pulse) : 0.0;
      record.acceleration.push_back(a);
      out << t << " " << a << "\n";
    }
  }
  analysis::RockingOptions rocking;  // 0.2 x 0.5 x 1 m, 2000 kg/m^3, 45 degrees, 1e9 Pa/m
  rocking.base_acceleration = record;
  rocking.duration = duration;
  const auto expected = analysis::analyse_rocking(rocking);
  REQUIRE(expected.uplift);
  REQUIRE_FALSE(expected.overturned);

  // The same block and base, the same joint; two monitor points on the top edge give the rotation about y.
  const std::string text = R"({
    "blockdem_model": 1,
    "name": "a rocking block",
    "materials": {"stone": {"density": 2000}, "base": {"density": 2000}},
    "joints": [{"between": ["*", "*"], "law": "mohr_coulomb", "normal_stiffness": 1e9, "shear_stiffness": 1e9,
                "friction_angle_deg": 45}],
    "contacts": {"kinds": "general"},
    "blocks": [
      {"name": "base", "group": "base", "material": "base", "motion": "base", "box": [[-1.4, -0.5, -0.5], [1.4, 0.5, 0]]},
      {"name": "block", "group": "block", "material": "stone", "box": [[-0.1, -0.25, 0], [0.1, 0.25, 1]]}
    ],
    "monitors": [{"name": "heel", "block": "block", "point": [-0.1, 0, 1]}, {"name": "toe", "block": "block", "point": [0.1, 0, 1]}],
    "excitation": {"record": "half_sine.txt", "units": "m/s2", "dt": 0.001, "axis": "x", "baseline": "none"},
    "study": {"levels_percent": [100], "rest_s": 0, "damping": {"scheme": "none"},
              "timestep": {"mass_increase_percent": 0}, "outputs": {"history_dt_s": 0.001}}
  })";
  const auto file = analysis::parse_model_file(text, (dir / "rocking.json").string(), dir.string());
  auto o = file.study;
  o.out_dir = (dir / "run").string();
  o.progress = false;
  const auto r = analysis::run_study(file.structure, o);
  REQUIRE(r.levels.size() == 1);
  const auto history = analysis::read_csv_table(o.out_dir + "/history_100.csv");
  auto column = [&](const std::string& name) -> const std::vector<double>& { return history.values[history.column(name)]; };
  const auto& t = column("time");
  const auto &heel_x = column("heel_ux"), &heel_z = column("heel_uz"), &toe_x = column("toe_ux"), &toe_z = column("toe_uz");
  // The top edge, 0.2 m long at the start: theta about +y turns x towards -z.
  double peak = 0, peak_expected = 0, error = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double theta = -std::atan2(toe_z[k] - heel_z[k], 0.2 + toe_x[k] - heel_x[k]);
    const auto at = static_cast<std::size_t>(std::lround(t[k] / rocking.record_interval));
    if (at >= expected.rotation.size()) break;
    peak = std::max(peak, std::abs(theta));
    peak_expected = std::max(peak_expected, std::abs(expected.rotation[at]));
    error = std::max(error, std::abs(theta - expected.rotation[at]));
  }
  MESSAGE("peak rotation: study ", peak, " rad, rocking_block ", peak_expected, " rad; largest difference ", error, " rad");
  CHECK(peak_expected > 0.01);
  CHECK(peak == doctest::Approx(peak_expected).epsilon(0.02));
  CHECK(error < 0.05 * peak_expected);
  std::filesystem::remove_all(dir);
}

}  // namespace test_model_rocking
