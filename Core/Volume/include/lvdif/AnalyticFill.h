// Filling a dictionary volume from an analytic signed distance function, chunk
// by chunk. Because a true SDF is 1-Lipschitz, one evaluation at a chunk's
// centre decides whether the whole chunk lies beyond the band (then it is
// stored as one uniform value and never expanded); only chunks near the
// surface are evaluated voxel by voxel. A 1024^3 sphere thus never needs
// 4 GiB.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <functional>

namespace lvdif
{

/// Signed distance in voxel units at voxel coordinates (x, y, z); negative inside.
using SdfFunction = std::function<float(double x, double y, double z)>;

/// Writes f into every voxel (band-clamped); colour key set to `color`.
/// f must be 1-Lipschitz for the chunk culling to be exact.
void fillFromFunction(DictionaryVolume& volume, const SdfFunction& f, ColorKey color = 0,
  Interrupter& interrupter = nullInterrupter());

/// The SDF of a sphere (voxel units), for tests, benchmarks and demos.
SdfFunction sphereSdf(double cx, double cy, double cz, double radius);

} // namespace lvdif
