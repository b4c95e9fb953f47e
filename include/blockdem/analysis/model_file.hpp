#pragma once
// The model file (docs/model-file.md; its JSON Schema: docs/model-file.schema.json): a structure and its study as
// one versioned JSON document, read into a Structure (the blocks, groups, laws, ties, monitor points and table) and
// StudyOptions (the excitation and the study, model_file_study.hpp). Every error names the file, line and column,
// the field (blocks[12].faces[3]) and what is allowed. Units are SI throughout (m, kg, s, N, Pa).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <span>
#include <sstream>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "blockdem/analysis/model_file_geometry.hpp"
#include "blockdem/analysis/model_file_laws.hpp"
#include "blockdem/analysis/model_file_study.hpp"
#include "blockdem/analysis/structure.hpp"
#include "blockdem/analysis/study_options.hpp"
#include "blockdem/core/error.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"
#include "blockdem/io/json_fields.hpp"
#include "blockdem/io/json_reader.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::analysis {

inline constexpr int model_file_version = 1;

/// A model file as read: the structure, the study it asks for (before a command line's overrides) and how the
/// record is scaled.
struct ModelFile {
  std::string path;
  Structure structure;
  StudyOptions study;
  RecordScale scale;  // the excitation's intensity target, resolved against the record at run time
  std::optional<PushoverOptions> pushover;  // "analysis": "pushover": the pushover instead of the levels
  std::vector<geometry::BlockIssue> geometry_issues;  // what the checks of imported blocks found and fixed
  std::vector<std::string> block_origin;  // per block, where it is defined: "walls.obj:120", "model.json:12:5"
};

namespace detail {

struct FileMaterial {
  double density = 0;
  double young = 0, poisson = 0;  // 0: not given (a deformable block needs them)
};

/// The block named by `v`: a name (a string) or an index (an integer), for monitor points and ties.
inline constexpr std::size_t ambiguous = static_cast<std::size_t>(-1);  // two blocks have the name

inline std::size_t block_reference(const io::JsonValue& v, const std::string& path, const std::map<std::string, std::size_t>& by_name,
                                   std::size_t blocks) {
  if (v.is_number()) {
    const double i = v.as_number();
    if (!(i >= 0 && i < static_cast<double>(blocks) && i == std::floor(i)))
      io::field_error(v, path, "no block " + num(i) + " (blocks are numbered 0.." + std::to_string(blocks - 1) + ")");
    return static_cast<std::size_t>(i);
  }
  const std::string& name = io::string_value(v, path);
  const auto it = by_name.find(name);
  if (it == by_name.end()) io::field_error(v, path, "no block named \"" + name + "\"");
  if (it->second == ambiguous) io::field_error(v, path, "more than one block is named \"" + name + "\": refer to it by its index");
  return it->second;
}

/// A block's shape: "box": [[x0, y0, z0], [x1, y1, z1]], or "vertices" and "faces" (vertex indices, each face's
/// orientation free: it is turned to face outwards, the block being convex).
inline geometry::ConvexPolyhedron block_shape(const io::JsonFields& f) {
  if (const auto* box = f.find("box")) {
    if (f.has("vertices") || f.has("faces")) io::field_error(*box, f.path("box"), "give a box or vertices and faces, not both");
    const auto& corners = io::array_value(*box, f.path("box"), 2, 2);
    const Vec3 lo = io::vec3_value(corners[0], f.path("box") + "[0]"), hi = io::vec3_value(corners[1], f.path("box") + "[1]");
    if (!((hi - lo).minCoeff() > 0)) io::field_error(*box, f.path("box"), "the second corner must exceed the first along x, y and z");
    return geometry::make_box(lo, hi);
  }
  geometry::ConvexPolyhedron p;
  const auto& vertices = io::array_value(f.required("vertices", "the corners [[x, y, z], ...], m; or a \"box\""), f.path("vertices"), 4);
  for (std::size_t i = 0; i < vertices.size(); ++i) p.vertices.push_back(io::vec3_value(vertices[i], f.path("vertices") + "[" + std::to_string(i) + "]"));
  const auto& faces = io::array_value(f.required("faces", "lists of vertex indices, one per face"), f.path("faces"), 4);
  Vec3 centre = Vec3::Zero();
  for (const auto& v : p.vertices) centre += v;
  centre /= static_cast<double>(p.vertices.size());
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const std::string path = f.path("faces") + "[" + std::to_string(k) + "]";
    std::vector<int> face;
    for (std::size_t j = 0; const auto& v : io::array_value(faces[k], path, 3)) {
      const double index = io::number_value(v, path + "[" + std::to_string(j++) + "]",
                                            {0, static_cast<double>(p.vertices.size() - 1), false, false, ""});
      if (index != std::floor(index)) io::field_error(v, path, "a vertex index must be an integer, got " + num(index));
      face.push_back(static_cast<int>(index));
    }
    p.faces.push_back(std::move(face));
    // Outwards: the face's normal points away from the centre of the vertices (inside a convex block).
    if (p.face_area_vector(k).dot(p.face_centroid(k) - centre) < 0) std::reverse(p.faces.back().begin(), p.faces.back().end());
  }
  return p;
}

}  // namespace detail

