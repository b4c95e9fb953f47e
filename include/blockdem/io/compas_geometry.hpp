#pragma once
// COMPAS JSON: meshes (compas.datastructures/Mesh) and compas_assembly assemblies of blocks, as COMPAS 1.x and 2.x
// write them, read as ImportedBlocks: every mesh in the document, in document order.

#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/geometry/imported_block.hpp"
#include "blockdem/io/json_fields.hpp"
#include "blockdem/io/json_reader.hpp"

namespace blockdem::io {

namespace detail {

/// The walk through a COMPAS document: the path to the current value (keys and indices, as text only for messages)
/// and the blocks found.
class CompasWalk {
 public:
  explicit CompasWalk(const std::string& source) : source_(source) {}

  std::vector<geometry::ImportedBlock> blocks;

  // `node`: the key of the graph node the value lies in (nullptr: none); `wrapper_name`: the "name" of the
  // {"dtype", "data", "name"} object whose data this value is (COMPAS 2.x keeps a name there).
  void walk(const JsonValue& v, const std::string* node, const JsonValue* wrapper_name, bool in_node_map) {
    if (v.is_array()) {
      const auto& items = v.as_array();
      for (std::size_t i = 0; i < items.size(); ++i) {
        path_.push_back({nullptr, i});
        walk(items[i], node, nullptr, false);
        path_.pop_back();
      }
      return;
    }
    if (!v.is_object()) return;
    const JsonValue* vertex = v.find("vertex");
    const JsonValue* face = v.find("face");
    if (vertex && face) return read_mesh(v, *vertex, *face, node, wrapper_name);
    const JsonValue* name = v.find("name");
    for (const auto& [key, child] : v.as_object()) {
      path_.push_back({&key, 0});
      const bool data = key == "data" || key == "value";
      walk(child, in_node_map ? &key : node, data ? name : nullptr, key == "node");
      path_.pop_back();
    }
  }

 private:
  struct Step {
    const std::string* key;  // nullptr: an index into an array
    std::size_t index;
  };

  std::string path(std::string_view tail = {}) const {
    std::string s;
    for (const auto& step : path_) {
      if (step.key) (s += s.empty() ? "" : ".") += *step.key;
      else ((s += '[') += std::to_string(step.index)) += ']';
    }
    if (!tail.empty()) (s += s.empty() || tail.front() == '[' ? "" : ".") += tail;
    return s;
  }

  // COMPAS names every mesh after its class unless told otherwise: such a name says nothing about the block.
  static bool is_given_name(const JsonValue* v) {
    return v && v->is_string() && !v->as_string().empty() && v->as_string() != "Mesh" && v->as_string() != "Block";
  }

  // A face's vertex: a key as the "vertex" object has it (a string), or the integer COMPAS writes for it.
  static bool key_text(const JsonValue& v, std::string& out) {
    if (v.is_string()) {
      out = v.as_string();
      return true;
    }
    if (!v.is_number()) return false;
    const double x = v.as_number();
    if (!(std::abs(x) < 1e15) || x != std::floor(x)) return false;
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, static_cast<long long>(x)).ptr;
    out.assign(buffer, end);
    return true;
  }

