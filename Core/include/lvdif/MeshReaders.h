// Triangle mesh readers with strict validation: PLY (ascii, binary little
// and big endian) and OFF. Polygons are fan-triangulated. Every count is
// checked against the file size before allocating, every index against the
// vertex count, every coordinate for NaN/infinity; a bad file gives
// Error(CorruptData) naming the file, the element and the problem.
#pragma once

#include "lvdif/TriangleMesh.h"

#include <string>

namespace lvdif
{

/// By extension (.ply, .off; case-insensitive). Throws IoFailure, CorruptData, Unsupported.
TriangleMesh readMesh(const std::string& path);
TriangleMesh readPly(const std::string& path);
TriangleMesh readOff(const std::string& path);

} // namespace lvdif
