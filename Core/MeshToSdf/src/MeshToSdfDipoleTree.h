// A hierarchy over weighted triangles for the sum of their solid angles with
// a RIGOROUS error bound (used for 2 w_{F+}, the reversed faces of the
// winding-number sign, MeshToSdfWinding.cpp). Far clusters use the dipole
// term of Barill et al., "Fast Winding Numbers for Soups and Clouds" (ACM TOG
// 2018): sum_t w_t a_t n_t . (c - p) / |c - p|^3, with the remainder bounded
// by the Taylor estimate below instead of being ignored.
#pragma once

#include "MeshToSdfGeometry.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

struct WeightedTri
{
  V3 v[3];
  double w = 1; // multiplicity of the triangle in the chain
};

class DipoleTree
{
public:
  explicit DipoleTree(std::vector<WeightedTri> tris);
  bool empty() const { return this->Tris.empty(); }
  std::size_t size() const { return this->Tris.size(); }

  enum class Refined
  {
    Done,   // goal(sLo, sHi) said so
    Exact,  // everything summed exactly, goal still not reached (within rounding)
    Failed  // goal gave up, or rho > 0 and the ball meets a leaf's triangle or bounded leaves alone miss the goal
  };
  /// s = sum_t w_t Omega_t(p) / (4 pi) lies in [sLo, sHi] for EVERY p with
  /// |p - q| <= rho. The interval starts as the root's bound, and the cluster with the largest error is
  /// split (a leaf summed exactly when rho == 0) until goal(sLo, sHi)
  /// returns 1 (done) or -1 (give up); 0 means go on. Barnes-Hut style, but
  /// driven by the sign decision instead of a fixed opening angle. A cluster
  /// (centre c, radius R, weighted area A) at d = |c - q| - rho - R > 0 uses
  /// the smallest of three rigorous bounds (clusterError, shared with the
  /// GPU): 0 with error A / d^2 (|Omega_t| <= area / dist^2), its dipole term
  /// at q with error 2 A (R + rho) / d^3 (Taylor: |grad (y / |y|^3)| <=
  /// 2 / |y|^3), or the dipole plus the second-order term with error
  /// 3 A R^2 / (|c - q| - R)^4 + 2 A rho / d^3; d <= 0: no bound.
  /// With rho > 0 a leaf is bounded triangle by triangle (the exact value at
  /// q plus rho times a Lipschitz bound of the solid angle on the ball,
  /// triangleLipschitz, the GPU's block bound) where that is tighter; such a
  /// leaf cannot get tighter, and the call fails as soon as the bounded
  /// leaves' error alone, around the present estimate, misses the goal.
  /// leafTris counts the triangles summed exactly.
  /// cut (optional): clusters to start from instead of the root (any set of
  /// nodes that covers every triangle exactly once, e.g. the cut a previous
  /// call ended with, a neighbouring voxel's); replaced by the final cut.
  Refined refine(V3 q, double rho, const std::function<int(double, double)>& goal, double& sLo, double& sHi,
    std::int64_t& leafTris, std::vector<std::int32_t>* cut = nullptr) const;
  /// The plain sum over all triangles (Van Oosterom & Strackee solid angles).
  double exact(V3 p) const;
  /// The same sum in triangle order with solidAngleCanonical: the same bits
  /// on the GPU (MeshToSdfCudaDipole.cuh), so a sign within rounding of +-1/2
  /// is decided alike on both.
  double exactCanonical(V3 p) const;

  struct Node
  {
    V3 c, dipole;        // centre; sum of w a n
    double r = 0, mass = 0; // radius about c; sum of |w| a
    double quad[9] = {};    // sum of w a n_i (g - c)_j, g the centroid (the second-order term)
    std::int32_t left = -1, right = -1, first = 0, count = 0;
  };
  // for the upload to the GPU (node 0 the root; leaves list tris()[first, first + count))
  const std::vector<Node>& nodes() const { return this->Nodes; }
  const std::vector<WeightedTri>& tris() const { return this->Tris; }

private:
  std::vector<WeightedTri> Tris;
  std::vector<Node> Nodes;
};

} // namespace detail::meshtosdf
} // namespace lvdif