  // Paths are put together only for a message: a long key above a large mesh would cost its length per vertex.
  void read_mesh(const JsonValue& mesh, const JsonValue& vertex, const JsonValue& face, const std::string* node, const JsonValue* wrapper_name) {
    if (!vertex.is_object())
      field_error(vertex, path("vertex"), std::string("expected an object of vertices {\"0\": {\"x\": 0, \"y\": 0, \"z\": 0}, ...}, got ") +
                                              JsonValue::kind_name(vertex.kind()));
    if (!face.is_object())
      field_error(face, path("face"), std::string("expected an object of faces {\"0\": [0, 1, 2, 3], ...}, got ") + JsonValue::kind_name(face.kind()));
    geometry::ImportedBlock block;
    const JsonValue* attributes = mesh.find("attributes");
    if (attributes && attributes->is_object() && is_given_name(attributes->find("name"))) block.name = attributes->find("name")->as_string();
    else if (is_given_name(mesh.find("name"))) block.name = mesh.find("name")->as_string();
    else if (is_given_name(wrapper_name)) block.name = wrapper_name->as_string();
    else if (node) block.name = "node " + *node;
    else block.name = "block " + std::to_string(blocks.size() + 1);
    block.origin = source_ + ":" + std::to_string(mesh.line());

    // Coordinates a vertex leaves out take the mesh's defaults (COMPAS 2.x "default_vertex_attributes", 1.x "dva").
    const JsonValue* defaults = mesh.find("default_vertex_attributes");
    if (!defaults) defaults = mesh.find("dva");
    std::unordered_map<std::string_view, int> index;
    for (const auto& [key, v] : vertex.as_object()) {
      const auto at = [&, &key = key] { return path("vertex." + key); };
      if (!v.is_object())
        field_error(v, at(), std::string("expected a vertex {\"x\": 0, \"y\": 0, \"z\": 0}, got ") + JsonValue::kind_name(v.kind()));
      Vec3 x;
      for (int k = 0; k < 3; ++k) {
        const std::string_view name = std::string_view("xyz").substr(static_cast<std::size_t>(k), 1);
        const JsonValue* c = v.find(name);
        if (!c && defaults && defaults->is_object() && defaults->find(name) && defaults->find(name)->is_number()) c = defaults->find(name);
        if (!c) field_error(v, at(), "no \"" + std::string(name) + "\" coordinate (a vertex is {\"x\": 0, \"y\": 0, \"z\": 0})");
        x[k] = c->is_number() ? c->as_number() : number_value(*c, at() + "." + std::string(name), Range::any("m"));
      }
      index.emplace(key, static_cast<int>(block.vertices.size()));
      block.vertices.push_back(x);
    }
    std::string text;
    for (const auto& [key, corners] : face.as_object()) {
      const auto at = [&, &key = key] { return path("face." + key); };
      if (!corners.is_array() || corners.as_array().size() < 3)
        field_error(corners, at(), corners.is_array() ? "a face with " + std::to_string(corners.as_array().size()) + " vertices (a face needs at least 3)"
                                                      : std::string("expected a list of vertex keys [0, 1, 2, ...], got ") + JsonValue::kind_name(corners.kind()));
      const auto& list = corners.as_array();
      std::vector<int> f;
      for (std::size_t i = 0; i < list.size(); ++i) {
        const auto item = [&] { return at() + "[" + std::to_string(i) + "]"; };
        if (!key_text(list[i], text))
          field_error(list[i], item(), std::string("expected a vertex key (an integer or a string), got ") +
                                           (list[i].is_number() ? "the number " + num(list[i].as_number()) : JsonValue::kind_name(list[i].kind())));
        const auto it = index.find(text);
        if (it == index.end()) {
          if (text.size() > 40) text = text.substr(0, 40) + "...";
          field_error(list[i], item(), "no vertex \"" + text + "\" in this mesh (its vertices: the keys of " + path("vertex") + ")");
        }
        f.push_back(it->second);
      }
      block.faces.push_back(std::move(f));
    }
    blocks.push_back(std::move(block));
  }

  const std::string& source_;
  std::vector<Step> path_;
};

}  // namespace detail

/// The blocks of a COMPAS JSON text; `source` names it in messages and in each block's origin ("arch.json:12", where
/// the mesh's object starts). Every object with both a "vertex" object ({"<key>": {"x": .., "y": .., "z": ..}}) and a
/// "face" object ({"<key>": [vertex keys ...]}) is a block, found wherever it lies: a bare mesh, a
/// {"dtype": "compas.datastructures/Mesh", "data" (2.x) or "value" (1.x): mesh}, an assembly
/// (data.graph.node.<key>.block, or data.node.<key>.block in older compas_assembly files) or an array of these.
/// Vertices in the file's order; faces in the file's order and winding (COMPAS: counter-clockwise seen from outside).
/// A block's name: its mesh's attributes.name, else the "name" beside its data (2.x), else "node <key>" after the
/// assembly's node it lies in, else "block N"; COMPAS's default names "Mesh" and "Block" count as none. A coordinate
/// a vertex leaves out is the mesh's default ("default_vertex_attributes", "dva"). Throws InvalidArgument naming
/// source:line:column and the value's path (data.graph.node.3.block.face.7[2]: no vertex "12" in this mesh) for
/// malformed JSON, a coordinate that is not a number, a face with fewer than 3 vertices or a key no vertex has, and
/// for a document with no mesh.
inline std::vector<geometry::ImportedBlock> read_compas_json(std::string_view text, const std::string& source) {
  const JsonValue root = parse_json(text, source);
  detail::CompasWalk walk(source);
  walk.walk(root, nullptr, nullptr, false);
  if (walk.blocks.empty())
    throw InvalidArgument(root.where() + ": no COMPAS mesh in the file (expected an object with \"vertex\" and \"face\" objects: a "
                                         "compas.datastructures/Mesh, a compas_assembly Assembly of blocks or an array of meshes)");
  return std::move(walk.blocks);
}

}  // namespace blockdem::io
