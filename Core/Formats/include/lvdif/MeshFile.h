// Triangle mesh files: OBJ, OFF, STL (ASCII and binary) and PLY (ASCII,
// binary little- and big-endian), read into lvdif::TriangleMesh with every
// count and index validated: an index out of range (or negative where the
// format has no relative indices), a face of fewer than three vertices, a NaN
// or infinite coordinate, a count larger than the file could hold, or a file
// without triangles is one clear Error (ParseError for text, CorruptData for
// binary layouts) naming the format, the line or element, and the problem.
// Polygons are split into triangles (triangulatePolygon: linear, local); STL's separate corners are merged
// into shared points when bit-identical. Written for this project (no
// OpenMesh: the readers stay in the dependency-free core, can be fuzzed, and
// check what OpenMesh's readers skip with a warning).
#pragma once

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "lvdif/TriangleMesh.h"

#include <cstdint>
#include <string>

namespace lvdif
{

/// Most corners a face (polygon) of a mesh file may have; a larger face is
/// refused with its place and corner count before its triangles are made.
/// Polygons are triangulated as if convex and planar, and a face of 10^6
/// corners took 204 s and 1.37 GB through mesh to SDF: a face that large is an
/// exporter's outline or damage, not a polygon (docs/FORMAT.md, "Mesh files").
constexpr std::int64_t MaxPolygonCorners = 65536;

enum class MeshFormat
{
  Auto, // from the file name's extension
  Obj,
  Off,
  Stl,
  Ply
};

/// The format of a file name's extension (case-insensitive); Error(InvalidArgument) if unknown.
MeshFormat meshFormatFromName(const std::string& path);

/// Reads a mesh from any source; `name` is used for Auto and in messages.
TriangleMesh readMesh(ByteSource& source, MeshFormat format, const std::string& name = std::string());
TriangleMesh loadMesh(const std::string& path, MeshFormat format = MeshFormat::Auto);

} // namespace lvdif
