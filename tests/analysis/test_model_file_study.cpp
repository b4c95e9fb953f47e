// The vault as a model file: `cross_vault model` writes it (analysis/model_file_writer.hpp), the reader builds the
// same structure bit for bit, and the study of the file gives the histories of the vault study exactly; and the study
// of structures that are not the vault.

#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "../approx.hpp"
#include "../file_contents.hpp"

using namespace blockdem;

// Named: this file shares a unity translation unit (tests/CMakeLists.txt).
namespace test_model_file_study {

namespace {

/// The coarse vault of test_vault_study.cpp (178 blocks) under a short cut of the synthetic record.
analysis::VaultStudyOptions coarse_vault() {
  analysis::VaultStudyOptions o;
  o.vault.unit_height = 0.2;
  o.vault.unit_length = 0.7;
  o.progress = false;
  o.rest = 0.05;
  o.window_start = 2.0;
  o.window_end = 2.3;
  o.window_default = false;
  o.levels = {75};
  return o;
}

analysis::ModelFile vault_file(const analysis::VaultStudyOptions& o) {
  std::ostringstream text;
  analysis::write_model_file(text, analysis::vault_description(o), o);
  return analysis::parse_model_file(text.str(), "vault.json");
}

}  // namespace

TEST_CASE("model file: the vault written by cross_vault model reads back as the vault's structure, bit for bit") {
  for (const auto kinematics : {analysis::VaultKinematics::rigid, analysis::VaultKinematics::mixed}) {
    CAPTURE(analysis::name(kinematics));
    auto o = coarse_vault();
    o.kinematics = kinematics;
    o.max_edge = 0.6;
    o.steel_max_edge = 1.0;
    const auto expected = analysis::vault_structure(o);
    const auto file = vault_file(o);
    const auto& s = file.structure;
    const auto& a = s.model.bodies;
    const auto& b = expected.model.bodies;
    REQUIRE(a.size() == b.size());
    bool same = true;
    for (std::size_t i = 0; i < a.size(); ++i)
      same = same && a.position[i] == b.position[i] && a.mass[i] == b.mass[i] && a.principal_inertia[i] == b.principal_inertia[i] &&
             a.orientation[i].coeffs() == b.orientation[i].coeffs() && a.joint_tag[i] == b.joint_tag[i] && a.motion[i] == b.motion[i];
    CHECK(same);
    CHECK(s.model.deformable.nodes.position == expected.model.deformable.nodes.position);
    CHECK(s.model.deformable.nodes.mass == expected.model.deformable.nodes.mass);
    CHECK(s.model.deformable.tetrahedra.size() == expected.model.deformable.tetrahedra.size());
    CHECK(s.model.deformable.trusses.size() == expected.model.deformable.trusses.size());
    CHECK(s.groups() == expected.groups());
    for (std::size_t g = 0; g < s.laws.groups(); ++g)
      for (std::size_t h = 0; h < s.laws.groups(); ++h) {
        REQUIRE(s.laws.has(g, h) == expected.laws.has(g, h));
        if (s.laws.has(g, h)) CHECK(s.laws.law(g, h) == expected.laws.law(g, h));
      }
    REQUIRE(s.monitors.size() == expected.monitors.size());
    for (std::size_t p = 0; p < s.monitors.size(); ++p) {
      CHECK(s.monitors[p].name == expected.monitors[p].name);
      CHECK(s.monitors[p].block == expected.monitors[p].block);
      CHECK(s.monitors[p].position == expected.monitors[p].position);
    }
    CHECK(s.table == expected.table);
    // The study's options as the vault's.
    CHECK(file.study.levels == o.levels);
    CHECK(file.study.record_level == o.record_level);
    CHECK(file.study.window_end == o.window_end);
    CHECK(file.study.contacts == o.contacts);
    CHECK(file.study.baseline == o.baseline);
  }
}

TEST_CASE("model file: the vault's model file through the generic study gives the vault study's histories exactly") {
  const auto base = std::filesystem::temp_directory_path() / "blockdem_vault_model_file";
  auto o = coarse_vault();
  o.out_dir = (base / "vault").string();
  const auto direct = analysis::run_vault_study(o);
  auto file = vault_file(o);
  file.study.out_dir = (base / "file").string();
  file.study.progress = false;
  const auto from_file = analysis::run_study(file.structure, file.study);
  REQUIRE(direct.levels.size() == 1);
  REQUIRE(from_file.levels.size() == 1);
  CHECK(from_file.levels[0].steps == direct.levels[0].steps);
  CHECK(from_file.timestep.dt == direct.timestep.dt);
  CHECK(from_file.settling.steps == direct.settling.steps);
  const std::string history = test::file_contents(base / "vault" / "history_75.csv");
  CHECK(history.size() > 1000);
  CHECK(test::file_contents(base / "file" / "history_75.csv") == history);  // every digit of every sample
  CHECK(test::file_contents(base / "file" / "contacts_75.csv") == test::file_contents(base / "vault" / "contacts_75.csv"));
  std::filesystem::remove_all(base);
}

}  // namespace test_model_file_study
