// A hierarchy over weighted triangles for the sum of their solid angles with
// a RIGOROUS error bound (used for 2 w_{F+}, the reversed faces of the
// winding-number sign, MeshToSdfWinding.cpp). Far clusters use the dipole
// term of Barill et al., "Fast Winding Numbers for Soups and Clouds" (ACM TOG
// 2018): sum_t w_t a_t n_t . (c - p) / |c - p|^3, with the remainder bounded
// by the Taylor estimate below instead of being ignored.
#pragma once

#include "MeshToSdfGeometry.h"

#include <cstdint>
#include <vector>

namespace lvdif
{
namespace sdfdetail
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

  /// sum_t w_t Omega_t(p) / (4 pi) for EVERY p with |p - q| <= rho lies in
  /// [value - err, value + err]. A cluster (centre c, radius R, weighted area
  /// A) at d = |c - q| - rho - R > 0 with R + rho <= theta d uses its dipole
  /// term at q; since |grad (y / |y|^3)| <= 2 / |y|^3, its error is at most
  /// 2 A (R + rho) / d^3. Closer leaves are summed exactly when rho == 0;
  /// with rho > 0 such a leaf makes the call return false (no bound).
  bool bound(V3 q, double rho, double theta, double& value, double& err) const;
  /// The plain sum over all triangles (Van Oosterom & Strackee solid angles).
  double exact(V3 p) const;

private:
  struct Node
  {
    V3 c, dipole;        // centre; sum of w a n
    double r = 0, mass = 0; // radius about c; sum of |w| a
    std::int32_t left = -1, right = -1, first = 0, count = 0;
  };
  std::vector<WeightedTri> Tris;
  std::vector<Node> Nodes;
};

} // namespace sdfdetail
} // namespace lvdif
