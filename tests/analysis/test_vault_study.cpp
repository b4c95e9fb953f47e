// The cross-vault study driver (analysis/vault_study.hpp) on a coarse vault (bricks 0.2 x 0.7 m: 178 blocks, about
// 1,500 contact points) so that each run takes seconds: rest under zero input, the table following the input, the
// energy balance of a level per damping scheme, thread independence, and the errors of bad options.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/motion/synthetic.hpp"
#include "../approx.hpp"
#include "../file_contents.hpp"
#include "../threads.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_vault_study {

namespace {

using test::OneThread;

analysis::VaultStudyOptions coarse_study() {
  analysis::VaultStudyOptions o;
  o.vault.unit_height = 0.2;
  o.vault.unit_length = 0.7;
  o.progress = false;
  o.rest = 0;
  return o;
}

motion::Record constant_record(double value, double duration, double dt = 0.01);

/// The coarse vault under 2 s of zero input.
analysis::VaultStudyOptions zero_input_study() {
  auto o = coarse_study();
  o.record = constant_record(0.0, 2.0);
  o.record_level = 100;
  o.levels = {100};
  o.window_start = 0;
  o.window_end = 2.0;
  o.baseline = "none";
  return o;
}

motion::Record constant_record(double value, double duration, double dt) {
  motion::Record r;
  r.name = "test record";
  r.dt = dt;
  r.acceleration.assign(static_cast<std::size_t>(std::llround(duration / dt)) + 1, value);
  return r;
}

double peak_abs(const analysis::LevelResult& level, const std::string& channel) {
  for (const auto& p : level.peaks)
    if (p.name == channel) return std::max(std::abs(p.max), std::abs(p.min));
  FAIL("no channel " << channel);
  return 0;
}

}  // namespace

TEST_CASE("vault study: under zero input the settled vault stays at rest (every monitor point within 1e-5 m over 2 s)") {
  const OneThread one_thread;
  const auto r = analysis::run_vault_study(zero_input_study());
  REQUIRE(r.settling.converged);
  REQUIRE(r.levels.size() == 1);
  CHECK(r.levels[0].simulated == doctest::Approx(2.0).epsilon(1e-3));
  double largest = 0;
  for (const auto& p : r.levels[0].peaks)
    if (p.name.find("_u") != std::string::npos) largest = std::max({largest, std::abs(p.max), std::abs(p.min)});
  MESSAGE("zero input: largest monitor displacement " << largest << " m over 2 s; settled in " << r.settling.steps << " steps");
  CHECK(largest < 1e-5);
  CHECK(r.settling.damaged_joints == 0);
  CHECK(r.levels[0].damage.total.damaged == 0);
  CHECK(r.levels[0].damage.loose_blocks == 0);  // every block of the vault touches another
}

TEST_CASE("vault study: under zero input the settled mixed and deformable vaults stay at rest (within 1e-5 m over 0.5 s)") {
  // One tetrahedron size of 1 m (each brick a few elements), partial density scaling to 5e-6 s (the deformable steel
  // frame's thin webs need most of the added mass: mass changes how fast a vault moves, not whether it stays at rest)
  // and 0.5 s (100,000 steps; over 2 s both drifted 2-3e-8 m) keep this to 20 s per variant. The monitor points
  // follow their nearest nodes.
  const OneThread one_thread;
  for (const auto kinematics : {analysis::VaultKinematics::mixed, analysis::VaultKinematics::deformable}) {
    const std::string variant = analysis::name(kinematics);
    CAPTURE(variant);
    auto o = zero_input_study();
    o.record = constant_record(0.0, 0.5);
    o.window_end = 0.5;
    o.kinematics = kinematics;
    o.max_edge = o.steel_max_edge = 1.0;
    o.target_dt = 5e-6;
    o.max_mass_increase_percent = 200;
    const auto r = analysis::run_vault_study(o);
    REQUIRE(r.settling.converged);
    REQUIRE(r.levels.size() == 1);
    CHECK(r.model.nodes > 1000);
    CHECK(r.model.deformable_blocks + (kinematics == analysis::VaultKinematics::mixed ? 6u : 1u) == r.model.blocks);
    double largest = 0;
    for (const auto& p : r.levels[0].peaks)
      if (p.name.find("_u") != std::string::npos) largest = std::max({largest, std::abs(p.max), std::abs(p.min)});
    MESSAGE(variant << ": " << r.model.nodes << " nodes; zero input: largest monitor displacement " << largest
                                       << " m over 0.5 s; settled in " << r.settling.steps << " steps; damaged joints "
                                       << r.levels[0].damage.total.damaged << "; energy balance error " << r.levels[0].energy.balance_error);
    CHECK(largest < 1e-5);
    CHECK(r.settling.damaged_joints == 0);
    CHECK(r.levels[0].damage.total.damaged == 0);
  }
}

