// One voxel's tests of the sharp features' regions (MeshToSdfSharpFeatures.h),
// shared by the CPU's pass (MeshToSdfSharpFeatures.cpp) and the CUDA kernel
// (MeshToSdfCudaSharp.cu): the same source for both, so that both keep the
// same voxels and store the Normal path's floats there.
#pragma once

#include "MeshToSdfGeometry.h"
#include "lvdif/HostDevice.h"

namespace lvdif
{
namespace detail::meshtosdf
{

/// A sharp feature as both sides read it (SharpFeature's arrays by pointer).
struct SharpFeatureView
{
  V3 a, b;
  const V3* limits = nullptr;
  const V3* normals = nullptr;
  int limitCount = 0, normalCount = 0;
  bool edge = false;
};

/// The offset d of p from the feature's closest point; false when p is past
/// the edge's ends (the end vertices' business) by more than `slack`.
LVDIF_HD bool sharpOffset(const SharpFeatureView& f, V3 p, double slack, V3& d)
{
  if (!f.edge)
  {
    d = p - f.a;
    return true;
  }
  const V3 e = f.b - f.a;
  const double len2 = dot(e, e), len = std::sqrt(len2);
  const double s = dot(p - f.a, e);
  if (s < -slack * len || s > len2 + slack * len) return false;
  double t = s / len2;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  d = p - (f.a + t * e);
  return true;
}

/// Whether direction d lies in the feature's cone and its faces' normals give
/// both signs there, each with `slack`.
LVDIF_HD bool sharpMayDiffer(const SharpFeatureView& f, V3 d, double slack)
{
  for (int i = 0; i < f.limitCount; ++i)
    if (dot(d, f.limits[i]) > slack) return false;
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i < f.normalCount; ++i)
  {
    const double s = dot(d, f.normals[i]);
    lo = s < lo ? s : lo;
    hi = s > hi ? s : hi;
  }
  return lo < slack && hi > -slack;
}

/// A voxel p of a brick of feature f, before its query: whether its closest
/// point can lie on the feature, in a direction where the faces' normals
/// disagree, and it is not farther from the feature than from `near` (the
/// closest triangle to the brick's centre, an upper bound of the distance to
/// the mesh), each with rounding's tolerance alone (`tol`, set here; the
/// bricks' margins keep the walk from missing any voxel). d: p's offset from
/// the feature.
LVDIF_HD bool sharpVoxelMayBeInRegion(const SharpFeatureView& f, V3 p, V3 near0, V3 near1, V3 near2,
  double diagonal, V3& d, double& tol)
{
  tol = 1e-9 * (norm(p - f.a) + norm(f.b - f.a) + diagonal);
  if (!sharpOffset(f, p, tol, d) || !sharpMayDiffer(f, d, tol)) return false;
  const V3 dn = closestPointOnTriangle(p, near0, near1, near2).point - p;
  return !(norm(d) - norm(dn) > tol);
}

/// After the query (dist2 to the mesh): p is in the region unless it is
/// farther from the feature than from the mesh beyond the tolerance.
LVDIF_HD bool sharpVoxelInRegion(V3 d, double tol, double dist2)
{
  return !(norm(d) - std::sqrt(dist2) > tol);
}

} // namespace detail::meshtosdf
} // namespace lvdif
