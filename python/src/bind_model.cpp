// The model file from Python (docs/model-file.md): read into blockdem's structure (every error naming the field),
// checked as `blockdem check` checks it, and the generators of common typologies (`blockdem generate`), which
// write model files. The Python class blockdem.Model (model.py) holds the file as a dict and calls these.

#include <sstream>

#include "bindings.hpp"

#include "blockdem/analysis/arch.hpp"
#include "blockdem/analysis/model_file.hpp"
#include "blockdem/analysis/model_file_writer.hpp"
#include "blockdem/analysis/structure_check.hpp"
#include "blockdem/analysis/typologies.hpp"
#include "blockdem/analysis/vault_study.hpp"
#include "blockdem/geometry/mass_properties.hpp"

namespace blockdem::python {

namespace {

py::list issue_list(const std::vector<geometry::BlockIssue>& issues) {
  py::list out;
  for (const auto& i : issues) {
    py::dict d;
    d["severity"] = geometry::BlockIssue::severity_name(i.severity);
    d["block"] = i.block;
    d["origin"] = i.origin;
    d["message"] = i.what;
    d["text"] = i.subject() + ": " + i.what;
    out.append(d);
  }
  return out;
}

/// What `blockdem check --json` prints of a model file, as a dict.
py::dict check(const analysis::ModelFile& file) {
  const auto& s = file.structure;
  s.validate();
  const auto c = analysis::check_structure_contacts(s, file.study.contacts, file.geometry_issues, file.block_origin);
  py::dict pairs;
  for (const auto& [pair, n] : c.contact_points_by_pair) pairs[py::str(s.laws.name(pair.first) + "-" + s.laws.name(pair.second))] = n;
  py::dict d;
  d["model"] = s.name;
  d["blocks"] = s.model.bodies.size();
  d["deformable_blocks"] = s.model.deformable.blocks.size();
  d["nodes"] = s.model.deformable.nodes.size();
  d["tetrahedra"] = s.model.deformable.tetrahedra.size();
  d["ties"] = s.model.deformable.trusses.size();
  d["groups"] = s.groups();
  d["free_mass_kg"] = s.model.total_mass();
  d["contact_points"] = c.contact_points;
  d["contact_points_by_group_pair"] = pairs;
  d["deepest_overlap_m"] = c.assembly.deepest_overlap;
  py::list monitors;
  for (const auto& m : s.monitors) monitors.append(m.name);
  d["monitor_points"] = monitors;
  d["table"] = s.table ? py::object(py::str(s.model.bodies.name[*s.table])) : py::object(py::none());
  d["issues"] = issue_list(c.issues);
  d["errors"] = analysis::count_issues(c.issues, geometry::BlockIssue::Severity::error);
  d["issues_text"] = analysis::issues_text(c.issues);
  return d;
}

std::string model_text(const analysis::ModelDescription& d, const analysis::StudyOptions& o, const analysis::PushoverOptions* p) {
  std::ostringstream out;
  analysis::write_model_file(out, d, o, p);
  return out.str();
}

analysis::MasonryUnit unit(const std::string& s) {
  return choice<analysis::MasonryUnit>(s, "unit", {{"brick", analysis::MasonryUnit::brick}, {"stone", analysis::MasonryUnit::stone}});
}

}  // namespace

void bind_model(py::module_& m) {
  py::class_<analysis::ModelFile>(m, "ModelFile", "A model file as blockdem reads it (internal: blockdem.Model wraps it).")
      .def_property_readonly("name", [](const analysis::ModelFile& f) { return f.structure.name; })
      .def_property_readonly("blocks", [](const analysis::ModelFile& f) { return f.structure.model.bodies.size(); })
      .def_property_readonly("groups", [](const analysis::ModelFile& f) { return f.structure.groups(); })
      .def_property_readonly("block_names", [](const analysis::ModelFile& f) { return f.structure.model.bodies.name; })
      .def_property_readonly("monitor_points", [](const analysis::ModelFile& f) {
        std::vector<std::string> names;
        for (const auto& mp : f.structure.monitors) names.push_back(mp.name);
        return names;
      })
      .def_property_readonly("pushover", [](const analysis::ModelFile& f) { return f.pushover.has_value(); })
      .def_property_readonly("free_mass", [](const analysis::ModelFile& f) { return f.structure.model.total_mass(); });

  m.def("parse_model", &analysis::parse_model_file, py::arg("text"), py::arg("source"), py::arg("base_dir") = "",
        "Reads a model file from its JSON text; `source` names it in messages, relative paths are taken from `base_dir`.");
  m.def("check_model", &check, py::arg("file"), "What `blockdem check --json` reports of a model file, as a dict.");

  m.def(
      "generate_wall",
      [](double length, int courses, double thickness, double unit_length, double unit_height,
         const std::vector<std::tuple<double, double, int, int>>& openings, double lintel_bearing, double return_length, bool floor,
         const std::string& unit_name, const std::string& lintel, double friction_angle, double normal_stiffness, bool pushover) {
        analysis::WallStudyOptions o;
        auto& w = o.wall;
        w.length = length;
        w.courses = courses;
        w.thickness = thickness;
        w.unit_length = unit_length;
        w.unit_height = unit_height;
        for (const auto& [x0, x1, sill, head] : openings) w.openings.push_back({x0, x1, sill, head});
        w.lintel_bearing = lintel_bearing;
        w.return_length = return_length;
        w.foundation = floor ? geometry::Foundation::floor : geometry::Foundation::block;
        o.unit = unit(unit_name);
        o.lintel = unit(lintel);
        o.joints.friction_angle_deg = friction_angle;
        o.joints.normal_stiffness = normal_stiffness;
        const auto p = analysis::wall_pushover(o);
        return model_text(analysis::wall_description(o), o, pushover ? &p : nullptr);
      },
      py::arg("length") = 2.0, py::arg("courses") = 20, py::arg("thickness") = 0.12, py::arg("unit_length") = 0.25,
      py::arg("unit_height") = 0.075, py::arg("openings") = std::vector<std::tuple<double, double, int, int>>{},
      py::arg("lintel_bearing") = 0.125, py::arg("return_length") = 0.0, py::arg("floor") = false, py::arg("unit") = "brick",
      py::arg("lintel") = "stone", py::arg("friction_angle") = 35.0, py::arg("normal_stiffness") = 1e10, py::arg("pushover") = false,
      "The model file (JSON text) of `blockdem generate wall`.");
  m.def(
      "generate_barrel_vault",
      [](double span, double thickness, double length, int rings, double unit_length, bool straight_joints, const std::string& unit_name,
         double friction_angle, double normal_stiffness, bool pushover) {
        analysis::BarrelVaultStudyOptions o;
        auto& b = o.vault;
        b.span = span;
        b.thickness = thickness;
        b.length = length;
        b.rings = rings;
        b.unit_length = unit_length;
        b.running_bond = !straight_joints;
        o.unit = unit(unit_name);
        o.joints.friction_angle_deg = friction_angle;
        o.joints.normal_stiffness = normal_stiffness;
        const auto p = analysis::barrel_vault_pushover(o);
        return model_text(analysis::barrel_vault_description(o), o, pushover ? &p : nullptr);
      },
      py::arg("span") = 2.0, py::arg("thickness") = 0.24, py::arg("length") = 1.0, py::arg("rings") = 15, py::arg("unit_length") = 0.25,
      py::arg("straight_joints") = false, py::arg("unit") = "brick", py::arg("friction_angle") = 35.0,
      py::arg("normal_stiffness") = 1e10, py::arg("pushover") = false, "The model file (JSON text) of `blockdem generate barrel-vault`.");
  m.def(
      "generate_arch",
      [](int voussoirs, double radius, double thickness_ratio, double depth, double friction_angle) {
        analysis::ArchOptions a;
        a.voussoirs = voussoirs;
        a.radius = radius;
        a.thickness_ratio = thickness_ratio;
        a.depth = depth;
        a.friction_angle_deg = friction_angle;
        analysis::StudyOptions o;
        o.axis = 'x';
        const auto p = analysis::arch_pushover(a);
        return model_text(analysis::arch_description(a), o, &p);
      },
      py::arg("voussoirs") = 40, py::arg("radius") = 1.0, py::arg("thickness_ratio") = 0.15, py::arg("depth") = 0.5,
      py::arg("friction_angle") = 40.0, "The model file (JSON text) of `blockdem generate arch`: its pushover along x.");
  m.def(
      "generate_cross_vault",
      []() {
        analysis::VaultStudyOptions o;
        return model_text(analysis::vault_description(o), o, nullptr);
      },
      "The model file (JSON text) of `blockdem generate cross-vault`: the paper's vault on the shake table.");
}

}  // namespace blockdem::python