/// Reads a model file from its text. `source` names it in messages; relative paths in it (the record) are taken
/// relative to `base_dir`. Throws InvalidArgument naming the file, line, column and field.
inline ModelFile parse_model_file(std::string_view text, const std::string& source, const std::string& base_dir = "") {
  const io::JsonValue root = io::parse_json(text, source);
  const io::JsonFields top(root, "", {"blockdem_model", "name", "units", "gravity", "materials", "groups", "joints", "blocks", "ties",
                                      "contacts", "monitors", "table", "excitation", "study"});
  {
    const auto& version = top.required("blockdem_model", "the format's version: 1");
    if (!version.is_number() || version.as_number() != model_file_version)
      io::field_error(version, "blockdem_model", "this blockdem reads version " + std::to_string(model_file_version) +
                                                     " of the model file (\"blockdem_model\": 1)");
  }
  ModelFile file;
  file.path = source;
  Structure& s = file.structure;
  s.name = top.string("name", std::filesystem::path(source).stem().string());
  if (const auto* units = top.find("units"))
    if (io::string_value(*units, "units") != "SI") io::field_error(*units, "units", "the model file is in SI units only (m, kg, s, N, Pa): \"SI\"");
  model::Model& m = s.model;
  m.gravity = top.vec3("gravity", Vec3(0, 0, -9.81), io::Range{-1e3, 1e3, false, false, "m/s^2"});

  // Materials.
  std::map<std::string, detail::FileMaterial> materials;
  const auto& all_materials = top.required("materials", "an object of named materials, {\"brick\": {\"density\": 1800}}");
  if (!all_materials.is_object())
    io::field_error(all_materials, "materials", std::string("expected an object of named materials, {\"brick\": {\"density\": 1800}}, got ") +
                                                    io::JsonValue::kind_name(all_materials.kind()));
  for (const auto& [name, value] : all_materials.as_object()) {
    const io::JsonFields f(value, "materials." + name, {"density", "youngs_modulus", "poisson_ratio"});
    detail::FileMaterial mat;
    mat.density = f.required_number("density", {0, 1e5, true, false, "kg/m^3"});
    mat.young = f.number("youngs_modulus", 0, {0, 1e13, true, false, "Pa"});
    mat.poisson = f.number("poisson_ratio", 0, {-1, 0.5, true, true, ""});
    materials[name] = mat;
  }

  // Groups: as listed, then as the blocks name them.
  std::vector<std::string> groups;
  if (const auto* g = top.find("groups"))
    for (std::size_t i = 0; const auto& v : io::array_value(*g, "groups", 1)) {
      const std::string path = "groups[" + std::to_string(i++) + "]";
      const std::string& name = io::string_value(v, path);
      if (name.empty() || name == "*") io::field_error(v, path, "a group needs a name (not \"\" or \"*\")");
      if (std::find(groups.begin(), groups.end(), name) != groups.end()) io::field_error(v, path, "\"" + name + "\" is listed twice");
      groups.push_back(name);
    }

  // Blocks: each entry one block, or (with "geometry") the blocks of a geometry file it takes.
  const auto& blocks = io::array_value(top.required("blocks", "the list of blocks"), "blocks", 1);
  std::map<std::string, std::size_t> by_name;  // detail::ambiguous: more than one
  std::vector<std::pair<std::size_t, double>> meshed;  // block, max edge
  std::vector<const io::JsonValue*> entry_of;  // per block, its entry in "blocks"
  std::vector<std::string> entry_path;
  std::vector<const detail::FileMaterial*> block_material;
  detail::GeometryFiles geometry_files;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::string path = "blocks[" + std::to_string(i) + "]";
    const io::JsonFields f(blocks[i], path, {"name", "group", "material", "motion", "deformable", "box", "vertices", "faces", "geometry",
                                             "objects", "planarity_tolerance"});
    const bool imported = f.has("geometry");
    static constexpr const char* shape_keys[] = {"name", "box", "vertices", "faces"};
    static constexpr const char* geometry_keys[] = {"objects", "planarity_tolerance"};
    for (const char* key : imported ? std::span<const char* const>(shape_keys) : std::span<const char* const>(geometry_keys))
      if (const auto* v = f.find(key))
        io::field_error(*v, f.path(key), imported ? "a \"geometry\" entry takes its blocks' names and shapes from the file: drop this key"
                                                  : "only with \"geometry\": a geometry file's blocks");
    const auto* group_value = f.find("group");
    const std::string given_group = f.string("group", "");
    if (group_value && (given_group.empty() || given_group == "*"))
      io::field_error(*group_value, f.path("group"), "a group needs a name (not \"\" or \"*\")");
    const auto& material_value = f.required("material", "the name of one of \"materials\"");
    const auto material = materials.find(io::string_value(material_value, f.path("material")));
    if (material == materials.end()) {
      std::vector<std::string> names;
      for (const auto& [n, v] : materials) names.push_back(n);
      io::field_error(material_value, f.path("material"), "no material \"" + material_value.as_string() + "\" (materials: " + io::join_words(names) + ")");
    }
    const auto motion = f.choice<model::Motion>("motion", model::Motion::free,
                                                {{"free", model::Motion::free}, {"fixed", model::Motion::fixed}, {"base", model::Motion::base}});
    double max_edge = 0;
    if (const auto* d = f.find("deformable")) {
      const io::JsonFields df(*d, f.path("deformable"), {"max_edge"});
      if (motion != model::Motion::free) io::field_error(*d, f.path("deformable"), "only a free block can be deformable");
      if (material->second.young == 0)
        io::field_error(*d, f.path("deformable"), "a deformable block's material needs a youngs_modulus (and a poisson_ratio, default 0)");
      max_edge = df.required_number("max_edge", {0.001, 100, false, false, "m"});
    }
    const auto add = [&](const geometry::ConvexPolyhedron& shape, const std::string& name, std::string group, const std::string& origin) {
      if (group.empty()) group = "default";
      auto g = std::find(groups.begin(), groups.end(), group);
      if (g == groups.end()) g = groups.insert(groups.end(), group);
      const std::size_t index = m.bodies.size();
      if (!by_name.emplace(name, index).second) by_name[name] = detail::ambiguous;  // referring to it by name is an error
      try {
        m.add_block(shape, material->second.density, name, static_cast<int>(g - groups.begin()), motion);
      } catch (const InvalidArgument& e) {
        io::field_error(blocks[i], path, e.what());
      }
      block_material.push_back(&material->second);
      entry_of.push_back(&blocks[i]);
      entry_path.push_back(path);
      file.block_origin.push_back(origin);
      if (max_edge > 0) meshed.emplace_back(index, max_edge);
    };
    if (imported) {
      for (const auto& b : geometry_files.take(f, base_dir)) add(b.shape, b.name, given_group.empty() ? b.group : given_group, b.origin);
    } else {
      add(detail::block_shape(f), f.string("name", "block " + std::to_string(i)), given_group, blocks[i].where());
    }
  }
  geometry_files.finish(source);
  file.geometry_issues = geometry_files.issues;
  // Meshes after all blocks (the tie ends on a deformable block go to its nodes).
  for (const auto& [b, edge] : meshed) {
    const auto* mat = block_material[b];
    try {
      m.make_deformable(b, edge, model::IsotropicElastic(mat->young, mat->poisson));
    } catch (const InvalidArgument& e) {
      io::field_error(*entry_of[b], entry_path[b] + ".deformable", e.what());
    }
  }

  // Joints: the most specific entry of a pair wins (a named pair over "*"); two entries as specific for one pair
  // are an error.
  s.laws = LawTable(groups);
  {
    const auto& joints = io::array_value(top.required("joints", "the joint law of every pair of groups that touch"), "joints", 1);
    std::vector<std::vector<int>> specificity(groups.size(), std::vector<int>(groups.size(), -1));
    std::vector<std::vector<const io::JsonValue*>> given(groups.size(), std::vector<const io::JsonValue*>(groups.size(), nullptr));
    for (std::size_t j = 0; j < joints.size(); ++j) {
      const std::string path = "joints[" + std::to_string(j) + "]";
      const io::JsonFields f(joints[j], path, {"between", "law", "preset", "contact_point_spacing", "normal_stiffness", "shear_stiffness",
                                               "tensile_strength", "cohesion", "friction_angle_deg", "friction_angle_rad",
                                               "residual_tensile_strength", "residual_cohesion", "residual_friction_angle_deg",
                                               "residual_friction_angle_rad", "compressive_strength", "residual_compressive_strength",
                                               "fracture_energy_tension", "fracture_energy_shear", "fracture_energy_compression",
                                               "cap_shear_factor", "damping_damage_limit", "unit_modulus", "mortar_modulus",
                                               "mortar_thickness", "poisson_ratio"});
      const auto& between = io::array_value(f.required("between", "two group names, [\"wall\", \"wall\"]; \"*\" for any"), f.path("between"), 2, 2);
      std::vector<std::size_t> side[2];
      for (int k = 0; k < 2; ++k) {
        const std::string& name = io::string_value(between[static_cast<std::size_t>(k)], f.path("between") + "[" + std::to_string(k) + "]");
        if (name == "*") {
          for (std::size_t g = 0; g < groups.size(); ++g) side[k].push_back(g);
          continue;
        }
        const auto g = std::find(groups.begin(), groups.end(), name);
        if (g == groups.end())
          io::field_error(between[static_cast<std::size_t>(k)], f.path("between") + "[" + std::to_string(k) + "]", "no group \"" + name + "\" (groups: " + io::join_words(groups) + ")");
        side[k].push_back(static_cast<std::size_t>(g - groups.begin()));
      }
      const int specific = (between[0].as_string() != "*") + (between[1].as_string() != "*");
      const auto law = detail::read_joint_law(f);
      const double spacing = f.number("contact_point_spacing", 0, {0, 100, false, false, "m"});
      for (const auto a : side[0])
        for (const auto b : side[1]) {
          if (given[a][b] == &joints[j]) continue;  // ["*", "*"] and ["a", "*"] meet some pairs twice
          if (specificity[a][b] == specific)
            io::field_error(joints[j], path, "a second law for the pair \"" + groups[a] + "\", \"" + groups[b] + "\" (the first at " +
                                                 given[a][b]->where() + ")");
          if (specificity[a][b] > specific) continue;
          specificity[a][b] = specificity[b][a] = specific;
          given[a][b] = given[b][a] = &joints[j];
          s.laws.set(a, b, law, spacing * spacing);
        }
    }
  }

  // Ties.
  if (const auto* ties = top.find("ties")) {
    const auto& list = io::array_value(*ties, "ties");
    for (std::size_t t = 0; t < list.size(); ++t) {
      const std::string path = "ties[" + std::to_string(t) + "]";
      const io::JsonFields f(list[t], path, {"name", "ends", "area", "youngs_modulus", "density", "pretension"});
      const auto& ends = io::array_value(f.required("ends", "two ends, [{\"block\": \"a\", \"point\": [x, y, z]}, {...}]"), f.path("ends"), 2, 2);
      model::TrussEnd end[2];
      for (std::size_t k = 0; k < 2; ++k) {
        const std::string end_path = f.path("ends") + "[" + std::to_string(k) + "]";
        const io::JsonFields e(ends[k], end_path, {"block", "point"});
        const std::size_t block = detail::block_reference(e.required("block", "a block's name or index"), e.path("block"), by_name, m.bodies.size());
        const Vec3 x = io::vec3_value(e.required("point", "[x, y, z], m"), e.path("point"));
        end[k] = m.deformable.is_deformable(block) ? m.node_end(m.nearest_node(block, x)) : m.block_end(block, x);
      }
      try {
        m.add_truss(end[0], end[1], f.required_number("area", {0, 100, true, false, "m^2"}),
                    f.required_number("youngs_modulus", {0, 1e13, true, false, "Pa"}), f.required_number("density", {0, 1e5, true, false, "kg/m^3"}),
                    f.number("pretension", 0, {0, 1e12, false, false, "N"}), f.string("name", ""));
      } catch (const InvalidArgument& e) {
        io::field_error(list[t], path, e.what());
      }
    }
  }

  // Contacts: the kinds are the study's (--contacts overrides them), the tolerance the structure's.
  if (const auto* c = top.find("contacts")) {
    const io::JsonFields f(*c, "contacts", {"kinds", "tolerance"});
    file.study.contacts = f.choice<model::ContactKinds>("kinds", model::ContactKinds::general,
                                                        {{"general", model::ContactKinds::general}, {"faces", model::ContactKinds::faces}});
    s.contacts.tolerance = f.number("tolerance", s.contacts.tolerance, {1e-7, 1, false, false, "m"});
  } else {
    file.study.contacts = model::ContactKinds::general;
  }

  // Monitor points: on a named block (its centroid, or a point given), or at a point (the block nearest to it).
  if (const auto* monitors = top.find("monitors")) {
    const auto& list = io::array_value(*monitors, "monitors");
    for (std::size_t p = 0; p < list.size(); ++p) {
      const std::string path = "monitors[" + std::to_string(p) + "]";
      const io::JsonFields f(list[p], path, {"name", "block", "point"});
      model::MonitorPoint point;
      point.name = io::string_value(f.required("name", "a name for the histories' columns"), f.path("name"));
      if (point.name.empty() || point.name.find_first_of(",\"\n") != std::string::npos)
        io::field_error(*f.find("name"), f.path("name"), "a monitor point's name must be non-empty, without commas, quotes or line breaks");
      for (std::size_t q = 0; q < s.monitors.size(); ++q)
        if (s.monitors[q].name == point.name) io::field_error(*f.find("name"), f.path("name"), "two monitor points are named \"" + point.name + "\"");
      if (const auto* block = f.find("block")) {
        point.block = detail::block_reference(*block, f.path("block"), by_name, m.bodies.size());
        point.position = f.vec3("point", m.bodies.position[point.block]);
      } else {
        point.position = io::vec3_value(f.required("point", "[x, y, z], m, or a \"block\""), f.path("point"));
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < m.bodies.size(); ++i) {
          const auto shape = m.bodies.world_shape(i);
          double d = -std::numeric_limits<double>::infinity();  // the largest signed distance to a face plane
          for (std::size_t k = 0; k < shape.faces.size(); ++k) d = std::max(d, shape.face_distance(k, point.position));
          if (d < best) {
            best = d;
            point.block = i;
          }
        }
      }
      s.monitors.push_back(point);
    }
  }

  // The table: a base block named, or the first base block.
  if (const auto* table = top.find("table")) {
    const std::size_t t = detail::block_reference(*table, "table", by_name, m.bodies.size());
    if (m.bodies.motion[t] != model::Motion::base) io::field_error(*table, "table", "the table must be a block with \"motion\": \"base\"");
    s.table = t;
  } else {
    for (std::size_t i = 0; i < m.bodies.size() && !s.table; ++i)
      if (m.bodies.motion[i] == model::Motion::base) s.table = i;
  }

  detail::read_study(top, file.study, file.scale, file.pushover, base_dir);
  return file;
}

/// Reads the model file at `path` (relative paths in it are taken relative to its folder).
inline ModelFile read_model_file(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InvalidArgument("the model file '" + path + "' is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument("cannot read the model file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_model_file(text.str(), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace blockdem::analysis
