// cross_vault: the full-scale brick cross vault of the LNEC shake-table test (paper Sect. 2 and 3.2): builds the
// blocks of every component, checks the assembly (validity, overlaps, contacts, masses against analytical volumes)
// and writes it out. The dynamic analysis comes in a later issue; for now --geometry-only is required.
//
//   cross_vault --geometry-only [--vtk vault.vtu] [--contacts-vtk cps.vtu] [--json] [--profile segmental|elliptical] [--span 2.9]
//               [--rise 1.2] [--thickness 0.12] [--plan 3.5] [...]
//
// Exit status: 0 on success, 1 if the assembly check fails, 2 on bad input.

#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "blockdem/io/json.hpp"
#include "blockdem/io/vtk.hpp"
#include "blockdem/models/cross_vault.hpp"
#include "cli.hpp"

namespace {

std::string vector_json(const blockdem::Vec3& p) {
  using blockdem::io::JsonObject;
  return "[" + JsonObject::number(p.x()) + ", " + JsonObject::number(p.y()) + ", " + JsonObject::number(p.z()) + "]";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace blockdem;
  using models::Component;
  CLI::App app{"The LNEC masonry cross vault: geometry, components, materials and contacts (blockdem)"};
  models::CrossVaultOptions o;
  model::ContactSettings contacts;
  bool geometry_only = false, json = false;
  std::string vtk_path, contacts_vtk_path;
  app.add_flag("--geometry-only", geometry_only, "build and check the model and write it out (required for now)");
  app.add_option("--vtk", vtk_path, "write the blocks with their component and material as cell fields (.vtu)");
  app.add_option("--contacts-vtk", contacts_vtk_path,
                 "write the contact points with their joint kind, components, gap, area and normal (.vtu)");
  app.add_flag("--json", json, "print a JSON summary");
  app.add_option("--profile", o.profile, "profile of both barrels: segmental (circular arc, rise <= span/2) or elliptical")
      ->transform(CLI::CheckedTransformer(std::map<std::string, models::VaultProfile>{
          {"segmental", models::VaultProfile::segmental}, {"elliptical", models::VaultProfile::elliptical}}))
      ->capture_default_str();
  app.add_option("--plan", o.plan_size, "side of the square plan, m")->capture_default_str();
  app.add_option("--span", o.span, "net span of each barrel at the intrados, m")->capture_default_str();
  app.add_option("--rise", o.rise, "intrados crown above the springing, m (segmental: <= span/2)")->capture_default_str();
  app.add_option("--thickness", o.thickness, "ring thickness, m")->capture_default_str();
  app.add_option("--unit-height", o.unit_height, "brick height along the arc, m")->capture_default_str();
  app.add_option("--unit-length", o.unit_length, "brick length along the barrel axis, m")->capture_default_str();
  app.add_option("--joint", o.joint_thickness, "mortar joint thickness, m")->capture_default_str();
  app.add_option("--infill-fraction", o.infill_rise_fraction, "infill height over the rise, [0, 1)")->capture_default_str();
  app.add_option("--min-block-fraction", o.min_block_fraction,
                 "groin pieces below this fraction of a whole block merge into their neighbour, [0, 0.5)")->capture_default_str();
  app.add_option("--pier-height", o.pier_height, "slab top to the tie anchors, m (assumed)")->capture_default_str();
  app.add_option("--anchor-height", o.anchor_height, "tie anchor blocks on the piers, m (assumed)")->capture_default_str();
  app.add_option("--masonry-density", o.masonry_density, "kg/m^3 (assumed; not in the paper)")->capture_default_str();
  app.add_option("--contact-tolerance", contacts.tolerance, "contact detection tolerance, m")->capture_default_str();
  app.add_option("--max-cp-area", contacts.max_contact_point_area, "largest area per contact point, m^2 (0: CPs at the corners)")
      ->capture_default_str();
  if (const auto status = programs::parse_command_line(app, argc, argv)) return *status;
  if (!geometry_only) {
    std::fprintf(stderr,
                 "cross_vault: the dynamic analysis of the cross vault comes in a later issue; run with --geometry-only "
                 "to build, check and write out the model\n");
    return programs::exit_bad_input;
  }
  try {
    contacts.validate();
    const auto t0 = std::chrono::steady_clock::now();
    const auto vault = models::make_cross_vault(o);
    const auto model = models::build_rigid_model(vault);
    const double generation_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto t1 = std::chrono::steady_clock::now();
    const auto check = models::check_assembly(vault, model, contacts);
    const double check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    const bool passed = check.max_penetration <= contacts.tolerance && check.vault_connected &&
                        check.vault_blocks_below_two_neighbours == 0 && check.max_mass_error() <= 0.02;

    if (!vtk_path.empty()) {
      io::BlockFields fields;
      for (const auto& b : vault.blocks) {
        fields["component"].push_back(static_cast<double>(models::index(b.component)));
        fields["material"].push_back(static_cast<double>(b.material));
      }
      io::write_blocks_vtu(vtk_path, model, fields);
    }
    if (!contacts_vtk_path.empty()) {
      std::vector<Vec3> points, normals;
      io::BlockFields fields;
      for (const auto& c : check.contacts) {
        const auto [a, b] = vault.components(c);
        points.push_back(c.position);
        normals.push_back(c.normal);
        fields["joint_kind"].push_back(static_cast<double>(vault.joint(c).kind));
        fields["component_a"].push_back(static_cast<double>(models::index(a)));
        fields["component_b"].push_back(static_cast<double>(models::index(b)));
        fields["gap"].push_back(c.gap);
        fields["area"].push_back(c.area);
      }
      io::write_points_vtu(contacts_vtk_path, points, fields, {{"normal", normals}});
    }

    const auto& opt = vault.options;
    if (json) {
      io::JsonObject blocks, mass, analytical, boxes, joints, by_joint;
      for (const auto c : models::all_components) {
        const auto i = models::index(c);
        const std::string key(models::name(c));
        blocks.add(key, static_cast<long long>(vault.count(c)));
        mass.add(key, check.mass[i]);
        analytical.add(key, check.analytical_mass[i]);
        const auto box = models::bounding_box(vault, c);
        boxes.add_raw(key, "[" + vector_json(box[0]) + ", " + vector_json(box[1]) + "]");
      }
      blocks.add("total", static_cast<long long>(vault.blocks.size()));
      for (const auto kind : {models::JointKind::Softening, models::JointKind::MohrCoulombFriction, models::JointKind::ElasticSteel}) {
        by_joint.add(models::name(kind), static_cast<long long>(check.contact_points_by_joint[static_cast<std::size_t>(kind)]));
        const auto& p = kind == models::JointKind::Softening ? vault.joint(Component::vault, Component::vault)
                        : kind == models::JointKind::MohrCoulombFriction ? vault.joint(Component::movable_pier, Component::slab)
                                                                         : vault.joint(Component::steel_frame, Component::slab);
        io::JsonObject j;
        j.add("normal_stiffness_pa_m", p.normal_stiffness).add("shear_stiffness_pa_m", p.shear_stiffness)
            .add("friction_angle_deg", p.friction_angle * 180 / pi).add("cohesion_pa", p.cohesion)
            .add("tensile_strength_pa", p.tensile_strength);
        if (kind == models::JointKind::Softening)
          j.add("compressive_strength_pa", p.compressive_strength).add("fracture_energy_tension_n_m", p.fracture_energy_tension)
              .add("fracture_energy_shear_n_m", p.fracture_energy_shear).add("fracture_energy_compression_n_m", p.fracture_energy_compression);
        joints.add(models::name(kind), j);
      }
      std::vector<io::JsonObject> monitors;
      for (const auto& p : vault.monitor_points) {
        io::JsonObject m;
        m.add("name", p.name).add_raw("position", vector_json(p.position)).add("block", static_cast<long long>(p.block))
            .add("block_name", vault.blocks[p.block].name).add("component", models::name(vault.blocks[p.block].component));
        monitors.push_back(m);
      }
      io::JsonObject out;
      out.add("profile", o.profile == models::VaultProfile::segmental ? "segmental" : "elliptical")
          .add("courses_per_barrel", vault.courses)
          .add("intrados_radius_m", vault.radius)
          .add("springing_level_m", vault.springing_level())
          .add("crown_extrados_m", vault.extrados_level(0, 0))
          .add("blocks", blocks)
          .add("contact_points", static_cast<long long>(check.contact_points))
          .add("open_contact_points", static_cast<long long>(check.open_contact_points))
          .add("contact_points_by_joint", by_joint)
          .add("mass_kg", mass)
          .add("analytical_mass_kg", analytical)
          .add("max_mass_error", check.max_mass_error())
          .add("bounding_box_m", boxes)
          .add("monitor_points", monitors)
          .add("ties", static_cast<long long>(vault.ties.size()))
          .add("tie_mass_kg", check.tie_mass)
          .add("joints", joints)
          .add("vault_slivers_merged", static_cast<long long>(vault.vault_slivers_merged))
          .add("infill_pieces_dropped", static_cast<long long>(vault.infill_pieces_dropped))
          .add("infill_volume_dropped_m3", vault.infill_volume_dropped)
          .add("max_penetration_m", check.max_penetration)
          .add("vault_connected", check.vault_connected)
          .add("min_vault_neighbours", static_cast<long long>(check.min_vault_neighbours))
          .add("generation_seconds", generation_seconds)
          .add("detection_seconds", check.detection_seconds)
          .add("check_seconds", check_seconds)
          .add("checks_passed", passed);
      fmt::print("{}\n", out.str());
    } else {
      fmt::print("cross vault: {} profile, span {:g} m, rise {:g} m, ring {:g} m, plan {:g} x {:g} m, {} courses per barrel{}\n",
                 o.profile == models::VaultProfile::segmental ? "segmental" : "elliptical", opt.span, opt.rise, opt.thickness,
                 opt.plan_size, opt.plan_size, vault.courses,
                 vault.radius > 0 ? fmt::format(" (intrados radius {:.4f} m)", vault.radius) : std::string());
      fmt::print("{:<14} {:>7} {:>12} {:>12} {:>9}\n", "component", "blocks", "mass kg", "analytical", "error");
      for (const auto c : models::all_components) {
        const auto i = models::index(c);
        fmt::print("{:<14} {:>7} {:>12.2f} {:>12.2f} {:>8.3f}%\n", models::name(c), vault.count(c), check.mass[i],
                   check.analytical_mass[i], 100 * (check.mass[i] / check.analytical_mass[i] - 1));
      }
      fmt::print("{} blocks; {} groin pieces merged into their neighbours; {} infill pieces dropped ({:.3g} m^3)\n",
                 vault.blocks.size(), vault.vault_slivers_merged, vault.infill_pieces_dropped, vault.infill_volume_dropped);
      fmt::print("{} contact points ({} softening, {} Mohr-Coulomb, {} elastic; {} open beyond the tolerance), deepest "
                 "overlap {:.2e} m, vault contact graph {}, every vault block touches >= {} vault blocks\n",
                 check.contact_points, check.contact_points_by_joint[0], check.contact_points_by_joint[1],
                 check.contact_points_by_joint[2], check.open_contact_points, check.max_penetration,
                 check.vault_connected ? "connected" : "NOT connected", check.min_vault_neighbours);
      fmt::print("{} ties ({:.1f} kg); monitor points:", vault.ties.size(), check.tie_mass);
      for (const auto& p : vault.monitor_points)
        fmt::print(" {} ({:.3f}, {:.3f}, {:.3f})", p.name, p.position.x(), p.position.y(), p.position.z());
      fmt::print("\ngenerated in {:.3f} s, checked in {:.3f} s (detection {:.3f} s): {}\n", generation_seconds, check_seconds,
                 check.detection_seconds, passed ? "all checks passed" : "CHECKS FAILED");
    }
    if (!passed) {
      std::fprintf(stderr, "cross_vault: the assembly check failed (overlap, connectivity or mass beyond 2 %%)\n");
      return 1;
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "cross_vault: error: %s\n", e.what());
    return programs::exit_bad_input;
  }
  return 0;
}
