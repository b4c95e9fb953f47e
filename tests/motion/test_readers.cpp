// Readers of PEER .AT2, ESM ASCII and plain text: the two real PEER records of ../shared/data against the PGA their
// headers state (skipped when the folder is absent), small hand-made files whose samples are known, and every kind
// of malformed input, whose message must name the file and the line.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "blockdem/core/error.hpp"
#include "blockdem/core/units.hpp"
#include "blockdem/motion/integration.hpp"
#include "blockdem/motion/readers.hpp"
#include "blockdem/motion/writers.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_readers {
using namespace blockdem::motion;

namespace {

const std::filesystem::path data_dir = BLOCKDEM_TEST_DATA_DIR;
const std::filesystem::path shared_data = std::filesystem::path(BLOCKDEM_SHARED_DIR) / "data";

/// The message of the InputError (or InvalidArgument) that `parse` throws; empty if it throws nothing.
ReadOptions options(std::optional<AccelerationUnit> units, std::optional<double> dt = {},
                    RecordFormat format = RecordFormat::automatic) {
  ReadOptions o;
  o.units = units;
  o.dt = dt;
  o.format = format;
  return o;
}

template <class F>
std::string error_of(F&& parse) {
  try {
    parse();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("readers: the two real PEER records reproduce the PGA of their headers to 1e-4 g") {
  // Reference: the PGA= field of each file's header (the data provider's value), ../shared/data/README.md.
  if (!std::filesystem::exists(shared_data / "ImperialValley1979_ElCentroArray4_140.AT2")) {
    MESSAGE("skipped: " << shared_data.string() << " is absent");
    return;
  }
  struct Case {
    std::string file;
    double header_pga_g;
    double first_sample_g;
  };
  for (const Case& c : {Case{"ImperialValley1979_ElCentroArray4_140.AT2", 0.48431, -0.2964875e-3},
                       Case{"ImperialValley1979_ElCentroArray4_230.AT2", 0.37043, -0.3183268e-2}}) {
    CAPTURE(c.file);
    const auto record = read_record(shared_data / c.file);
    CHECK(record.source == "PEER NGA .AT2");
    CHECK(record.input_unit == AccelerationUnit::g);
    CHECK(record.size() == 7818);
    CHECK(record.dt == doctest::Approx(0.005).epsilon(1e-12));
    CHECK(record.acceleration.front() == doctest::Approx(c.first_sample_g * standard_gravity).epsilon(1e-12));
    REQUIRE(record.header_pga.has_value());
    CHECK(*record.header_pga / standard_gravity == doctest::Approx(c.header_pga_g).epsilon(1e-12));
    const double pga_g = peak_absolute(record.acceleration) / standard_gravity;
    CHECK(std::abs(pga_g - c.header_pga_g) <= 1e-4);
  }
}

TEST_CASE("readers: PEER .AT2 samples in g become m/s^2, five to a line, numbers without a leading zero") {
  const auto record = read_record(data_dir / "small.AT2");
  const double expected_g[] = {0.1, -0.3, 0.2, -0.1, 0.05, -0.025, 0.0};
  REQUIRE(record.size() == 7);
  for (std::size_t i = 0; i < 7; ++i) CHECK(record.acceleration[i] == doctest::Approx(expected_g[i] * 9.80665));
  CHECK(record.dt == 0.01);
  CHECK(record.duration() == doctest::Approx(0.06));
  CHECK(*record.header_pga == doctest::Approx(0.3 * 9.80665));
}

TEST_CASE("readers: the older PEER form of line 4 ('3000  0.0100  NPTS, DT') and cm/s^2 units") {
  const std::string text =
      "PEER STRONG MOTION DATABASE RECORD\nOLD FORMAT\nACCELERATION TIME HISTORY IN UNITS OF CM/SEC/SEC\n"
      "    4    0.0200    NPTS, DT\n 10.0 -20.0 30.0 -40.0\n";
  const auto record = parse_record(text, "old.AT2");
  REQUIRE(record.size() == 4);
  CHECK(record.dt == 0.02);
  CHECK(record.acceleration[3] == doctest::Approx(-0.40));
  CHECK(record.input_unit == AccelerationUnit::cm_s2);
}

TEST_CASE("readers: malformed PEER files name the file and the line") {
  const auto path = [](const char* name) { return (data_dir / name).string(); };
  CHECK(error_of([&] { read_record(path("short.AT2")); }) ==
        path("short.AT2") + ": header says NPTS=7 but 6 samples were read");
  CHECK(error_of([&] { read_record(path("text_in_data.AT2")); }) ==
        path("text_in_data.AT2") + ":6: expected a number, found 'abc'");
  CHECK(error_of([&] { read_record(path("missing_dt.AT2")); }).starts_with(path("missing_dt.AT2") +
                                                                            ":4: the header has no DT="));
  const std::string head = "PEER\nX\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= .01 SEC\n";
  CHECK(error_of([&] { parse_record(head + " .1 NaN .2\n", "nan.AT2"); }) == "nan.AT2:5: 'NaN' is not a finite number");
  CHECK(error_of([&] { parse_record(head + " .1 .2 .3 .4\n", "long.AT2"); }) ==
        "long.AT2: header says NPTS=3 but 4 samples were read");
  CHECK(error_of([&] { parse_record("PEER\nX\nACCELERATION\nNPTS= 2, DT= .01\n 1 2\n", "u.AT2"); })
            .starts_with("u.AT2:3: the header does not state the units"));
  CHECK(error_of([&] { parse_record("PEER\nX\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 2, DT= .01\n1 2\n", "v.VT2",
                                    options({}, {}, RecordFormat::peer_at2)); })
            .starts_with("v.VT2:3: this is a VELOCITY time series"));
  CHECK(error_of([&] { parse_record(head + " .1 .2 .3\n", "dt.AT2", options({}, 0.02)); })
            .find("dt = 0.02 s was given but dt.AT2 states a time step of 0.01 s") != std::string::npos);
  CHECK(error_of([&] { parse_record("PEER\nX\n", "tiny.AT2"); }).starts_with("tiny.AT2: a PEER .AT2 file starts with"));
  CHECK(error_of([&] { read_record(data_dir / "does_not_exist.AT2"); }).ends_with("does_not_exist.AT2: no such file"));
}

TEST_CASE("readers: explicit units win over the header") {
  const auto record = read_record(data_dir / "small.AT2", options(AccelerationUnit::m_s2));
  CHECK(record.acceleration[1] == doctest::Approx(-0.3));
  CHECK(record.input_unit == AccelerationUnit::m_s2);
}

TEST_CASE("readers: ESM/ITACA ASCII with its KEY: value header") {
  const auto record = read_record(data_dir / "small_esm.asc");
  CHECK(record.source == "ESM/ITACA ASCII");
  REQUIRE(record.size() == 6);
  CHECK(record.dt == 0.01);
  CHECK(record.acceleration[1] == doctest::Approx(-2.5));  // -250 cm/s^2
  CHECK(*record.header_pga == doctest::Approx(2.5));
  CHECK(record.input_unit == AccelerationUnit::cm_s2);

  const std::string head = "EVENT_NAME: X\nUNITS: cm/s^2\n";
  CHECK(error_of([&] { parse_record(head + "NDATA: 3\nSAMPLING_INTERVAL_S: 0.01\n1\n2\n", "a.asc"); }) ==
        "a.asc: header says NDATA=3 but 2 samples were read");
  CHECK(error_of([&] { parse_record(head + "NDATA: 2\n1\n2\n", "b.asc"); }) ==
        "b.asc: the header has no SAMPLING_INTERVAL_S");
  CHECK(error_of([&] { parse_record(head + "NDATA: 2\nSAMPLING_INTERVAL_S: 0.01\n1\nx2\n", "c.asc"); }) ==
        "c.asc:6: expected a number, found 'x2'");
  CHECK(error_of([&] { parse_record("NDATA: 2\nSAMPLING_INTERVAL_S: 0.01\nUNITS: furlong\n1\n2\n", "d.asc"); })
            .starts_with("d.asc:3: UNITS 'furlong' is not g, m/s^2 or cm/s^2"));
  CHECK(error_of([&] { parse_record("NDATA: 2\nSAMPLING_INTERVAL_S: -0.01\nUNITS: g\n1\n2\n", "e.asc"); })
            .starts_with("e.asc:2: SAMPLING_INTERVAL_S = -0.01 s; the time step must be > 0"));
}

TEST_CASE("readers: plain text with one column needs the time step, comments may state it and the units") {
  const auto record = read_record(data_dir / "one_column.txt", options(AccelerationUnit::g, 0.02));
  REQUIRE(record.size() == 5);
  CHECK(record.dt == 0.02);
  CHECK(record.acceleration[2] == doctest::Approx(-9.80665));
  CHECK(error_of([&] { read_record(data_dir / "one_column.txt", options(AccelerationUnit::g)); })
            .ends_with("one_column.txt: one column of samples and no time step; give it (--dt)"));
  CHECK(error_of([&] { read_record(data_dir / "one_column.txt", options({}, 0.01)); })
            .ends_with("one_column.txt: the file does not state its units; give them (--units g|m/s2|cm/s2)"));
  const auto commented = parse_record("# units: m/s2\n# dt: 0.005 s\n1.0\n2.0\n3.0\n", "c.txt");
  CHECK(commented.dt == 0.005);
  CHECK(commented.acceleration[2] == 3.0);
}

TEST_CASE("readers: plain text with two columns takes dt and the start time from the time column") {
  const auto record = parse_record("# units: cm/s2\n1.00, 0.5\n1.01, -1.5\n1.02, 2.0\n1.03, 0.0\n", "two.csv");
  CHECK(record.dt == doctest::Approx(0.01).epsilon(1e-12));
  CHECK(record.start_time == 1.0);
  CHECK(record.acceleration[1] == doctest::Approx(-0.015));

  // Times printed with 4 decimals at dt = 1/300 s step by 0.0033 or 0.0034: rounding, not a non-uniform column.
  std::ostringstream rounded;
  rounded << "# units: g\n";
  for (int i = 0; i < 50; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.4f %d\n", i / 300.0, i % 3);
    rounded << line;
  }
  const auto fine = parse_record(rounded.str(), "rounded.txt");
  CHECK(fine.dt == doctest::Approx(1.0 / 300.0).epsilon(1e-3));

  // Shortest-form times ("0", "0.01", "0.015") are exact: an integer "0" must not widen the tolerance.
  CHECK(error_of([&] { parse_record("# units: g\n0 1\n0.005 2\n0.01 3\n0.0165 4\n0.02 5\n", "g.txt"); }) ==
        "g.txt:5: time step 0.0065 differs from 0.005 (non-uniform time column)");

  const auto path = (data_dir / "nonuniform.txt").string();
  CHECK(error_of([&] { read_record(path); }) ==
        path + ":7: time step 0.01 differs from 0.005 (non-uniform time column)");
  CHECK(error_of([&] { read_record(data_dir / "nan.txt"); }).ends_with("nan.txt:4: 'NaN' is not a finite number"));
  CHECK(error_of([&] { parse_record("# units: g\n0 1\n0.01 2 3\n", "cols.txt"); }) ==
        "cols.txt:3: expected 2 columns, found 3");
  CHECK(error_of([&] { parse_record("# units: g\n0 1 2\n", "three.txt"); }) ==
        "three.txt:2: expected 1 column (acceleration) or 2 columns (time, acceleration), found 3");
  CHECK(error_of([&] { parse_record("# units: g\n0 1\n0.01 2\nabc def\n", "text.txt"); }) ==
        "text.txt:4: expected a number, found 'abc'");
  CHECK(error_of([&] { parse_record("# units: g\n0 1\n0 2\n", "dup.txt"); }) ==
        "dup.txt:3: time 0 does not increase (previous 0)");
  CHECK(error_of([&] { parse_record("# units: g\n0 1\n", "one.txt"); }) ==
        "one.txt: 1 sample was read; a record needs at least 2");
}

TEST_CASE("readers: a record written as CSV reads back with its unit, time step and start time") {
  Record record;
  record.name = "round trip";
  record.source = "test";
  record.dt = 0.004;
  record.start_time = 2.5;
  record.acceleration = {0.0, 1.25, -3.5, 2.0, 0.125, -0.5};
  std::ostringstream csv;
  write_record_csv(csv, record);
  CHECK(csv.str().find("time_s,acceleration_m_s2,velocity_m_s,displacement_m,arias_m_s\n") != std::string::npos);
  const auto back = parse_record(csv.str(), "round_trip.csv");
  CHECK(back.source == "plain text");
  CHECK(back.input_unit == AccelerationUnit::m_s2);
  CHECK(back.dt == doctest::Approx(0.004).epsilon(1e-9));
  CHECK(back.start_time == doctest::Approx(2.5));
  REQUIRE(back.size() == record.size());
  for (std::size_t i = 0; i < record.size(); ++i) CHECK(back.acceleration[i] == doctest::Approx(record.acceleration[i]));
}

TEST_CASE("readers: format detection and unit names") {
  CHECK(detect_format("anything", "x.at2") == RecordFormat::peer_at2);
  CHECK(detect_format("PEER NGA STRONG MOTION DATABASE RECORD\n", "x.txt") == RecordFormat::peer_at2);
  CHECK(detect_format("EVENT_NAME: A\nNDATA: 3\n", "x.txt") == RecordFormat::esm_ascii);
  CHECK(detect_format("0 1\n0.01 2\n", "x.txt") == RecordFormat::plain_text);
  CHECK(parse_acceleration_unit("G") == AccelerationUnit::g);
  CHECK(parse_acceleration_unit("cm/s^2") == AccelerationUnit::cm_s2);
  CHECK(parse_acceleration_unit("CM/SEC/SEC") == AccelerationUnit::cm_s2);
  CHECK(parse_acceleration_unit("gal") == AccelerationUnit::cm_s2);
  CHECK(parse_acceleration_unit("m/s2") == AccelerationUnit::m_s2);
  CHECK(parse_acceleration_unit("m/s") == std::nullopt);
  CHECK(parse_acceleration_unit("mm/s2") == std::nullopt);
  CHECK(to_m_s2(AccelerationUnit::g) == 9.80665);
}

}  // namespace test_readers
