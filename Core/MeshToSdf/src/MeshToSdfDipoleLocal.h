// Local (Taylor) expansions of the correction s over a block of voxels, with
// rigorous error bounds: the multipole-to-local step of the fast multipole
// method (Greengard & Rokhlin, "A fast algorithm for particle simulations",
// J. Comput. Phys. 1987) applied to the dipole tree's clusters (the dipole
// and second-order terms of Barill et al. 2018, MeshToSdfDipoleTree.h).
//
// Why: a block's ball bound (DipoleTree::refine with rho > 0) moves each
// cluster's value over the ball by a Lipschitz term 2 A rho / d^3, so its
// interval is as wide as the variation of every cluster's term summed in
// absolute value; next to the corrected faces, and deep inside a mesh whose
// winding number is near 1/2, no ball decides and every voxel was refined on
// its own. Here the far clusters are summed ONCE per block as a quadratic
// polynomial in the voxel's offset from the block's centre, whose error over
// the whole ball shrinks like (rho / r)^3 instead of rho / r; the clusters
// near the block are opened down to leaves whose triangles are summed
// exactly at each voxel. Each voxel then gets its own rigorous interval of s
// for the price of a quadratic form plus its near triangles.
#pragma once

#include "MeshToSdfDipoleTree.h"

#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// A quadratic in the offset x = p - b from the block's centre b:
/// v + g.x + x'Hx / 2 (H symmetric: xx, xy, xz, yy, yz, zz). In units of 4 pi.
struct LocalPoly
{
  /// symmetric 3x3 as 6 entries: xx, xy, xz, yy, yz, zz
  static constexpr int Sym[3][3] = { { 0, 1, 2 }, { 1, 3, 4 }, { 2, 4, 5 } };
  double v = 0, g[3] = {}, H[6] = {};
  void add(const LocalPoly& o, double sign);
  /// inline: called for every open voxel at every check (the quadratic form
  /// from its 6 distinct products)
  double at(V3 x) const
  {
    const double q = this->H[0] * x.x * x.x + this->H[3] * x.y * x.y + this->H[5] * x.z * x.z +
      2 * (this->H[1] * x.x * x.y + this->H[2] * x.x * x.z + this->H[4] * x.y * x.z);
    return this->v + (this->g[0] * x.x + this->g[1] * x.y + this->g[2] * x.z) + 0.5 * q;
  }
};

/// The Taylor expansion about b of a cluster's multipole term (order 1: the
/// dipole; order 2: plus the second-order term; y0 = c - b), and the bound of
/// its Taylor remainder at every point of the ball (b, rho) (its third
/// derivatives: |D^k (1/|y|)| <= k! / |y|^(k+1), the multilinear norm of a
/// symmetric form being its largest value on one unit direction).
LocalPoly clusterLocal(const DipoleTree::Node& nd, V3 y0, int order);
double clusterLocalRemainder(const DipoleTree::Node& nd, double rMin, double rho, int order);

/// The error over the ball (b, rho) of the cluster's best local option, r0 =
/// |c - b| (order 0: no polynomial, error A / d^2; order 1/2: the
/// expansion's truncation at any point of the ball, 2 A R / d^3 or
/// 3 A R^2 / d^4 with d = r0 - rho - R, plus the Taylor remainder times
/// remainderScale, which only a test sets below 1). Infinite when d <= 0.
double clusterLocalError(const DipoleTree::Node& nd, double r0, double rho, int& order, double remainderScale = 1);

/// s at each of the points pts[0, n) (all within rho of centre): rigorous
/// intervals [lo[i], hi[i]] from far clusters summed as one local
/// polynomial and near triangles summed exactly at each point (a leaf is
/// first split into its triangles, each a cluster about its centroid).
/// Clusters are opened largest error first (starting from `start`, a cut as
/// DipoleTree::refine's, else the root) until every interval lies inside
/// (m - 1/2, m + 1/2) for an integer m (which decides the point whatever its
/// crossing count), or the work (node expansions + triangles x points)
/// passes `budget`. Returns the number of points so decided; every interval
/// holds either way (those not decided are returned too).
int localBounds(const DipoleTree& tree, V3 centre, double rho, const V3* pts, int n, double* lo, double* hi,
  std::int64_t budget, const std::vector<std::int32_t>* start = nullptr, double remainderScale = 1);

/// Whether [lo, hi] lies inside (m - 1/2, m + 1/2) for an integer m.
inline bool avoidsHalfIntegers(double lo, double hi)
{
  const double m = std::floor(0.5 * (lo + hi) + 0.5);
  return lo > m - 0.5 && hi < m + 0.5;
}

} // namespace detail::meshtosdf
} // namespace lvdif
