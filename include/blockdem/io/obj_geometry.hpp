#pragma once
// Wavefront OBJ, as Rhino, Blender and COMPAS export meshes: one block per object (`o`), or per group (`g`) in a file
// without objects, or per connected set of faces in a file with neither. With objects, `g` names the block's group (a
// Rhino layer). Vertices (`v`, global to the file, 1-based or negative from the end) and faces (`f`, with or without
// texture and normal indices) are read; texture coordinates, normals, materials, smoothing, lines and points are
// skipped. What is wrong with a block's shape is for geometry/polyhedron_check.hpp to say.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <map>
#include <numeric>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/geometry/imported_block.hpp"
#include "blockdem/io/json.hpp"

namespace blockdem::io {

namespace detail {

inline std::string_view obj_trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

inline std::vector<std::string_view> obj_words(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != '\r') ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

}  // namespace detail

/// The blocks of an OBJ file's text; `source` names it in messages and in each block's origin ("walls.obj:12").
/// Throws InputError naming the line for what cannot be parsed: a coordinate that is not a finite number, a face
/// with fewer than 3 corners or a corner that refers to no vertex.
inline std::vector<geometry::ImportedBlock> read_obj(std::string_view text, const std::string& source) {
  struct Face {
    std::vector<std::size_t> corners;  // 0-based into the file's vertices
    std::size_t block;
  };
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::vector<geometry::ImportedBlock> blocks;  // vertices empty until the end
  bool has_objects = false;
  std::string group;
  // Objects decide the blocks when there are any: a first pass finds out.
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const auto line = detail::obj_trim(text.substr(at, end - at));
    if (line.size() > 1 && line[0] == 'o' && (line[1] == ' ' || line[1] == '\t')) has_objects = true;
    at = end + 1;
  }
  std::size_t current = static_cast<std::size_t>(-1);
  auto start_block = [&](std::string name, std::size_t line_number) {
    blocks.push_back({std::move(name), has_objects ? group : std::string(), {}, {}, source + ":" + std::to_string(line_number)});
    current = blocks.size() - 1;
  };
  std::string pending;  // a line continued with a backslash
  std::size_t line_number = 0, pending_line = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    ++line_number;
    std::string_view raw = detail::obj_trim(text.substr(at, end - at));
    at = end + 1;
    if (!raw.empty() && raw.back() == '\\') {
      if (pending.empty()) pending_line = line_number;
      pending.append(raw.substr(0, raw.size() - 1)).push_back(' ');
      continue;
    }
    std::string joined;
    std::size_t here = line_number;
    if (!pending.empty()) {
      joined = pending + std::string(raw);
      pending.clear();
      raw = joined;
      here = pending_line;
    }
    if (const auto hash = raw.find('#'); hash != std::string_view::npos) raw = raw.substr(0, hash);
    const auto words = detail::obj_words(raw);
    if (words.empty()) continue;
    const auto where = [&] { return source + ":" + std::to_string(here) + ": "; };
    const auto rest_name = [&] {  // what follows the keyword, as one name
      const auto k = raw.find(words[0]) + words[0].size();
      return std::string(detail::obj_trim(raw.substr(k)));
    };
    const std::string_view key = words[0];
    if (key == "v") {
      if (words.size() < 4) throw InputError(where() + "a vertex needs three coordinates (v x y z), got " + std::to_string(words.size() - 1));
      Vec3 x;
      for (int k = 0; k < 3; ++k) {
        const auto w = words[static_cast<std::size_t>(k) + 1];
        double value = 0;
        const auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
        if (ec != std::errc() || ptr != w.data() + w.size() || !std::isfinite(value))
          throw InputError(where() + "vertex coordinate '" + std::string(w) + "' is not a finite number");
        x[k] = value;
      }
      vertices.push_back(x);
    } else if (key == "f") {
      if (words.size() < 4) throw InputError(where() + "a face needs at least 3 corners (f a b c ...), got " + std::to_string(words.size() - 1));
      Face face;
      for (std::size_t k = 1; k < words.size(); ++k) {
        const auto w = words[k].substr(0, words[k].find('/'));  // v, v/vt, v//vn, v/vt/vn
        long long index = 0;
        const auto [ptr, ec] = std::from_chars(w.data(), w.data() + w.size(), index);
        if (ec != std::errc() || ptr != w.data() + w.size() || index == 0)
          throw InputError(where() + "face corner '" + std::string(words[k]) + "' is not a vertex number (1, 2, ... or -1 for the last)");
        const long long count = static_cast<long long>(vertices.size());
        const long long zero_based = index > 0 ? index - 1 : count + index;
        if (zero_based < 0 || zero_based >= count)
          throw InputError(where() + "face corner " + std::to_string(index) + " refers to no vertex (" + std::to_string(count) +
                           " vertices so far: faces may refer only to vertices listed before them)");
        face.corners.push_back(static_cast<std::size_t>(zero_based));
      }
      if (current == static_cast<std::size_t>(-1)) start_block("", here);
      face.block = current;
      faces.push_back(std::move(face));
    } else if (key == "o") {
      start_block(rest_name(), here);
    } else if (key == "g") {
      if (has_objects) {
        group = rest_name();  // the group of the blocks that follow, and of the current one while it has no face
        if (current != static_cast<std::size_t>(-1) && (faces.empty() || faces.back().block != current)) blocks[current].group = group;
      } else {
        start_block(rest_name(), here);
      }
    }
    // vt, vn, vp, s, usemtl, mtllib, l, p, cstype ...: nothing a block needs.
  }
  if (!pending.empty()) throw InputError(source + ":" + std::to_string(pending_line) + ": the file ends in a line continued with '\\'");

  // Without objects or groups: one block per connected set of faces (faces sharing a vertex).
  if (blocks.size() == 1 && blocks[0].name.empty() && !faces.empty()) {
    std::vector<std::size_t> parent(vertices.size());
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    auto find = [&](std::size_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const auto& f : faces)
      for (auto c : f.corners) parent[find(c)] = find(f.corners.front());
    std::map<std::size_t, std::size_t> block_of_root;
    const std::string origin = blocks[0].origin;
    blocks.clear();
    for (auto& f : faces) {
      const auto root = find(f.corners.front());
      auto [it, added] = block_of_root.emplace(root, blocks.size());
      if (added) blocks.push_back({"block " + std::to_string(blocks.size() + 1), "", {}, {}, origin});
      f.block = it->second;
    }
  }
  // Each block's vertices: those its faces use, in the file's order.
  std::vector<std::vector<std::size_t>> used(blocks.size());
  for (const auto& f : faces) used[f.block].insert(used[f.block].end(), f.corners.begin(), f.corners.end());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    auto& u = used[b];
    std::sort(u.begin(), u.end());
    u.erase(std::unique(u.begin(), u.end()), u.end());
    for (auto c : u) blocks[b].vertices.push_back(vertices[c]);
  }
  for (const auto& f : faces) {
    const auto& u = used[f.block];
    std::vector<int> face;
    for (auto c : f.corners) face.push_back(static_cast<int>(std::lower_bound(u.begin(), u.end(), c) - u.begin()));
    blocks[f.block].faces.push_back(std::move(face));
  }
  std::vector<geometry::ImportedBlock> out;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (blocks[i].faces.empty()) continue;  // an object with lines or points only, or an empty group
    if (blocks[i].name.empty()) blocks[i].name = "block " + std::to_string(out.size() + 1);
    out.push_back(std::move(blocks[i]));
  }
  return out;
}

/// Writes `blocks` as OBJ: `o` per block, `g` with its group, its vertices (shortest text that reads back exactly)
/// and faces (1-based, in the block's winding: counter-clockwise seen from outside for the library's polyhedra).
inline void write_obj(std::ostream& out, const std::vector<geometry::ImportedBlock>& blocks, std::string_view title) {
  out << "# " << title << "\n# blockdem blocks: one object per block, metres\n";
  std::size_t base = 1;
  for (const auto& b : blocks) {
    if (b.name.find_first_of("\n\r") != std::string::npos) throw InvalidArgument("OBJ: block name with a line break: '" + b.name + "'");
    out << "o " << b.name << "\n";
    if (!b.group.empty()) out << "g " << b.group << "\n";
    for (const auto& v : b.vertices)
      out << "v " << JsonObject::number(v.x()) << ' ' << JsonObject::number(v.y()) << ' ' << JsonObject::number(v.z()) << "\n";
    for (const auto& f : b.faces) {
      out << "f";
      for (int k : f) out << ' ' << base + static_cast<std::size_t>(k);
      out << "\n";
    }
    base += b.vertices.size();
  }
}

}  // namespace blockdem::io
