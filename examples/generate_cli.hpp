#pragma once
// `blockdem generate KIND [options] > model.json`: model files of common masonry typologies (docs/generators.md), which
// `blockdem run` runs as they are: a running-bond wall with openings, lintels and return walls, the semicircular arch,
// the barrel vault and the paper's cross vault.

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "blockdem/analysis/arch.hpp"
#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/typologies.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/core/error.hpp"
#include "cli.hpp"

namespace blockdem::programs {

struct GenerateCommand {
  CLI::App* wall_app = nullptr;
  CLI::App* barrel_app = nullptr;
  CLI::App* arch_app = nullptr;
  CLI::App* vault_app = nullptr;
  analysis::WallStudyOptions wall;
  std::vector<std::string> openings;
  bool floor = false;
  std::string wall_unit = "brick", lintel_unit = "stone", vault_unit = "brick";
  analysis::BarrelVaultStudyOptions barrel;
  bool straight_joints = false;
  analysis::ArchOptions arch;
  analysis::VaultStudyOptions vault;
  bool pushover = false;

  static void add_joints(CLI::App& app, analysis::DryJointOptions& j) {
    app.add_option("--friction-angle", j.friction_angle_deg, "friction angle of the dry joints, degrees, (0, 89]")->capture_default_str();
    app.add_option("--normal-stiffness", j.normal_stiffness, "normal stiffness of the joints, Pa/m, [1e6, 1e15] (shear: half)")->capture_default_str();
  }

  void add_to(CLI::App& app) {
    app.require_subcommand(1);
    const char* pushover_help = "write the equivalent-static pushover (\"analysis\": \"pushover\") instead of the seismic levels";
    wall_app = app.add_subcommand("wall", "a running-bond wall on a foundation (out-of-plane study along y)");
    auto& w = wall.wall;
    wall_app->add_option("--length", w.length, "m along x, a multiple of half a unit")->capture_default_str();
    wall_app->add_option("--courses", w.courses, "number of courses")->capture_default_str();
    wall_app->add_option("--thickness", w.thickness, "m along y (one unit through)")->capture_default_str();
    wall_app->add_option("--unit-length", w.unit_length, "m, a unit with its joint, along x")->capture_default_str();
    wall_app->add_option("--unit-height", w.unit_height, "m, a course with its joint")->capture_default_str();
    wall_app->add_option("--opening", openings, "an opening X0,X1,SILL,HEAD: jambs in m from the left end, the lowest course cut "
                                                "away and the lintel's course (0-based); repeat for more")
        ->type_name("X0,X1,SILL,HEAD");
    wall_app->add_option("--lintel-bearing", w.lintel_bearing, "m each lintel runs past each jamb")->capture_default_str();
    wall_app->add_option("--return-length", w.return_length, "m: return walls at both ends along +y (0: none)")->capture_default_str();
    wall_app->add_flag("--floor", floor, "a thin floor slab instead of a foundation block");
    wall_app->add_option("--unit", wall_unit, "brick (1800 kg/m^3) or stone (2200)")->check(CLI::IsMember({"brick", "stone"}))->capture_default_str();
    wall_app->add_option("--lintel", lintel_unit, "brick or stone")->check(CLI::IsMember({"brick", "stone"}))->capture_default_str();
    add_joints(*wall_app, wall.joints);
    wall_app->add_flag("--pushover", pushover, pushover_help);

    barrel_app = app.add_subcommand("barrel-vault", "a semicircular barrel vault on two abutments (study across the span, along x)");
    auto& b = barrel.vault;
    barrel_app->add_option("--span", b.span, "m, clear (the intrados' diameter)")->capture_default_str();
    barrel_app->add_option("--thickness", b.thickness, "m, radial")->capture_default_str();
    barrel_app->add_option("--length", b.length, "m along y, a multiple of half a unit")->capture_default_str();
    barrel_app->add_option("--rings", b.rings, "voussoirs across the span")->capture_default_str();
    barrel_app->add_option("--unit-length", b.unit_length, "m along y")->capture_default_str();
    barrel_app->add_flag("--straight-joints", straight_joints, "rings not staggered (joints straight through along x)");
    barrel_app->add_option("--unit", vault_unit, "brick or stone")->check(CLI::IsMember({"brick", "stone"}))->capture_default_str();
    add_joints(*barrel_app, barrel.joints);
    barrel_app->add_flag("--pushover", pushover, pushover_help);

    arch_app = app.add_subcommand("arch", "the semicircular arch of `arch` on fixed springings: its pushover along x (always)");
    arch_app->add_option("--voussoirs", arch.voussoirs, "number of voussoirs")->capture_default_str();
    arch_app->add_option("--radius", arch.radius, "m, to the centreline")->capture_default_str();
    arch_app->add_option("--thickness-ratio", arch.thickness_ratio, "t/R")->capture_default_str();
    arch_app->add_option("--depth", arch.depth, "m")->capture_default_str();
    arch_app->add_option("--friction-angle", arch.friction_angle_deg, "degrees")->capture_default_str();

    vault_app = app.add_subcommand("cross-vault", "the paper's cross vault on the shake table (as `cross_vault model`)");
  }

  static analysis::MasonryUnit unit(const std::string& s) { return s == "stone" ? analysis::MasonryUnit::stone : analysis::MasonryUnit::brick; }

  static geometry::WallOpening opening(const std::string& text) {
    std::vector<double> v;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
      try {
        std::size_t used = 0;
        v.push_back(std::stod(item, &used));
        if (used != item.size()) throw std::invalid_argument(item);
      } catch (const std::exception&) {
        throw InvalidArgument("--opening '" + text + "': '" + item + "' is not a number (X0,X1,SILL,HEAD: m, m, course, course)");
      }
    }
    if (v.size() != 4) throw InvalidArgument("--opening '" + text + "': give four values X0,X1,SILL,HEAD (m, m, course, course)");
    for (int k : {2, 3})
      if (v[static_cast<std::size_t>(k)] != static_cast<int>(v[static_cast<std::size_t>(k)]))
        throw InvalidArgument("--opening '" + text + "': SILL and HEAD are course numbers (0, 1, ...)");
    return {v[0], v[1], static_cast<int>(v[2]), static_cast<int>(v[3])};
  }

  int run() {
    if (wall_app->parsed()) {
      for (const auto& o : openings) wall.wall.openings.push_back(opening(o));
      wall.wall.foundation = floor ? geometry::Foundation::floor : geometry::Foundation::block;
      wall.unit = unit(wall_unit);
      wall.lintel = unit(lintel_unit);
      const auto d = analysis::wall_description(wall);
      const auto p = analysis::wall_pushover(wall);
      analysis::write_model_file(std::cout, d, wall, pushover ? &p : nullptr);
    } else if (barrel_app->parsed()) {
      barrel.vault.running_bond = !straight_joints;
      barrel.unit = unit(vault_unit);
      const auto d = analysis::barrel_vault_description(barrel);
      const auto p = analysis::barrel_vault_pushover(barrel);
      analysis::write_model_file(std::cout, d, barrel, pushover ? &p : nullptr);
    } else if (arch_app->parsed()) {
      const auto d = analysis::arch_description(arch);
      analysis::StudyOptions o;
      o.axis = 'x';
      const auto p = analysis::arch_pushover(arch);  // on fixed springings: no table for a record to move
      analysis::write_model_file(std::cout, d, o, &p);
    } else {
      analysis::write_model_file(std::cout, analysis::vault_description(vault), vault);
    }
    return 0;
  }
};

}  // namespace blockdem::programs
