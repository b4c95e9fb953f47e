#pragma once
// A geometry file of any format blockdem reads, by its extension: Wavefront OBJ (.obj), a 3DEC deck (.3ddat, .dat,
// .txt) or a COMPAS assembly or mesh (.json); and the writers of the first two.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "blockdem/core/error.hpp"
#include "blockdem/geometry/imported_block.hpp"
#include "blockdem/io/compas_geometry.hpp"
#include "blockdem/io/obj_geometry.hpp"
#include "blockdem/io/threedec_geometry.hpp"

namespace blockdem::io {

enum class GeometryFormat { obj, threedec, compas };

inline const char* geometry_extensions() { return ".obj (Wavefront OBJ), .3ddat, .dat or .txt (3DEC deck), .json (COMPAS)"; }

/// The format of a geometry file named `path`; throws InvalidArgument naming the extensions known.
inline GeometryFormat geometry_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return GeometryFormat::obj;
  if (ext == ".3ddat" || ext == ".dat" || ext == ".txt") return GeometryFormat::threedec;
  if (ext == ".json") return GeometryFormat::compas;
  throw InvalidArgument("'" + path + "': not a geometry file blockdem reads; it reads " + geometry_extensions());
}

inline bool is_geometry_file(const std::string& path) {
  try {
    (void)geometry_format(path);
    return true;
  } catch (const InvalidArgument&) {
    return false;
  }
}

/// The blocks of a geometry file's text in the given format; `source` names it in messages.
inline std::vector<geometry::ImportedBlock> parse_geometry(std::string_view text, GeometryFormat format, const std::string& source) {
  switch (format) {
    case GeometryFormat::obj: return read_obj(text, source);
    case GeometryFormat::threedec: return read_threedec_deck(text, source).blocks;
    case GeometryFormat::compas: return read_compas_json(text, source);
  }
  return {};
}

/// The blocks of the geometry file at `path`, in the format its extension names.
inline std::vector<geometry::ImportedBlock> read_geometry_file(const std::string& path) {
  const auto format = geometry_format(path);
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InvalidArgument("the geometry file '" + path + "' is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument("cannot read the geometry file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_geometry(text.str(), format, path);
}

/// Writes `blocks` to `path` in the format its extension names (OBJ or a 3DEC deck).
inline void write_geometry_file(const std::string& path, const std::vector<geometry::ImportedBlock>& blocks, std::string_view title) {
  const auto format = geometry_format(path);
  if (format == GeometryFormat::compas) throw InvalidArgument("'" + path + "': blockdem writes .obj and 3DEC decks (.3ddat), not COMPAS JSON");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InvalidArgument("cannot write '" + path + "'");
  if (format == GeometryFormat::obj)
    write_obj(out, blocks, title);
  else
    write_threedec_deck(out, blocks, title);
  if (!out) throw InvalidArgument("could not write all of '" + path + "'");
}

}  // namespace blockdem::io
