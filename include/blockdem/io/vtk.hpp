#pragma once
// VTK XML unstructured grids (.vtu) for ParaView: blocks as polygon faces with per-block fields, contact points as
// vertices with their stresses, gap and damage. Every file is written atomically (io/atomic_file.hpp).

#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/core/types.hpp"
#include "blockdem/io/atomic_file.hpp"
#include "blockdem/model/model.hpp"

namespace blockdem::io {

namespace detail {

inline void write_points(std::ostream& out, const std::vector<Vec3>& points) {
  out << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  char buffer[96];
  for (const auto& p : points) {
    std::snprintf(buffer, sizeof buffer, "%.10g %.10g %.10g\n", p.x(), p.y(), p.z());
    out << buffer;
  }
  out << "</DataArray></Points>\n";
}

template <class T>
void write_array(std::ostream& out, const std::string& name, const std::vector<T>& values, int components = 1) {
  out << "<DataArray type=\"" << (std::is_integral_v<T> ? "Int32" : "Float64") << "\" Name=\"" << name
      << "\" NumberOfComponents=\"" << components << "\" format=\"ascii\">\n";
  for (const auto& v : values) out << v << ' ';
  out << "\n</DataArray>\n";
}

}  // namespace detail

/// Per-block cell fields: name -> one value per block.
using BlockFields = std::map<std::string, std::vector<double>>;

/// Writes every block's faces as polygons; cell data `block`, `motion` (0 free, 1 fixed, 2 base) and `fields`.
inline void write_blocks_vtu(const std::string& path, const model::Model& model, const BlockFields& fields = {}) {
  const auto& b = model.bodies;
  for (const auto& [name, values] : fields)
    if (values.size() != b.size())
      throw InvalidArgument("vtk: block field '" + name + "' has " + std::to_string(values.size()) + " values for " + std::to_string(b.size()) + " blocks");
  std::vector<Vec3> points;
  std::vector<int> connectivity, offsets, types, block, motion;
  std::map<std::string, std::vector<double>> cell_fields;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const auto shape = b.world_shape(i);
    const int first = static_cast<int>(points.size());
    points.insert(points.end(), shape.vertices.begin(), shape.vertices.end());
    for (const auto& face : shape.faces) {
      for (int v : face) connectivity.push_back(first + v);
      offsets.push_back(static_cast<int>(connectivity.size()));
      types.push_back(7);  // VTK_POLYGON
      block.push_back(static_cast<int>(i));
      motion.push_back(static_cast<int>(b.motion[i]));
      for (const auto& [name, values] : fields) cell_fields[name].push_back(values[i]);
    }
  }
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << points.size() << "\" NumberOfCells=\"" << types.size() << "\">\n";
    detail::write_points(out, points);
    out << "<Cells>\n";
    detail::write_array(out, "connectivity", connectivity);
    detail::write_array(out, "offsets", offsets);
    out << "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (int t : types) out << t << ' ';
    out << "\n</DataArray>\n</Cells>\n<CellData Scalars=\"block\">\n";
    detail::write_array(out, "block", block);
    detail::write_array(out, "motion", motion);
    for (const auto& [name, values] : cell_fields) detail::write_array(out, name, values);
    out << "</CellData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
  });
}

/// Writes points (e.g. the contact points found before a run) as vertices with per-point scalar fields (name -> one
/// value per point) and vector fields (name -> one vector per point).
inline void write_points_vtu(const std::string& path, const std::vector<Vec3>& points, const BlockFields& scalars,
                             const std::map<std::string, std::vector<Vec3>>& vectors = {}) {
  auto check = [&](const std::string& name, std::size_t size) {
    if (size != points.size())
      throw InvalidArgument("vtk: point field '" + name + "' has " + std::to_string(size) + " values for " +
                            std::to_string(points.size()) + " points");
  };
  for (const auto& [name, values] : scalars) check(name, values.size());
  for (const auto& [name, values] : vectors) check(name, values.size());
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << points.size() << "\" NumberOfCells=\"" << points.size() << "\">\n";
    detail::write_points(out, points);
    std::vector<int> connectivity(points.size()), offsets(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      connectivity[i] = static_cast<int>(i);
      offsets[i] = static_cast<int>(i + 1);
    }
    out << "<Cells>\n";
    detail::write_array(out, "connectivity", connectivity);
    detail::write_array(out, "offsets", offsets);
    out << "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < points.size(); ++i) out << "1 ";  // VTK_VERTEX
    out << "\n</DataArray>\n</Cells>\n<PointData>\n";
    for (const auto& [name, values] : scalars) detail::write_array(out, name, values);
    for (const auto& [name, values] : vectors) {
      std::vector<double> flat;
      for (const auto& v : values) flat.insert(flat.end(), {v.x(), v.y(), v.z()});
      detail::write_array(out, name, flat, 3);
    }
    out << "</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
  });
}

