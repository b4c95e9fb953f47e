// The expansion of a sweep into cases (analysis/sweep.hpp): the paper's sensitivity sweep (Sect. 5, Table 3) and an
// incremental dynamic analysis over records and levels, their order, ids and options, and the errors of a bad grid.

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "blockdem/analysis/sweep.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_sweep {
using namespace blockdem::analysis;

namespace {

/// The paper's sweep (Table 3): MassProp at 2, 3, 4, 5 % x centre 3, 7.5, 15 Hz; Maxwell at 2, 3, 4, 5 % over 1-40 Hz.
SweepSpec table3() {
  SweepSpec spec;
  spec.schemes = {SweepScheme{DampingScheme::mass, {0.02, 0.03, 0.04, 0.05}, {3, 7.5, 15}, {}, {}},
                  SweepScheme{DampingScheme::maxwell, {0.02, 0.03, 0.04, 0.05}, {}, {}, {}}};
  return spec;
}

}  // namespace

TEST_CASE("sweep: the paper's sensitivity sweep (Table 3) expands to its 16 analyses, in the documented order") {
  const auto cases = expand_sweep(table3(), VaultStudyOptions{});
  REQUIRE(cases.size() == 16);
  CHECK(cases[0].id == "rigid_aqa75_mass_z0.02_f3");
  CHECK(cases[1].id == "rigid_aqa75_mass_z0.02_f7.5");
  CHECK(cases[2].id == "rigid_aqa75_mass_z0.02_f15");
  CHECK(cases[3].id == "rigid_aqa75_mass_z0.03_f3");
  CHECK(cases[11].id == "rigid_aqa75_mass_z0.05_f15");
  CHECK(cases[12].id == "rigid_aqa75_maxwell_z0.02_b1-40_n3");
  CHECK(cases[15].id == "rigid_aqa75_maxwell_z0.05_b1-40_n3");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    CAPTURE(cases[i].id);
    CHECK(cases[i].index == i);
    CHECK(cases[i].options.levels == std::vector<double>{25, 50, 75});  // incremental: all levels in one case
    CHECK(cases[i].options.record_path.empty());
  }
  CHECK(cases[4].options.damping == DampingScheme::mass);
  CHECK(cases[4].options.zeta == 0.03);
  CHECK(cases[4].options.frequency_hz == 7.5);
  CHECK(cases[13].options.damping == DampingScheme::maxwell);
  CHECK(cases[13].options.zeta == 0.03);
  CHECK(cases[13].options.lower_hz == 1);
  CHECK(cases[13].options.upper_hz == 40);
}

TEST_CASE("sweep: an IDA is a case per record and level, each from the undamaged vault, ids do not depend on the grid") {
  SweepSpec spec;
  spec.records = {"data/RSN1_EW.AT2", "/abs/path/ESM_IT.AQA..HNE.txt", ""};
  spec.schemes = {SweepScheme{DampingScheme::none, {}, {}, {}, {}}};
  spec.levels = {25, 50};
  spec.incremental = false;
  const auto cases = expand_sweep(spec, VaultStudyOptions{});
  REQUIRE(cases.size() == 6);
  CHECK(cases[0].id == "rigid_RSN1_EW_none_L25");
  CHECK(cases[1].id == "rigid_RSN1_EW_none_L50");
  CHECK(cases[2].id == "rigid_ESM_IT.AQA..HNE_none_L25");
  CHECK(cases[5].id == "rigid_aqa75_none_L50");
  CHECK(cases[2].options.record_path == "/abs/path/ESM_IT.AQA..HNE.txt");
  CHECK(cases[3].options.levels == std::vector<double>{50});
  // The same parameters give the same id in a smaller grid: ids name cases, positions do not.
  spec.records = {""};
  spec.levels = {50};
  const auto one = expand_sweep(spec, VaultStudyOptions{});
  REQUIRE(one.size() == 1);
  CHECK(one[0].id == cases[5].id);
  CHECK(one[0].index == 0);
}

TEST_CASE("sweep: defaults are named in the ids, and the base options carry over") {
  SweepSpec spec;
  spec.kinematics = {VaultKinematics::rigid, VaultKinematics::mixed};
  spec.schemes = {SweepScheme{DampingScheme::maxwell, {}, {}, {{0.5, 20}}, {2, 4}},
                  SweepScheme{DampingScheme::rayleigh, {0.05}, {}, {}, {}}};
  VaultStudyOptions base;
  base.rest = 0.25;
  base.window_end = 6;
  const auto cases = expand_sweep(spec, base);
  REQUIRE(cases.size() == 6);  // 2 kinematics x (2 Maxwell branch counts + 1 Rayleigh)
  CHECK(cases[0].id == "rigid_aqa75_maxwell_z-default_b0.5-20_n2");
  CHECK(cases[1].id == "rigid_aqa75_maxwell_z-default_b0.5-20_n4");
  CHECK(cases[2].id == "rigid_aqa75_rayleigh_z0.05_b1-40");
  CHECK(cases[3].id == "mixed_aqa75_maxwell_z-default_b0.5-20_n2");
  CHECK(cases[1].options.branches == 4);
  CHECK(cases[1].options.zeta == 0);  // the scheme's default
  CHECK(cases[1].options.lower_hz == 0.5);
  CHECK(cases[3].options.kinematics == VaultKinematics::mixed);
  for (const auto& c : cases) {
    CHECK(c.options.rest == 0.25);
    CHECK(c.options.window_end == 6);
  }
}

TEST_CASE("sweep: a bad grid is refused with the field and its range named") {
  const auto message = [](const SweepSpec& spec) {
    try {
      expand_sweep(spec, VaultStudyOptions{});
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SweepSpec spec = table3();
  spec.schemes[0].bands_hz = {{1, 40}};
  CHECK(message(spec).find("mass: takes no band (bands_hz") != std::string::npos);
  spec = table3();
  spec.schemes[1].zetas.push_back(0.7);
  const std::string zeta = message(spec);
  CHECK(zeta.find("case rigid_aqa75_maxwell_z0.7_b1-40_n3") != std::string::npos);
  CHECK(zeta.find("--zeta must be in (0, 0.5)") != std::string::npos);
  spec = table3();
  spec.levels = {25, 25};
  spec.incremental = false;
  CHECK(message(spec).find("two cases would both be rigid_aqa75_mass_z0.02_f3_L25") != std::string::npos);
  spec = table3();
  spec.schemes.clear();
  CHECK(message(spec).find("schemes: give at least one") != std::string::npos);
  spec = table3();
  spec.schemes[1].branches = {5};
  CHECK(message(spec).find("--branches must be in 1..4") != std::string::npos);
  spec = table3();
  spec.schemes.push_back(SweepScheme{DampingScheme::none, {0.02}, {}, {}, {}});
  CHECK(message(spec).find("none: takes no damping ratio") != std::string::npos);
}

}  // namespace test_sweep
