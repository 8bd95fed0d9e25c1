// Brushes and CSG on the dictionary volume (paper Sect. 3.4, Fig. 7).
//
// A dab is one primitive (sphere, cube, or a capsule for stroke segments)
// placed in voxel coordinates; the primitive SDFs are Quilez's
// (https://iquilezles.org/articles/distfunctions/). Applying a dab combines
// the primitive's distance s with the stored distance d:
//
//   Add       d' = min(d, s)          (union; smooth: d' = smin(d, s, k))
//   Subtract  d' = max(d, -s)         (subtraction; smooth: d' = smax(d, -s, k))
//   Paint     d' = d, bit-identical   (colour only)
//
// smin is Quilez's polynomial smooth minimum: h = max(k - |a - b|, 0) / k,
// smin = min(a, b) - h*h*k/4; smax(a, b, k) = -smin(-a, -b, k). k = 0 is the
// paper's hard CSG. Every written distance goes through volume.encode(), so
// it saturates to +-band like every other write.
//
// Colour (the exact rule):
//   Add       colour := brush colour where s <= colorOffset (the original's
//             rule: the primitive's inside plus a 1.5-voxel skin, written even
//             where the geometry does not change, so a smaller add inside a
//             body recolours its interior, as the dice demo needs); with a
//             blend k > 0 also where the smooth result changed the distance
//             and d' <= colorOffset (the fillet).
//   Subtract  colour unchanged (as the original: a cut exposes the colour the
//             interior already has).
//   Paint     colour := brush colour where s <= 0 and |d| <= colorOffset: the
//             skin of the surface inside the brush, nothing deeper.
//
// Only chunks that intersect the dab's influence box are visited; a voxel is
// written only when its 4 bytes change, so exactly the chunks with a changed
// voxel are marked dirty (DictionaryVolume::set marks them), and chunks left
// all-equal by the edit are collapsed back to uniform. Chunks are processed
// in parallel (OpenMP), each by one thread; a list of dabs is applied per
// voxel in list order, which is bit-identical to applying them one by one.
#pragma once

#include "lvdif/HostDevice.h"

#include "lvdif/DictionaryVolume.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

// The primitive functions below also compile as CUDA device code (Brush.cu).

