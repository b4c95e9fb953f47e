#pragma once
// The incremental shake-table analysis of the LNEC cross vault (paper Sect. 5, 6.1; Table 4, Figs. 14-18): the
// vault's structure (its blocks, rigid or meshed, its ties, its components as groups with the joint law of every
// pair, the monitor points of the test and the slab as the table) fed to the study of any structure (study.hpp).

#include <cstddef>
#include <string>
#include <variant>

#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/study.hpp"
#include "blockdem/analysis/vault_study_options.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/models/cross_vault.hpp"

namespace blockdem::analysis {

/// The simulation of the vault under damping policy D: the study's (the three joint laws of the paper).
template <class D>
using VaultSimulation = StudySimulation<D>;
using VaultStudyResult = StudyResult;

namespace detail {

/// Whether the options make block i of the vault deformable: every free block (deformable), every free block but the
/// steel frame (mixed, Sect. 6.1.1), none (rigid).
inline bool meshed(const VaultStudyOptions& o, const models::CrossVaultBlock& b) {
  if (b.motion != model::Motion::free || o.kinematics == VaultKinematics::rigid) return false;
  return o.kinematics == VaultKinematics::deformable || b.component != models::Component::steel_frame;
}

/// The model of the options: the generator's blocks, rigid or meshed into constant-strain tetrahedra (max edge
/// o.max_edge for masonry and concrete, o.steel_max_edge for the steel frame and the movable steel piers, Sect. 5)
/// with each block's material, and the steel ties as trusses between the anchors (an end on a deformable anchor on
/// its nearest node, on a rigid one fixed to the block).
inline model::Model vault_model(const models::CrossVault& v, const VaultStudyOptions& o) {
  model::Model m = models::build_rigid_model(v);
  for (std::size_t i = 0; i < v.blocks.size(); ++i) {
    const auto& b = v.blocks[i];
    if (!meshed(o, b)) continue;
    const bool steel = b.component == models::Component::steel_frame || b.component == models::Component::movable_pier;
    const auto& material = v.materials[b.material];
    m.make_deformable(i, steel ? o.steel_max_edge : o.max_edge, model::IsotropicElastic(material.youngs_modulus, material.poisson_ratio));
  }
  auto end = [&m](std::size_t block, const Vec3& x) {
    return m.deformable.is_deformable(block) ? m.node_end(m.nearest_node(block, x)) : m.block_end(block, x);
  };
  for (const auto& t : v.ties)
    m.add_truss(end(t.block_a, t.end_a), end(t.block_b, t.end_b), t.area, t.youngs_modulus, t.density, t.pretension, t.name);
  return m;
}

}  // namespace detail

/// The vault as a structure: its components are its groups (joint tag = component index), the joint of every pair
/// of components (Table 1-2) is the law table's, OC1-OC4 and the accelerometers are its monitor points, the slab
/// is the table.
inline Structure vault_structure(const models::CrossVault& v, const VaultStudyOptions& o) {
  Structure s;
  s.name = "cross vault";
  s.model = detail::vault_model(v, o);
  s.laws = LawTable(std::vector<std::string>(models::component_names.begin(), models::component_names.end()));
  for (const auto a : models::all_components)
    for (const auto b : models::all_components)
      if (models::index(a) <= models::index(b) && v.joint(a, b).normal_stiffness > 0)
        s.laws.set(models::index(a), models::index(b), models::joint_law(v.joint(a, b)));
  s.monitors = v.monitor_points;
  for (std::size_t i = 0; i < v.blocks.size(); ++i)
    if (v.blocks[i].component == models::Component::slab) {
      s.table = i;
      break;
    }
  s.report = {{"kinematics", io::JsonObject::quoted(name(o.kinematics))},
              {"residual_compressive_strength_pa", io::JsonObject::number(o.vault.residual_compressive_strength)}};
  return s;
}
inline Structure vault_structure(const VaultStudyOptions& o) { return vault_structure(models::make_cross_vault(o.vault), o); }

/// The vault of the options as a model file describes it (model_file_writer.hpp): the generator's blocks with their
/// world shapes and materials, meshed as the kinematics say, its ties, joints, monitor points and table. Reading the
/// file back gives vault_structure(o) bit for bit.
inline ModelDescription vault_description(const VaultStudyOptions& o) {
  const auto v = models::make_cross_vault(o.vault);
  const Structure s = vault_structure(v, o);
  ModelDescription d;
  d.name = "LNEC cross vault (paper Sect. 2)";
  d.gravity = s.model.gravity;
  for (const auto& m : v.materials) d.materials.push_back({m.name, m.density, m.youngs_modulus, m.poisson_ratio});
  d.laws = s.laws;
  for (const auto& b : v.blocks) {
    const bool steel = b.component == models::Component::steel_frame || b.component == models::Component::movable_pier;
    d.blocks.push_back({b.name, models::index(b.component), b.material, b.motion, b.shape,
                        detail::meshed(o, b) ? (steel ? o.steel_max_edge : o.max_edge) : 0.0});
  }
  for (const auto& t : v.ties) {
    ModelDescription::Tie tie;
    tie.name = t.name;
    tie.block[0] = t.block_a;
    tie.block[1] = t.block_b;
    tie.point[0] = t.end_a;
    tie.point[1] = t.end_b;
    tie.area = t.area;
    tie.young = t.youngs_modulus;
    tie.density = t.density;
    tie.pretension = t.pretension;
    d.ties.push_back(tie);
  }
  d.monitors = s.monitors;
  d.table = s.table;
  d.contact_tolerance = s.contacts.tolerance;
  return d;
}

/// The settled vault's first natural frequency and damping ratio at OC1 (measure_free_vibration of study.hpp).
inline FreeVibrationResult measure_free_vibration(const VaultStudyOptions& o, double duration = 1.0, double pulse_velocity = 1e-3,
                                                  double pulse_duration = 0.05) {
  o.validate();
  return measure_free_vibration(vault_structure(o), o, duration, pulse_velocity, pulse_duration);
}

/// Runs the vault study (run_study of study.hpp on the vault's structure).
inline StudyResult run_vault_study(const VaultStudyOptions& o) {
  o.validate();
  return run_study(vault_structure(o), o);
}

}  // namespace blockdem::analysis