TEST_CASE("vault study: the table follows the scaled input, and the acceleration on the slab is the input's") {
  const OneThread one_thread;
  // ACC2 sits on the slab (the base block), so its displacement relative to the table is zero and its acceleration,
  // from centred differences of the recorded velocity, is the input acceleration scaled by level / record level.
  auto o = coarse_study();
  o.record = constant_record(1.0, 0.5);
  o.record_level = 200;  // the file holds 200 % of the original record ...
  o.levels = {50};       // ... so this level applies a quarter of it: 0.25 m/s^2
  o.window_start = 0;
  o.window_end = 0.5;
  o.baseline = "none";
  o.damping = analysis::DampingScheme::mass;
  const auto r = analysis::run_vault_study(o);
  REQUIRE(r.levels.size() == 1);
  const auto& L = r.levels[0];
  double ay_max = 0, ay_min = 0;
  for (const auto& p : L.peaks)
    if (p.name == "ACC2_ay") ay_max = p.max, ay_min = p.min;
  CHECK(ay_max == doctest::Approx(0.25).epsilon(0.02));
  CHECK(ay_min > 0.2);  // one-sided differences at the ends see a quarter of a step of rest at most
  CHECK(peak_abs(L, "ACC2_uy") < 1e-12);
  CHECK(peak_abs(L, "ACC2_ax") < 1e-9);
}

TEST_CASE("vault study: the energy balance of a level closes within 1 % for noDamp, MassProp and Maxwell") {
  // noDamp at 75 % over 2 s of the strong part is the hardest case: about 690 damaged contact points and 280 where
  // blocks that had no contact touch (sliding and re-contacting), nothing viscous to hide an error. The energy that re-detection stores in new CPs
  // (EnergyReport::contact_update) is a term of its own: a few J, about 1 % of the work in.
  const OneThread one_thread;
  for (const auto scheme : {analysis::DampingScheme::none, analysis::DampingScheme::mass, analysis::DampingScheme::maxwell}) {
    auto o = coarse_study();
    const bool damaging = scheme == analysis::DampingScheme::none;
    o.levels = {damaging ? 75.0 : 50.0};
    o.window_start = 2.0;  // the strong part of the synthetic AQA75 stand-in
    o.window_end = damaging ? 4.0 : 3.0;
    o.damping = scheme;
    const auto r = analysis::run_vault_study(o);
    REQUIRE(r.levels.size() == 1);
    const auto& e = r.levels[0].energy;
    MESSAGE(std::string(analysis::name(scheme)) << ": balance error " << e.balance_error << ", base work " << e.base_work << " J, viscous "
                                   << e.viscous << " J, hysteretic " << e.slip << " J, kinetic " << e.kinetic << " J, contact updates "
                                   << e.contact_update << " J; damaged contact points " << r.levels[0].damage.total.damaged
                                   << ", new ones " << r.levels[0].damage.total.new_contacts);
    CHECK(e.balance_error < 0.01);
    if (damaging) CHECK(r.levels[0].damage.total.damaged > 200);
    if (damaging) CHECK(r.levels[0].damage.total.new_contacts > 200);
    CHECK(std::abs(e.base_work) > 0);
    if (scheme == analysis::DampingScheme::none) CHECK(e.viscous == doctest::Approx(0.0));
    else CHECK(e.viscous > 0);
  }
}

TEST_CASE("vault study: one and two threads write the same histories, bit for bit") {
  const auto base = std::filesystem::temp_directory_path() / "blockdem_vault_threads";
  int run = 0;
  const auto different = test::differences_between_one_and_two_threads([&] {
    auto o = coarse_study();
    o.levels = {75};
    o.window_start = 2.0;
    o.window_end = 2.3;
    o.out_dir = (base / std::to_string(run++)).string();
    analysis::run_vault_study(o);
    const auto text = test::file_contents(std::filesystem::path(o.out_dir) / "history_75.csv");
    return std::vector<double>(text.begin(), text.end());
  });
  CHECK(different == 0);
  std::filesystem::remove_all(base);
}