/// Writes the tetrahedra of the deformable blocks (VTK_TETRA) with the point fields `density_scaling_factor`
/// (dsf = m_scaled / m_real, paper Fig. 7), `displacement` (m, from `reference` if given) and `block`, and the cell
/// fields `stress` (Pa, xx yy zz xy yz zx) and `mean_stress`.
inline void write_tetrahedra_vtu(const std::string& path, const model::Model& model, const std::vector<Vec3>& reference = {}) {
  const auto& nd = model.deformable.nodes;
  const auto& te = model.deformable.tetrahedra;
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << nd.size() << "\" NumberOfCells=\"" << te.size() << "\">\n";
    detail::write_points(out, nd.position);
    std::vector<int> connectivity, offsets;
    for (std::size_t t = 0; t < te.size(); ++t) {
      for (auto n : te.node[t]) connectivity.push_back(static_cast<int>(n));
      offsets.push_back(static_cast<int>(4 * (t + 1)));
    }
    out << "<Cells>\n";
    detail::write_array(out, "connectivity", connectivity);
    detail::write_array(out, "offsets", offsets);
    out << "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t t = 0; t < te.size(); ++t) out << "10 ";  // VTK_TETRA
    out << "\n</DataArray>\n</Cells>\n<PointData Scalars=\"density_scaling_factor\">\n";
    std::vector<double> dsf(nd.size()), displacement;
    std::vector<int> block(nd.size());
    for (std::size_t i = 0; i < nd.size(); ++i) {
      dsf[i] = nd.density_scaling_factor(i);
      block[i] = static_cast<int>(nd.block[i]);
    }
    detail::write_array(out, "density_scaling_factor", dsf);
    detail::write_array(out, "block", block);
    if (reference.size() == nd.size()) {
      for (std::size_t i = 0; i < nd.size(); ++i) {
        const Vec3 u = nd.position[i] - reference[i];
        displacement.insert(displacement.end(), {u.x(), u.y(), u.z()});
      }
      detail::write_array(out, "displacement", displacement, 3);
    }
    out << "</PointData>\n<CellData>\n";
    std::vector<double> stress, mean;
    for (const auto& s : te.stress) {
      stress.insert(stress.end(), s.begin(), s.end());
      mean.push_back((s[0] + s[1] + s[2]) / 3.0);
    }
    detail::write_array(out, "stress", stress, 6);
    detail::write_array(out, "mean_stress", mean);
    out << "</CellData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
  });
}

/// Writes contact points as vertices with normal_stress, shear_stress (Pa), gap (m), area (m^2), damage,
/// never_bonded and the normal, plus `extra` fields (one value per point): visit(f) calls f(view) for each point
/// (a ContactView: integrate/contact_view.hpp).
template <class Visit>
void write_contact_points_vtu(const std::string& path, Visit&& visit, BlockFields extra = {}) {
  std::vector<Vec3> points, normal;
  BlockFields fields = std::move(extra);
  for (const char* name : {"normal_stress", "shear_stress", "gap", "area", "damage", "never_bonded"}) fields[name];
  visit([&](const auto& c) {
    points.push_back(c.position);
    normal.push_back(c.normal);
    fields["normal_stress"].push_back(c.normal_stress);
    fields["shear_stress"].push_back(c.shear_stress);
    fields["gap"].push_back(c.gap);
    fields["area"].push_back(c.area);
    fields["damage"].push_back(c.damage);
    fields["never_bonded"].push_back(c.never_bonded ? 1.0 : 0.0);
  });
  write_points_vtu(path, points, fields, {{"normal", normal}});
}

/// Writes the contact points of a simulation (write_contact_points_vtu).
template <class Simulation>
void write_contacts_vtu(const std::string& path, const Simulation& simulation) {
  write_contact_points_vtu(path, [&](auto&& f) { simulation.visit_contacts(f); });
}

}  // namespace blockdem::io
