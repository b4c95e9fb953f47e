// The sweep description file (analysis/sweep_file.hpp): the paper's sensitivity sweep (Sect. 5, Table 3) and an
// IDA written as files and expanded, paths taken relative to the file's folder, and bad files refused with the
// file, line, column and key.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "blockdem/analysis/sweep_file.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_sweep_file {
using namespace blockdem::analysis;

namespace {

/// Table 3: MassProp at 2, 3, 4, 5 % x centre 3, 7.5, 15 Hz; Maxwell at 2, 3, 4, 5 % over 1-40 Hz, 3 branches.
const char* const table3_file = R"({
  "kinematics": "rigid",
  "levels": [25, 50, 75],
  "schemes": [
    {"scheme": "mass", "zeta": [0.02, 0.03, 0.04, 0.05], "frequency_hz": [3, 7.5, 15]},
    {"scheme": "maxwell", "zeta": [0.02, 0.03, 0.04, 0.05], "band_hz": [1, 40], "branches": 3}
  ]
})";

/// The message of the InvalidArgument that parsing `text` as "bad.json" throws, or "no error".
std::string sweep_error(const std::string& text) {
  try {
    parse_sweep(text, "bad.json");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("sweep file: the paper's sensitivity sweep (Table 3) as a file expands to its 16 analyses") {
  const SweepSpec spec = parse_sweep(table3_file, "table3.json");
  REQUIRE(spec.schemes.size() == 2);
  CHECK(spec.schemes[0].scheme == DampingScheme::mass);
  CHECK(spec.schemes[0].frequencies_hz == std::vector<double>{3, 7.5, 15});
  CHECK(spec.schemes[1].bands_hz == std::vector<std::array<double, 2>>{{1, 40}});  // one pair is one band
  CHECK(spec.schemes[1].branches == std::vector<int>{3});                          // one number is a list of one
  CHECK(spec.incremental);
  CHECK(spec.measure == IntensityMeasure::level);
  const auto cases = expand_sweep(spec, VaultStudyOptions{});
  REQUIRE(cases.size() == 16);
  CHECK(cases.front().id == "rigid_aqa75_mass_z0.02_f3");
  CHECK(cases[12].id == "rigid_aqa75_maxwell_z0.02_b1-40_n3");
  CHECK(cases.back().id == "rigid_aqa75_maxwell_z0.05_b1-40_n3");
  CHECK(cases.back().options.levels == std::vector<double>{25, 50, 75});
}

TEST_CASE("sweep file: an IDA by peak ground acceleration, with records relative to the file's folder") {
  const SweepSpec spec = parse_sweep(R"({
    "records": ["records/RSN1_EW.AT2", "/data/ESM.txt", ""],
    "pga_g": [0.1, 0.2],
    "incremental": false,
    "measured": "measured.csv",
    "measured_level": 75,
    "schemes": [{"scheme": "none"}]
  })", "ida.json", "/study");
  CHECK(spec.records == std::vector<std::string>{
                            (std::filesystem::path("/study") / "records/RSN1_EW.AT2").string(), "/data/ESM.txt", ""});
  CHECK(spec.measured == (std::filesystem::path("/study") / "measured.csv").string());
  CHECK(spec.measured_level == 75);
  CHECK(spec.measure == IntensityMeasure::pga);
  const auto cases = expand_sweep(spec, VaultStudyOptions{});
  REQUIRE(cases.size() == 6);
  CHECK(cases[0].id == "rigid_RSN1_EW_none_pga0.1g");
  CHECK(cases[1].id == "rigid_RSN1_EW_none_pga0.2g");
  CHECK(cases[5].id == "rigid_aqa75_none_pga0.2g");
  CHECK(cases[0].intensities == std::vector<double>{0.1});
  CHECK(cases[0].measure == IntensityMeasure::pga);
  CHECK(cases[0].options.record_path == "/study/records/RSN1_EW.AT2");

  const SweepSpec sa = parse_sweep(R"({"sa_g": 0.3, "sa_period_s": 0.25, "kinematics": ["mixed", "deformable"],
    "schemes": {"scheme": "rayleigh", "zeta": 0.03, "band_hz": [[2, 20], [1, 10]]}})", "sa.json");
  CHECK(sa.measure == IntensityMeasure::sa);
  CHECK(sa.sa_period == 0.25);
  CHECK(sa.levels == std::vector<double>{0.3});
  CHECK(sa.kinematics == std::vector<VaultKinematics>{VaultKinematics::mixed, VaultKinematics::deformable});
  CHECK(sa.schemes.at(0).bands_hz.size() == 2);
  CHECK(sa.records == std::vector<std::string>{""});  // the default: the built-in record
}