TEST_CASE("vault study: the outputs of a level are complete files") {
  const OneThread one_thread;
  const auto dir = std::filesystem::temp_directory_path() / "blockdem_vault_outputs";
  std::filesystem::remove_all(dir);
  auto o = coarse_study();
  o.levels = {25};
  o.window_start = 2.0;
  o.window_end = 2.1;
  o.out_dir = dir.string();
  o.snapshots_every = 0.05;
  const auto r = analysis::run_vault_study(o);
  for (const char* name : {"report.json", "history_25.csv", "damage_25.vtu", "contacts_25.vtu", "contacts_25.csv", "snapshots.pvd"})
    CHECK_MESSAGE(std::filesystem::exists(dir / name), name);
  CHECK_FALSE(std::filesystem::exists(dir / "report.json.part"));
  const auto report = test::file_contents(dir / "report.json");
  CHECK(report.find("\"complete\": true") != std::string::npos);
  CHECK(report.find("NOT the AQA recording") != std::string::npos);
  const auto history = test::file_contents(dir / "history_25.csv");
  CHECK(history.rfind("time,OC1_ux,OC1_uy,OC1_uz,OC1_ax,OC1_ay,OC1_az,", 0) == 0);
  // 0.1 s at 0.005 s: 21 rows and the header, every row with 1 + 9 x 6 fields.
  CHECK(std::count(history.begin(), history.end(), '\n') == 22);
  CHECK(test::file_contents(dir / "damage_25.vtu").find("</VTKFile>") != std::string::npos);
  CHECK(r.timestep.dt > r.timestep.critical_unscaled * 0.5);  // density scaling raised the timestep, or left it
  std::filesystem::remove_all(dir);
}