namespace lvdif
{

enum class BrushShape : int
{
  Sphere = 0,
  Cube = 1,
  Capsule = 2
};

enum class BrushOp : int
{
  Add = 0,
  Subtract = 1,
  Paint = 2
};

const char* toString(BrushShape s);
const char* toString(BrushOp op);

/// One placed primitive, in voxel coordinates.
struct Dab
{
  BrushShape shape = BrushShape::Sphere;
  std::array<double, 3> center{ 0, 0, 0 };
  /// Sphere radius, cube HALF edge, capsule radius (voxels, > 0; <= 0 is skipped).
  double radius = 1.0;
  /// Second end point of a capsule (ignored otherwise).
  std::array<double, 3> end{ 0, 0, 0 };
};

struct BrushSettings
{
  BrushOp op = BrushOp::Add;
  Rgba color{ 255, 255, 255, 255 };
  /// Smooth blend radius k in voxels (0 = hard CSG).
  double blend = 0.0;
  /// Skin thickness (voxels) that gets the colour; the original uses 1.5.
  double colorOffset = 1.5;
  /// Edge rounding of cube dabs (Quilez's round box: box(h - r) - r), 0..half edge.
  double rounding = 0.0;
};

// ---- primitive SDFs (voxel units, negative inside) ---------------------------

LVDIF_HD double sphereDistance(double px, double py, double pz, double r)
{
  return std::sqrt(px * px + py * py + pz * pz) - r;
}

/// Quilez's box with half extent h on every axis.
LVDIF_HD double cubeDistance(double px, double py, double pz, double h)
{
  const double ux = std::fabs(px) - h, uy = std::fabs(py) - h, uz = std::fabs(pz) - h;
  const double mx = ux > 0 ? ux : 0, my = uy > 0 ? uy : 0, mz = uz > 0 ? uz : 0;
  const double outside = std::sqrt(mx * mx + my * my + mz * mz);
  double m = ux > uy ? ux : uy;
  m = m > uz ? m : uz;
  return outside + (m < 0 ? m : 0);
}

/// Quilez's box with half extents (hx, hy, hz).
LVDIF_HD double cubeDistanceBox(double px, double py, double pz, double hx, double hy, double hz)
{
  const double ux = std::fabs(px) - hx, uy = std::fabs(py) - hy, uz = std::fabs(pz) - hz;
  const double mx = ux > 0 ? ux : 0, my = uy > 0 ? uy : 0, mz = uz > 0 ? uz : 0;
  double m = ux > uy ? ux : uy;
  m = m > uz ? m : uz;
  return std::sqrt(mx * mx + my * my + mz * mz) + (m < 0 ? m : 0);
}

/// Quilez's capsule from a to b (p relative to a, ba = b - a).
LVDIF_HD double capsuleDistance(double px, double py, double pz, double bax, double bay, double baz, double r)
{
  const double bb = bax * bax + bay * bay + baz * baz;
  double t = bb > 0 ? (px * bax + py * bay + pz * baz) / bb : 0.0;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  const double qx = px - t * bax, qy = py - t * bay, qz = pz - t * baz;
  return std::sqrt(qx * qx + qy * qy + qz * qz) - r;
}

/// The dab's signed distance at voxel (x, y, z); `rounding` rounds cube edges.
LVDIF_HD double dabDistance(const Dab& d, double x, double y, double z, double rounding = 0.0)
{
  const double px = x - d.center[0], py = y - d.center[1], pz = z - d.center[2];
  switch (d.shape)
  {
    case BrushShape::Cube:
    {
      const double r = rounding < d.radius ? rounding : d.radius;
      return r > 0 ? cubeDistance(px, py, pz, d.radius - r) - r : cubeDistance(px, py, pz, d.radius);
    }
    case BrushShape::Capsule:
      return capsuleDistance(px, py, pz, d.end[0] - d.center[0], d.end[1] - d.center[1], d.end[2] - d.center[2], d.radius);
    default:
      return sphereDistance(px, py, pz, d.radius);
  }
}

/// Quilez's polynomial smooth minimum (k > 0).
LVDIF_HD double smoothMin(double a, double b, double k)
{
  const double diff = a > b ? a - b : b - a;
  const double h = (k - diff > 0 ? k - diff : 0) / k;
  return (a < b ? a : b) - h * h * k * 0.25;
}

/// The voxels whose value or colour this dab may change (not clipped to the volume):
/// the primitive's bounding box grown by the band (Add/Subtract) or by nothing (Paint),
/// plus the colour skin and the blend radius.
VoxelBox dabInfluenceBox(const DictionaryVolume& volume, const Dab& dab, const BrushSettings& settings);

/// Told before the first write into a chunk during one apply call (from the thread that
/// owns the chunk; different chunks may call concurrently). The undo stack uses it to
/// snapshot the chunk (copy-on-write).
class ChunkWriteObserver
{
public:
  virtual ~ChunkWriteObserver() = default;
  virtual void beforeChunkWrite(const DictionaryVolume& volume, std::int64_t chunkId) = 0;
};

struct EditResult
{
  std::int64_t changedVoxels = 0;
  /// Chunks with at least one changed voxel, increasing ids.
  std::vector<std::int64_t> changedChunks;
  /// A box holding every changed voxel (empty when none changed): exact per row
  /// of the brush loop, the whole chunk box where a chunk was filled in one go.
  /// Feed it to ChunkedMarchingCubes::chunksAffectedBy for the exact set of
  /// marching cubes chunks to re-mesh.
  VoxelBox changedBox;
};

/// Applies the dabs in order (see the header comment). Adds the brush colour to the
/// volume's colour dictionary first (Error DictionaryFull if it cannot). Invalid dabs
/// (non-finite position or radius) are refused with Error(InvalidArgument) before any write.
EditResult applyDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  ChunkWriteObserver* observer = nullptr);

inline EditResult applyDab(DictionaryVolume& volume, const Dab& dab, const BrushSettings& settings,
  ChunkWriteObserver* observer = nullptr)
{
  return applyDabs(volume, std::vector<Dab>{ dab }, settings, observer);
}

} // namespace lvdif