TEST_CASE("sweep file: read from disk, relative paths resolved against the file's folder") {
  const auto folder = std::filesystem::temp_directory_path() / "blockdem_test_sweep_file";
  std::filesystem::create_directories(folder);
  const auto path = (folder / "sweep.json").string();
  std::ofstream(path) << R"({"records": "RSN1_EW.AT2", "schemes": [{"scheme": "maxwell"}]})";
  const SweepSpec spec = read_sweep_file(path);
  CHECK(spec.records == std::vector<std::string>{(folder / "RSN1_EW.AT2").string()});
  std::ofstream(path) << "{\"schemes\": [\n  {\"scheme\": \"maxwel\"}]}";
  CHECK_THROWS_WITH_AS(read_sweep_file(path),
                       (path + ":2:14: schemes[0].scheme: unknown damping scheme \"maxwel\" (allowed: none, mass, "
                               "stiffness, rayleigh, maxwell)").c_str(),
                       InvalidArgument);
  std::filesystem::remove_all(folder);
  CHECK_THROWS_WITH_AS(read_sweep_file(path), (path + ": no such file").c_str(), InvalidArgument);
}

TEST_CASE("sweep file: bad files are refused with the line, column, key and what is allowed") {
  struct Bad {
    std::string text;
    std::string start;  // "bad.json:line:column: key"
    std::string word;
  };
  const std::string none = R"("schemes": [{"scheme": "none"}])";
  const std::vector<Bad> bad{
      {"{\"schemes\": [\n  {\"scheme\": \"none\"},\n]}", "bad.json:3:1: ", "trailing comma"},
      {"[]", "bad.json:1:1: ", "one JSON object"},
      {"{}", "bad.json:1:1: schemes", "missing"},
      {R"({"schemes": []})", "bad.json:1:13: schemes", "at least one"},
      {"{" + none + ",\n \"level\": [25]}", "bad.json:2:11: unknown key \"level\"",
       "allowed keys: model, kinematics, records, levels, pga_g, sa_g, sa_period_s, incremental, measured"},
      {R"({"schemes": [{"scheme": "none", "zetas": 0.02}]})", "bad.json:1:42: unknown key \"zetas\" in schemes[0]",
       "allowed keys: scheme, zeta, frequency_hz, band_hz, branches"},
      {R"({"schemes": [{"scheme": "viscous"}]})", "bad.json:1:25: schemes[0].scheme",
       "unknown damping scheme \"viscous\" (allowed: none, mass, stiffness, rayleigh, maxwell)"},
      {R"({"schemes": [{"zeta": 0.03}]})", "bad.json:1:14: schemes[0]", "\"scheme\" is missing"},
      {"{\"kinematics\": [\"rigid\", \"bent\"], " + none + "}", "bad.json:1:26: kinematics[1]",
       "unknown kinematics \"bent\" (allowed: rigid, mixed, deformable)"},
      {"{\"levels\": [25], \"pga_g\": [0.1], " + none + "}", "bad.json:1:27: pga_g",
       "only one of levels, pga_g, sa_g (levels is given at 1:12)"},
      {"{\"sa_period_s\": 0.3, " + none + "}", "bad.json:1:17: sa_period_s", "only allowed with sa_g"},
      {"{\"sa_g\": [0.3], " + none + "}", "bad.json:1:10: sa_g", "needs \"sa_period_s\""},
      {"{\"levels\": \"25\", " + none + "}", "bad.json:1:12: levels",
       "expected a number or a list of numbers, got a string"},
      {"{\"levels\": [25, \"50\"], " + none + "}", "bad.json:1:17: levels[1]", "expected a number, got a string"},
      {"{\"incremental\": 1, " + none + "}", "bad.json:1:17: incremental", "expected true or false, got a number"},
      {"{\"records\": [3], " + none + "}", "bad.json:1:14: records[0]", "a file path"},
      {R"({"schemes": [{"scheme": "maxwell", "branches": [3, 2.5]}]})", "bad.json:1:52: schemes[0].branches[1]",
       "integer number of Maxwell branches (such as 3), got 2.5"},
      {R"({"schemes": [{"scheme": "maxwell", "band_hz": [1, 2, 40]}]})", "bad.json:1:47: schemes[0].band_hz",
       "two numbers [lower, upper] in Hz, got a list of 3"},
      {R"({"schemes": [{"scheme": "maxwell", "band_hz": [[1, 40], [2]]}]})", "bad.json:1:57: schemes[0].band_hz[1]",
       "two numbers"},
      {R"({"schemes": [{"scheme": "maxwell", "frequency_hz": 3}]})", "bad.json:1:52: schemes[0].frequency_hz",
       "takes no frequency_hz (frequency_hz: mass, stiffness only)"},
      {R"({"schemes": ["mass"]})", "bad.json:1:14: schemes[0]", "expected a scheme such as"},
  };
  for (const Bad& b : bad) {
    CAPTURE(b.text);
    const std::string message = sweep_error(b.text);
    CAPTURE(message);
    CHECK(message.rfind(b.start, 0) == 0);
    CHECK(message.find(b.word) != std::string::npos);
  }
}

TEST_CASE("sweep file: value ranges are left to expand_sweep") {
  const SweepSpec spec = parse_sweep(R"({"schemes": [{"scheme": "maxwell", "zeta": 0.7, "branches": 9}]})", "r.json");
  CHECK(spec.schemes[0].zetas == std::vector<double>{0.7});
  CHECK_THROWS_AS(expand_sweep(spec, VaultStudyOptions{}), InvalidArgument);
}

}  // namespace test_sweep_file