TEST_CASE("vault study: bad options name the option and the allowed range") {
  auto message = [](auto change) {
    auto o = coarse_study();
    change(o);
    try {
      analysis::run_vault_study(o);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message([](auto& o) { o.levels = {25, 0}; }).find("--levels: each level must be in (0, 1000] %, got 0") != std::string::npos);
  CHECK(message([](auto& o) { o.levels = {1001}; }).find("(0, 1000] %") != std::string::npos);
  CHECK(message([](auto& o) { o.record_level = 0; }).find("--record-level must be in (0, 1000] %") != std::string::npos);
  CHECK(message([](auto& o) { o.window_start = 20, o.window_end = 40; }).find("lies outside the record") != std::string::npos);
  CHECK(message([](auto& o) { o.branches = 5; }).find("--branches must be in 1..4") != std::string::npos);
  CHECK(message([](auto& o) { o.target_dt = 5e-4; }).find("more mass by density scaling, above --max-mass-increase") != std::string::npos);
  CHECK(message([](auto& o) { o.record_path = "/nonexistent/record.at2"; }).find("/nonexistent/record.at2") != std::string::npos);
  CHECK(message([](auto& o) { o.out_dir = "/proc/blockdem_cannot_write_here"; }).find("--out") != std::string::npos);
}

TEST_CASE("free decay: frequency and damping ratio of a damped sinusoid, and of the first of two modes") {
  // x = exp(-zeta w t) sin(w_d t) with w_d = w sqrt(1 - zeta^2): the decrement gives zeta exactly at the peaks.
  const double dt = 2e-4, f = 16, zeta = 0.02, w = 2 * pi * f, wd = w * std::sqrt(1 - zeta * zeta);
  std::vector<double> t, one, two;
  for (int i = 0; i < 5000; ++i) {
    t.push_back(dt * i);
    one.push_back(std::exp(-zeta * w * t.back()) * std::sin(wd * t.back()));
    // a second mode at 41 Hz, undamped, as large as the first at the start: the band-pass must leave the first
    // mode's decay (its spectral peak is half the second's over the 1 s)
    two.push_back(one.back() + std::sin(2 * pi * 41 * t.back()));
  }
  const auto d = analysis::analyse_free_decay(t, one);
  CHECK(d.frequency_hz == doctest::Approx(wd / (2 * pi)).epsilon(1e-3));
  CHECK(d.damping_ratio == doctest::Approx(zeta).epsilon(0.02));
  const auto m = analysis::analyse_first_mode(two, dt);
  CHECK(m.frequency_hz == doctest::Approx(wd / (2 * pi)).epsilon(5e-3));
  CHECK(m.damping_ratio == doctest::Approx(zeta).epsilon(0.1));
  CHECK_THROWS_AS(analysis::analyse_free_decay(std::vector<double>{0, 1, 2, 3}, std::vector<double>{1, 1, 1, 1}), InvalidArgument);
}

TEST_CASE("vault study: the settled vault in free decay has the damping ratio of its scheme at its first frequency") {
  const OneThread one_thread;
  // Eq. 10 (MassProp: alpha / 2 omega) and eq. 19 (Maxwell: Im M_T / 2 Re M_T) at the measured frequency, within 15 %;
  // noDamp below 0.5 % while the joints stay elastic (the pulse moves the crown by micrometres).
  for (const auto scheme : {analysis::DampingScheme::none, analysis::DampingScheme::mass, analysis::DampingScheme::maxwell}) {
    auto o = coarse_study();
    o.damping = scheme;
    const auto f = analysis::measure_free_vibration(o);
    REQUIRE_MESSAGE(f.measured, f.note);
    MESSAGE(std::string(analysis::name(scheme)) << ": " << f.decay.frequency_hz << " Hz, zeta " << f.decay.damping_ratio << " (scheme: "
                                   << f.expected_damping_ratio << ") over " << f.decay.cycles << " cycles");
    CHECK(f.decay.frequency_hz > 5);
    CHECK(f.decay.frequency_hz < 60);
    if (scheme == analysis::DampingScheme::none) {
      CHECK(std::abs(f.decay.damping_ratio) < 0.005);
    } else {
      CHECK(f.expected_damping_ratio > 0.005);
      CHECK(f.decay.damping_ratio == doctest::Approx(f.expected_damping_ratio).epsilon(0.15));
    }
  }
}

TEST_CASE("vault study: with general contacts the vault runs the paper's levels close to the face-to-face model") {
  // General contacts keep every face-to-face CP and add those of the infill slivers that stand on an edge on the
  // anchors (16 CPs). Blocks that meet along a line only get none: at the groins, where four joints cross, their
  // face-to-face plane is the common plane; at the crown line, where eight blocks meet, the block between them
  // meets both face to face. The issue asked for OC1 within 1 %; measured on 2 s of the strong part, 25, 50 and 75 %
  // in turn: -0.01, -0.19 and -0.11 % (+1.3, -7.6 and -2.3 % when those lines had edge CPs; the paper's vault: -0.1,
  // -0.1 and +0.4 %, docs/vault-study.md). Checked here: within 1 %, and more contact points.
  const OneThread one_thread;
  std::vector<double> peaks[2];
  std::size_t points[2] = {0, 0};
  for (const auto kinds : {model::ContactKinds::faces, model::ContactKinds::general}) {
    auto o = coarse_study();
    o.contacts = kinds;
    o.levels = {25, 50, 75};
    o.window_start = 2.0;
    o.window_end = 4.0;
    const auto r = analysis::run_vault_study(o);
    REQUIRE(r.levels.size() == 3);
    const auto k = static_cast<std::size_t>(kinds == model::ContactKinds::general);
    for (const auto& L : r.levels) peaks[k].push_back(peak_abs(L, "OC1_uy"));
    points[k] = r.model.contact_points;
  }
  CHECK(points[1] > points[0]);
  for (std::size_t level = 0; level < 3; ++level) {
    MESSAGE("level " << level << ": peak OC1_uy faces " << peaks[0][level] << " m, general " << peaks[1][level] << " m");
    CHECK(peaks[0][level] > 1e-4);
    CHECK(peaks[1][level] == test::approx(peaks[0][level]).epsilon(0.01));
  }
}

TEST_CASE("vault study: a short collapse, shaken at 500 % with general contacts, ends the level within the energy books") {
  // The collapse path (hundreds of re-detections of blocks in flight, edge and vertex contacts, CPs dropped and
  // added) in a run short enough for the sanitizer stage, which leaves out the longer test below: the coarse vault at
  // 500 % of the stand-in from 2 s. Measured: 0.44 s into the level ACC12 is 0.303 m from where it settled, 1,001
  // detections in 18,828 steps, energy balance 1.1e-3 (6 s in Release on two threads).
  const OneThread one_thread;
  const auto dir = std::filesystem::temp_directory_path() / "blockdem_vault_short_collapse";
  std::filesystem::remove_all(dir);
  auto o = coarse_study();
  o.contacts = model::ContactKinds::general;
  o.levels = {500};
  o.window_start = 2.0;
  o.window_end = 4.0;
  o.out_dir = dir.string();
  const auto r = analysis::run_vault_study(o);
  REQUIRE(r.levels.size() == 1);
  const auto& fell = r.levels[0];
  MESSAGE("collapse " << fell.collapse.time << " s into 500 %: " << fell.collapse.point << " moved " << fell.collapse.displacement
                      << " m; " << fell.detections << " detections; energy balance error " << fell.energy.balance_error);
  REQUIRE(fell.collapse.collapsed);
  CHECK(fell.collapse.time < 1.0);
  CHECK(fell.collapse.displacement > o.collapse_displacement);
  CHECK(fell.detections > 300);
  CHECK(fell.energy.balance_error < 0.01);
  std::filesystem::remove_all(dir);
}

TEST_CASE("vault study: run on past the paper's levels with general contacts, the vault collapses and the study ends there") {
  // The coarse vault at 75 % and then 150 % of the stand-in record (2-6 s): at 150 % the webs lose the springings
  // and fall (measured: 1.9 s into the level OC3 is 0.30 m from where it settled, 0.27 m lower, 663 joints damaged,
  // energy balance 0.17 %; other roundings give other times and points, a collapse being chaotic). The level ends
  // at the collapse, as a result, and 300 % is not run.
  const OneThread one_thread;
  const auto dir = std::filesystem::temp_directory_path() / "blockdem_vault_collapse";
  std::filesystem::remove_all(dir);
  auto o = coarse_study();
  o.contacts = model::ContactKinds::general;
  o.levels = {75, 150, 300};
  o.window_start = 2.0;
  o.window_end = 6.0;
  o.out_dir = dir.string();
  const auto r = analysis::run_vault_study(o);
  REQUIRE(r.levels.size() == 2);
  CHECK_FALSE(r.interrupted);
  const auto& survived = r.levels[0];
  CHECK_FALSE(survived.collapse.collapsed);
  CHECK(survived.simulated == test::approx(survived.duration).epsilon(1e-4));
  const auto& fell = r.levels[1];
  REQUIRE(fell.collapse.collapsed);
  CHECK_FALSE(fell.interrupted);
  MESSAGE("collapse " << fell.collapse.time << " s into 150 %: " << fell.collapse.point << " moved " << fell.collapse.displacement
                      << " m; OC1 residual z " << fell.residual_displacement[0].z() << " m; damaged joints " << fell.damage.total.damaged
                      << "; energy balance error " << fell.energy.balance_error);
  CHECK(fell.collapse.displacement > o.collapse_displacement);
  CHECK(fell.collapse.time > 0.5);
  CHECK(fell.simulated == test::approx(fell.collapse.time).epsilon(1e-3));
  CHECK(fell.simulated < fell.duration - 1.0);
  CHECK(fell.residual_displacement[0].z() < -0.05);  // the crown has come down
  CHECK(fell.damage.total.damaged > 10 * std::max<long long>(survived.damage.total.damaged, 1));
  CHECK(fell.energy.balance_error < 0.01);  // the fall is still within the energy books
  const auto report = test::file_contents(dir / "report.json");
  CHECK(report.find("\"collapsed\": true") != std::string::npos);
  CHECK(report.find("\"monitor_point\": \"" + fell.collapse.point + "\"") != std::string::npos);
  CHECK(std::filesystem::exists(dir / "damage_150.vtu"));
  CHECK_FALSE(std::filesystem::exists(dir / "history_300.csv"));
  // Resumed from the checkpoint written at the collapse, there is nothing left to run.
  o.resume = (dir / analysis::study_checkpoint_file).string();
  const auto resumed = analysis::run_vault_study(o);
  CHECK(resumed.levels.size() == 2);
  CHECK(resumed.levels.back().collapse.collapsed);
}

}  // namespace test_vault_study
