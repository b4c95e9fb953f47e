// The checkpoints of the cross-vault study (analysis/vault_checkpoint.hpp): a run stopped in the middle of a level
// and resumed writes, bit for bit, what the run not stopped writes; a checkpoint that is truncated, corrupted or of
// other options is refused with a message naming the file, and nothing of the run it belongs to is touched.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "blockdem/analysis/vault_study.hpp"
#include "../file_contents.hpp"
#include "../threads.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_vault_checkpoint {

namespace {

using test::OneThread;

/// The coarse vault (178 blocks), two short levels, snapshots: a few seconds per run.
analysis::VaultStudyOptions two_levels(const std::filesystem::path& dir) {
  analysis::VaultStudyOptions o;
  o.vault.unit_height = 0.2;
  o.vault.unit_length = 0.7;
  o.progress = false;
  o.rest = 0.02;
  o.levels = {25, 50};
  o.window_start = 2.0;
  o.window_end = 2.15;
  o.history_dt = 0.002;
  o.snapshots_every = 0.05;
  o.out_dir = dir.string();
  return o;
}

std::string refusal(const analysis::VaultStudyOptions& o) {
  try {
    analysis::run_vault_study(o);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("vault study: a run stopped inside a level and resumed from its checkpoint is bitwise the run not stopped") {
  const OneThread one_thread;
  const auto base = std::filesystem::temp_directory_path() / "blockdem_vault_resume";
  std::filesystem::remove_all(base);
  const auto whole = analysis::run_vault_study(two_levels(base / "whole"));
  REQUIRE(whole.levels.size() == 2);
  REQUIRE_FALSE(whole.interrupted);
  const long long first_level = whole.levels[0].steps, all = first_level + whole.levels[1].steps;

  // Stopped twice (inside level 25, then inside level 50), resumed each time.
  auto o = two_levels(base / "split");
  o.stop_after_steps = first_level / 2;
  const auto part1 = analysis::run_vault_study(o);
  CHECK(part1.interrupted);
  CHECK(part1.levels.size() == 1);  // the level in progress, as far as it went
  CHECK(test::file_contents(base / "split" / "report.json").find("\"complete\": false") != std::string::npos);
  // The history of a level not finished is not under its own name, which only a whole level's history takes.
  CHECK_FALSE(std::filesystem::exists(base / "split" / "history_25.csv"));
  CHECK(std::filesystem::exists(base / "split" / "history_25.csv.part"));
  o.resume = (base / "split" / analysis::study_checkpoint_file).string();
  o.stop_after_steps = first_level + (all - first_level) / 3;
  const auto part2 = analysis::run_vault_study(o);
  CHECK(part2.interrupted);
  o.stop_after_steps = 0;
  const auto resumed = analysis::run_vault_study(o);
  CHECK_FALSE(resumed.interrupted);
  REQUIRE(resumed.levels.size() == 2);

  for (const char* name : {"history_25.csv", "history_50.csv", "contacts_25.csv", "contacts_50.csv", "damage_50.vtu",
                           "snapshots.pvd", "snapshots/level50_1.vtu"}) {
    const auto a = test::file_contents(base / "whole" / name), b = test::file_contents(base / "split" / name);
    CHECK_MESSAGE(!a.empty(), name);
    CHECK_MESSAGE(a == b, name);
  }
  for (std::size_t l = 0; l < 2; ++l) {
    CHECK(resumed.levels[l].steps == whole.levels[l].steps);
    CHECK(resumed.levels[l].energy.kinetic == whole.levels[l].energy.kinetic);
    CHECK(resumed.levels[l].energy.slip == whole.levels[l].energy.slip);
    for (std::size_t c = 0; c < whole.levels[l].peaks.size(); ++c) {
      CHECK(resumed.levels[l].peaks[c].max == whole.levels[l].peaks[c].max);
      CHECK(resumed.levels[l].peaks[c].min == whole.levels[l].peaks[c].min);
    }
  }
  CHECK(resumed.settling.steps == whole.settling.steps);
  CHECK(test::file_contents(base / "split" / "report.json").find("\"complete\": true") != std::string::npos);
  for (const auto& entry : std::filesystem::recursive_directory_iterator(base / "split"))
    CHECK_MESSAGE(entry.path().extension() != ".part", entry.path().string());
  std::filesystem::remove_all(base);
}

TEST_CASE("vault study: a truncated, corrupted or foreign checkpoint is refused, naming the file") {
  const OneThread one_thread;
  const auto base = std::filesystem::temp_directory_path() / "blockdem_vault_bad_checkpoint";
  std::filesystem::remove_all(base);
  auto o = two_levels(base / "run");
  o.levels = {25};
  o.window_end = 2.05;
  analysis::run_vault_study(o);
  const auto checkpoint = base / "run" / analysis::study_checkpoint_file;
  const std::string good = test::file_contents(checkpoint);
  REQUIRE(good.size() > 1000);
  const std::string report = test::file_contents(base / "run" / "report.json");

  auto with_file = [&](const std::string& bytes, auto change) {
    const auto path = base / "other.bin";
    std::ofstream(path, std::ios::binary) << bytes;
    auto bad = o;
    bad.resume = path.string();
    change(bad);
    return refusal(bad);
  };
  const auto none = [](auto&) {};
  const auto truncated = with_file(good.substr(0, good.size() / 2), none);
  CHECK(truncated.find("other.bin") != std::string::npos);
  CHECK(truncated.find("truncated") != std::string::npos);
  std::string flipped = good;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  CHECK(with_file(flipped, none).find("corrupted payload (checksum mismatch") != std::string::npos);
  CHECK(with_file("not a checkpoint at all", none).find("not a blockdem checkpoint") != std::string::npos);
  CHECK(with_file(good, [](auto& b) { b.zeta = 0.05; }).find("another model or other options") != std::string::npos);
  CHECK(with_file(good, [](auto& b) { b.vault.unit_length = 0.6; }).find("another model or other options") != std::string::npos);
  auto missing = o;
  missing.resume = (base / "none.bin").string();
  CHECK(refusal(missing).find("none.bin") != std::string::npos);
  // The run the checkpoint belongs to is untouched by the refusals.
  CHECK(test::file_contents(base / "run" / "report.json") == report);
  CHECK(test::file_contents(checkpoint) == good);
  // The good checkpoint (after the last level) resumes to the same report, with nothing left to run.
  auto again = o;
  again.resume = checkpoint.string();
  const auto r = analysis::run_vault_study(again);
  CHECK(r.levels.size() == 1);
  CHECK_FALSE(r.interrupted);
  std::filesystem::remove_all(base);
}

}  // namespace test_vault_checkpoint
