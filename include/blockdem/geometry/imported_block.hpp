#pragma once
// A block as a geometry file gives it (Wavefront OBJ, a 3DEC deck, a COMPAS assembly: io/*_geometry.hpp): a name,
// vertices and faces as listed, not yet checked. geometry/polyhedron_check.hpp says what in it cannot be used and turns
// what can into a ConvexPolyhedron; the readers only refuse what they cannot parse.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "blockdem/core/types.hpp"
#include "blockdem/geometry/convex_polyhedron.hpp"

namespace blockdem::geometry {

struct ImportedBlock {
  std::string name;    // the file's object or block name ("" if it gave none: the reader names it after its place)
  std::string group;   // the file's group, layer or 3DEC group ("" none)
  std::vector<Vec3> vertices;            // m
  std::vector<std::vector<int>> faces;   // indices into vertices, in the file's order (3DEC's clockwise faces turned)
  std::string origin;  // where it starts, for messages: "blocks.obj:12"
};

/// The block of a convex polyhedron (faces counter-clockwise seen from outside), for the writers.
inline ImportedBlock imported_block(const ConvexPolyhedron& p, std::string name, std::string group = "") {
  return {std::move(name), std::move(group), p.vertices, p.faces, ""};
}

/// Adds the face given by its corners' coordinates (a 3DEC deck, a file without shared vertices) to `block`, reusing
/// a vertex within `weld` (m) of a corner instead of adding it again, so that faces share their edges' ends.
inline void add_face_by_corners(ImportedBlock& block, const std::vector<Vec3>& corners, double weld) {
  std::vector<int> face;
  for (const auto& c : corners) {
    int index = -1;
    for (std::size_t i = 0; i < block.vertices.size() && index < 0; ++i)
      if ((block.vertices[i] - c).norm() <= weld) index = static_cast<int>(i);
    if (index < 0) {
      index = static_cast<int>(block.vertices.size());
      block.vertices.push_back(c);
    }
    if (face.empty() || face.back() != index) face.push_back(index);
  }
  if (face.size() > 1 && face.front() == face.back()) face.pop_back();  // a face closed by repeating its first corner
  block.faces.push_back(std::move(face));
}

}  // namespace blockdem::geometry
