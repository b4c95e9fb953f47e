#pragma once
// Writes a model file (docs/model-file.md) from a description of the structure as built: the blocks' shapes in world
// coordinates as given (not as a model stores them, in body frames), so that reading the file back builds the same
// model bit for bit; numbers are written in the shortest form that reads back exactly. Used by `cross_vault model`.

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "blockdem/analysis/pushover_options.hpp"
#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/contact/laws.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/io/json.hpp"
#include "blockdem/model/model.hpp"
#include "blockdem/model/monitor_point.hpp"

namespace blockdem::analysis {

/// A structure as a model file describes it.
struct ModelDescription {
  struct Material {
    std::string name;
    double density = 0, young = 0, poisson = 0;  // kg/m^3, Pa (0: not given)
  };
  struct Block {
    std::string name;
    std::size_t group = 0, material = 0;
    model::Motion motion = model::Motion::free;
    geometry::ConvexPolyhedron shape;  // world, m
    double max_edge = 0;               // m; 0: rigid
  };
  struct Tie {
    std::string name;
    std::size_t block[2] = {0, 0};
    Vec3 point[2];
    double area = 0, young = 0, density = 0, pretension = 0;
  };
  std::string name;
  Vec3 gravity = Vec3(0, 0, -9.81);
  std::vector<Material> materials;
  LawTable laws;  // its groups too
  std::vector<Block> blocks;
  std::vector<Tie> ties;
  std::vector<model::MonitorPoint> monitors;
  std::optional<std::size_t> table;
  double contact_tolerance = 1e-3;
};

namespace detail {

inline std::string json_number(double x) { return io::JsonObject::number(x); }
inline std::string json_vec3(const Vec3& x) { return "[" + json_number(x.x()) + ", " + json_number(x.y()) + ", " + json_number(x.z()) + "]"; }
inline std::string json_string(std::string_view s) { return io::JsonObject::quoted(s); }

inline std::string joint_json(const contact::JointLaw& law) {
  std::string s;
  auto add = [&s](const char* key, double value) { (((s += ", \"") += key) += "\": ") += json_number(value); };
  std::visit([&]<class P>(const P& p) {
    if constexpr (std::is_same_v<P, contact::Elastic::Parameters>) {
      s += "\"law\": \"elastic\"";
      add("normal_stiffness", p.normal_stiffness);
      add("shear_stiffness", p.shear_stiffness);
    } else if constexpr (std::is_same_v<P, contact::MohrCoulomb::Parameters>) {
      s += "\"law\": \"mohr_coulomb\"";
      add("normal_stiffness", p.normal_stiffness);
      add("shear_stiffness", p.shear_stiffness);
      add("tensile_strength", p.tensile_strength);
      add("cohesion", p.cohesion);
      add("friction_angle_rad", p.friction_angle);
      add("residual_tensile_strength", p.residual_tensile_strength);
      add("residual_cohesion", p.residual_cohesion);
      add("residual_friction_angle_rad", p.residual_friction_angle);
    } else {
      s += "\"law\": \"softening\"";
      add("normal_stiffness", p.normal_stiffness);
      add("shear_stiffness", p.shear_stiffness);
      add("tensile_strength", p.tensile_strength);
      add("cohesion", p.cohesion);
      add("friction_angle_rad", p.friction_angle);
      add("compressive_strength", p.compressive_strength);
      add("residual_tensile_strength", p.residual_tensile_strength);
      add("residual_cohesion", p.residual_cohesion);
      add("residual_friction_angle_rad", p.residual_friction_angle);
      add("residual_compressive_strength", p.residual_compressive_strength);
      add("fracture_energy_tension", p.tension_fracture_energy);
      add("fracture_energy_shear", p.shear_fracture_energy);
      add("fracture_energy_compression", p.compression_fracture_energy);
      add("cap_shear_factor", p.cap_shear_factor);
      add("damping_damage_limit", p.damping_damage_limit);
    }
  }, law);
  return s;
}

inline const char* motion_name(model::Motion m) { return m == model::Motion::free ? "free" : m == model::Motion::fixed ? "fixed" : "base"; }
inline const char* axis_name(char axis) { return axis == 'x' ? "x" : axis == 'y' ? "y" : "z"; }

}  // namespace detail

/// Writes `d` with the study `o` (its excitation and study; not how it is run: output folder, progress, checkpoints).
inline void write_model_file(std::ostream& out, const ModelDescription& d, const StudyOptions& o,
                             const PushoverOptions* pushover = nullptr) {
  using detail::json_number, detail::json_string, detail::json_vec3;
  out << "{\n  \"blockdem_model\": 1,\n  \"name\": " << json_string(d.name) << ",\n  \"units\": \"SI\",\n  \"gravity\": " << json_vec3(d.gravity)
      << ",\n  \"materials\": {";
  for (std::size_t i = 0; i < d.materials.size(); ++i) {
    const auto& m = d.materials[i];
    out << (i ? ",\n    " : "\n    ") << json_string(m.name) << ": {\"density\": " << json_number(m.density);
    if (m.young > 0) out << ", \"youngs_modulus\": " << json_number(m.young) << ", \"poisson_ratio\": " << json_number(m.poisson);
    out << "}";
  }
  out << "\n  },\n  \"groups\": [";
  const auto& groups = d.laws.group_names();
  for (std::size_t g = 0; g < groups.size(); ++g) out << (g ? ", " : "") << json_string(groups[g]);
  out << "],\n  \"joints\": [";
  bool first = true;
  for (std::size_t a = 0; a < groups.size(); ++a)
    for (std::size_t b = a; b < groups.size(); ++b) {
      if (!d.laws.has(a, b)) continue;
      out << (first ? "\n    " : ",\n    ") << "{\"between\": [" << json_string(groups[a]) << ", " << json_string(groups[b]) << "], "
          << detail::joint_json(d.laws.law(a, b));
      if (d.laws.contact_point_area(a, b) > 0) out << ", \"contact_point_spacing\": " << json_number(std::sqrt(d.laws.contact_point_area(a, b)));
      out << "}";
      first = false;
    }
  out << "\n  ],\n  \"contacts\": {\"kinds\": \"" << (o.contacts == model::ContactKinds::general ? "general" : "faces")
      << "\", \"tolerance\": " << json_number(d.contact_tolerance) << "},\n  \"blocks\": [";
  for (std::size_t i = 0; i < d.blocks.size(); ++i) {
    const auto& b = d.blocks[i];
    out << (i ? ",\n    " : "\n    ") << "{\"name\": " << json_string(b.name) << ", \"group\": " << json_string(groups[b.group])
        << ", \"material\": " << json_string(d.materials[b.material].name) << ", \"motion\": \"" << detail::motion_name(b.motion) << "\"";
    if (b.max_edge > 0) out << ", \"deformable\": {\"max_edge\": " << json_number(b.max_edge) << "}";
    out << ",\n     \"vertices\": [";
    for (std::size_t v = 0; v < b.shape.vertices.size(); ++v) out << (v ? ", " : "") << json_vec3(b.shape.vertices[v]);
    out << "],\n     \"faces\": [";
    for (std::size_t f = 0; f < b.shape.faces.size(); ++f) {
      out << (f ? ", [" : "[");
      for (std::size_t k = 0; k < b.shape.faces[f].size(); ++k) out << (k ? ", " : "") << b.shape.faces[f][k];
      out << "]";
    }
    out << "]}";
  }
  out << "\n  ]";
  if (!d.ties.empty()) {
    out << ",\n  \"ties\": [";
    for (std::size_t t = 0; t < d.ties.size(); ++t) {
      const auto& tie = d.ties[t];
      out << (t ? ",\n    " : "\n    ") << "{\"name\": " << json_string(tie.name) << ", \"ends\": [";
      for (int k = 0; k < 2; ++k)
        out << (k ? ", " : "") << "{\"block\": " << tie.block[k] << ", \"point\": " << json_vec3(tie.point[k]) << "}";
      out << "], \"area\": " << json_number(tie.area) << ", \"youngs_modulus\": " << json_number(tie.young)
          << ", \"density\": " << json_number(tie.density) << ", \"pretension\": " << json_number(tie.pretension) << "}";
    }
    out << "\n  ]";
  }
  if (!d.monitors.empty()) {
    out << ",\n  \"monitors\": [";
    for (std::size_t p = 0; p < d.monitors.size(); ++p) {
      const auto& m = d.monitors[p];
      out << (p ? ",\n    " : "\n    ") << "{\"name\": " << json_string(m.name) << ", \"block\": " << m.block
          << ", \"point\": " << json_vec3(m.position) << "}";
    }
    out << "\n  ]";
  }
  if (d.table) out << ",\n  \"table\": " << *d.table;
  // The excitation and the study.
  // The record by its absolute path: the file may be read from another folder (a relative path in a model file is
  // relative to the file's folder).
  const std::string record = o.record_path.empty() ? std::string() : std::filesystem::absolute(o.record_path).string();
  out << ",\n  \"excitation\": {\"record\": " << json_string(record) << ", \"axis\": \"" << detail::axis_name(o.axis)
      << "\", \"baseline\": " << json_string(o.baseline);
  if (o.read.units) out << ", \"units\": \"" << (*o.read.units == motion::AccelerationUnit::g ? "g" : *o.read.units == motion::AccelerationUnit::m_s2 ? "m/s2" : "cm/s2") << "\"";
  if (o.read.dt) out << ", \"dt\": " << json_number(*o.read.dt);
  if (o.truncation == Truncation::wavelet) out << ", \"truncation\": \"wavelet\"";
  else if (!o.window_default) out << ", \"window_s\": [" << json_number(o.window_start) << ", " << json_number(o.window_end) << "]";
  out << ", \"record_level_percent\": " << json_number(o.record_level) << "},\n  \"study\": {\n    \"analysis\": ";
  if (pushover)
    out << "\"pushover\", \"pushover\": {\"axis\": \"" << (pushover->sign < 0 ? "-" : "") << pushover->axis << "\", \"upper\": "
        << json_number(pushover->upper) << ", \"resolution\": " << json_number(pushover->resolution)
        << ", \"collapse_displacement_m\": " << json_number(pushover->collapse_displacement) << ", \"tolerance\": "
        << json_number(pushover->tolerance) << ", \"max_steps\": " << pushover->max_steps << "},\n    ";
  else
    out << "\"levels\", ";
  out << "\"levels_percent\": [";
  for (std::size_t l = 0; l < o.levels.size(); ++l) out << (l ? ", " : "") << json_number(o.levels[l]);
  out << "], \"rest_s\": " << json_number(o.rest) << ",\n    \"damping\": {\"scheme\": \"" << name(o.damping) << "\", \"zeta\": "
      << json_number(o.zeta) << ", \"frequency_hz\": " << json_number(o.frequency_hz) << ", \"band_hz\": [" << json_number(o.lower_hz)
      << ", " << json_number(o.upper_hz) << "], \"branches\": " << o.branches << ", \"frame\": \"" << name(o.damping_frame)
      << "\"},\n    \"timestep\": {\"target_dt_s\": "
      << json_number(o.target_dt) << ", \"mass_increase_percent\": " << json_number(o.default_mass_increase_percent)
      << ", \"max_mass_increase_percent\": " << json_number(o.max_mass_increase_percent) << "},\n    \"settle\": {\"method\": \""
      << name(o.settling) << "\", \"tolerance\": " << json_number(o.settle_tolerance) << ", \"max_steps\": " << o.settle_max_steps
      << "},\n    \"outputs\": {\"history_dt_s\": "
      << json_number(o.history_dt) << ", \"snapshots_every_s\": " << json_number(o.snapshots_every) << "},\n    \"collapse_displacement_m\": "
      << json_number(o.collapse_displacement) << ", \"runaway_displacement_m\": " << json_number(o.runaway_displacement)
      << ", \"max_speed_m_s\": " << json_number(o.max_speed) << ", \"free_vibration\": " << (o.free_vibration ? "true" : "false")
      << "\n  }\n}\n";
}

}  // namespace blockdem::analysis
