// The vault as a model file: `cross_vault model` writes it (analysis/model_file_writer.hpp), the reader builds the
// same structure bit for bit, and the study of the file gives the histories of the vault study exactly; and the study
// of structures that are not the vault.

#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/geometry/mass_properties.hpp"
#include "blockdem/geometry/polyhedron_check.hpp"
#include "blockdem/io/threedec_geometry.hpp"
#include "blockdem/model/contact_detection.hpp"
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

TEST_CASE("model file: the vault written to a 3DEC deck and read back is the same model (blocks, volumes, contact points)") {
  const analysis::VaultStudyOptions o;  // the paper's vault, rigid blocks
  const auto d = analysis::vault_description(o);
  std::vector<geometry::ImportedBlock> blocks;
  for (const auto& b : d.blocks) blocks.push_back(geometry::imported_block(b.shape, b.name, d.laws.name(b.group)));
  std::ostringstream deck;
  io::write_threedec_deck(deck, blocks, "LNEC cross vault");
  const auto back = io::read_threedec_deck(deck.str(), "vault.3ddat");
  REQUIRE(back.blocks.size() == d.blocks.size());
  auto e = d;
  double worst_volume = 0, worst_centroid = 0;
  std::vector<geometry::BlockIssue> issues;
  for (std::size_t i = 0; i < d.blocks.size(); ++i) {
    const auto shape = geometry::check_polyhedron(back.blocks[i], issues);
    REQUIRE(shape);
    CHECK(back.blocks[i].group == d.laws.name(d.blocks[i].group));
    const auto a = geometry::mass_properties(d.blocks[i].shape), b = geometry::mass_properties(*shape);
    worst_volume = std::max(worst_volume, std::abs(a.volume - b.volume) / a.volume);
    worst_centroid = std::max(worst_centroid, (a.centroid - b.centroid).norm());
    e.blocks[i].shape = *shape;
  }
  CHECK(analysis::count_issues(issues, geometry::BlockIssue::Severity::error) == 0);
  CHECK(worst_volume < 1e-9);
  CHECK(worst_centroid < 1e-9);
  auto contacts = [&](const analysis::ModelDescription& m) {
    std::ostringstream text;
    analysis::write_model_file(text, m, o);
    const auto file = analysis::parse_model_file(text.str(), "vault.json");
    auto settings = file.structure.contacts;
    settings.kinds = file.study.contacts;
    file.structure.laws.fill(settings);
    return model::detect_contacts(file.structure.model.bodies, settings);
  };
  const auto ca = contacts(d), cb = contacts(e);
  CHECK(ca.size() > 10000);
  REQUIRE(ca.size() == cb.size());
  double area_a = 0, area_b = 0;
  for (std::size_t k = 0; k < ca.size(); ++k) {
    area_a += ca[k].area;
    area_b += cb[k].area;
  }
  CHECK(std::abs(area_a - area_b) <= 1e-9 * area_a);
}

TEST_CASE("model file: the vault written by cross_vault model reads back as the vault's structure, bit for bit") {
  for (const auto kinematics : {analysis::VaultKinematics::rigid, analysis::VaultKinematics::mixed}) {
    CAPTURE(analysis::name(kinematics));
    auto o = coarse_vault();
    o.kinematics = kinematics;
    o.max_edge = 0.6;
    o.steel_max_edge = 1.0;
    o.settling = kinematics == analysis::VaultKinematics::rigid ? analysis::Settling::inertial : analysis::Settling::local;
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
    CHECK(file.study.settling == o.settling);
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
