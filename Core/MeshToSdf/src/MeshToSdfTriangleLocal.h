// The Taylor expansion of one triangle's exact solid angle about a point, with
// a rigorous remainder over a ball: a near triangle's term in localBounds
// (MeshToSdfDipoleLocal.cpp) that is cheaper than its exact solid angle at
// each voxel of the block and tighter than its dipole.
//
// Why: a triangle opened as a cluster about its centroid (triangleCluster)
// keeps the dipole's truncation 2 A R / d^3 however small the block's ball;
// where the voxels' margins are small (patch30's deep voxels, w near 1/2)
// thousands of triangles 8 or more voxels from the block were then summed
// exactly at each of up to 64 voxels. The exact solid angle's own expansion
// has no truncation, only the Taylor remainder, which shrinks like
// (rho / dist)^3.
//
// The math. With the face's unit normal n, Omega(p) = integral over the face
// of n.(y - p) / |y - p|^3 dA(y), a first derivative of phi = 1/|z| in the
// direction n at z = y - p. Its third derivatives in p are fourth derivatives
// of phi: the symmetric form D^4 phi(z) has norm 4! / |z|^5 (the k-th
// derivative along a unit direction is k! P_k(cos) / |z|^(k+1), |P_k| <= 1,
// and a symmetric form's norm is its largest value on one unit direction,
// Banach, Studia Math. 1938), so |D^3 Omega(p)[u, u, u]| <= 24 A / dist(p, face)^5. Over the
// ball (b, rho), dist >= g = dist(b, face) - rho, and Lagrange's remainder
// after the quadratic is at most rho^3 / 3! times that: 4 A rho^3 / g^5.
//
// The value at b is Van Oosterom & Strackee's formula (1983); the gradient is
// the Biot-Savart integral over the boundary (the solid angle is the magnetic
// scalar potential of a unit current around the edges):
//   grad Omega(p) = sum over edges a -> b of (r1 x r2) G,  r1 = a - p, r2 = b - p,
//   G = integral_0^1 dt / |r1 + t (b - a)|^3 = (l1 + l2) / (l1 l2 (l1 l2 + r1.r2)),
// and the Hessian its derivative in closed form (dr1/dp = dr2/dp = -I):
//   d/dp_k [(r1 x r2) G] = ((b - a) x e_k) G + (r1 x r2) dG/dp_k,
//   dG/dp = G (-(r1/l1 + r2/l2) / (l1 + l2) + v / (l1 l2) + (v + r1 + r2) / (l1 l2 + r1.r2)),
//   v = l2 r1 / l1 + l1 r2 / l2;
// one edge's part is not symmetric, the sum over the three is (Omega is
// smooth off the face), so the Hessian is taken as its symmetric part.
#pragma once

#include "MeshToSdfDipoleLocal.h" // LocalPoly, nearSolidAngle
#include "MeshToSdfGeometry.h"    // closestPointOnTriangle

#include <cmath>

namespace lvdif
{
namespace detail::meshtosdf
{

/// One edge a -> b's part of grad Omega at p (g) and of its Hessian (J, row
/// j column k: d g_j / d p_k), added; mag += a bound of the sizes of this
/// edge's terms over the ball (b, rho), times the relative loss of Q's
/// cancellation (rounding slack).
inline void addEdgeField(V3 p, V3 a, V3 b, double rho, double g[3], double J[3][3], double& mag)
{
  const V3 r1 = a - p, r2 = b - p, e = b - a;
  const double l1 = norm(r1), l2 = norm(r2);
  const double P = l1 * l2, Q = P + dot(r1, r2), N = l1 + l2;
  const double G = N / (P * Q);
  const V3 c = cross(r1, r2);
  const V3 u = (1 / l1) * r1 + (1 / l2) * r2;
  const V3 v = (l2 / l1) * r1 + (l1 / l2) * r2;
  const double iN = 1 / N, iP = 1 / P, iQ = 1 / Q;
  const V3 dG = G * ((-iN) * u + iP * v + iQ * (v + r1 + r2));
  const double cc[3] = { c.x, c.y, c.z }, dg[3] = { dG.x, dG.y, dG.z };
  // ex[j][k] = (e x e_k)_j: columns (0, e.z, -e.y), (-e.z, 0, e.x), (e.y, -e.x, 0)
  const double ex[3][3] = { { 0, -e.z, e.y }, { e.z, 0, -e.x }, { -e.y, e.x, 0 } };
  for (int j = 0; j < 3; ++j)
  {
    g[j] += cc[j] * G;
    for (int k = 0; k < 3; ++k) J[j][k] += ex[j][k] * G + cc[j] * dg[k];
  }
  const double cn = norm(c), dGn = G * (norm(u) * iN + 2 * norm(v) * iP + norm(v + r1 + r2) * iQ);
  mag += (cn * G * rho + (norm(e) * G + cn * dGn) * rho * rho) * (1 + 2 * P * iQ);
}

/// The quadratic Taylor polynomial about b of w Omega (triangle (a0, a1,
/// a2), weight w), in the offset x = p - b (units of 4 pi, as LocalPoly).
/// b must be off the triangle (every edge's G finite). mag: a bound of its
/// terms' sizes over the ball (b, rho) for the rounding slack (the value's
/// as a near triangle's exact sum is counted, its size).
inline LocalPoly triangleTaylor(V3 b, double rho, V3 a0, V3 a1, V3 a2, double w, double& mag)
{
  double g[3] = { 0, 0, 0 }, J[3][3] = {};
  double edges = 0;
  addEdgeField(b, a0, a1, rho, g, J, edges);
  addEdgeField(b, a1, a2, rho, g, J, edges);
  addEdgeField(b, a2, a0, rho, g, J, edges);
  LocalPoly p;
  p.v = w * nearSolidAngle(b, a0, a1, a2);
  for (int k = 0; k < 3; ++k) p.g[k] = w * g[k];
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l) p.H[symIndex(k, l)] = w * 0.5 * (J[k][l] + J[l][k]);
  mag = std::fabs(p.v) + 10 * std::fabs(w) * edges;
  return p;
}

/// The Taylor remainder of triangleTaylor over the ball (b, rho): 4 A rho^3
/// / g^5 (A = |w| x area, g = dist(b, face) - rho), times remainderScale
/// (only a test sets it below 1). Infinite when the ball meets the face.
/// dist (out): dist(b, face), by the closest point (Ericson's routine; a
/// degenerate face has A = 0, and a distance that is NaN gives no bound).
inline double triangleTaylorError(V3 b, double rho, const WeightedTri& t, double& dist, double remainderScale = 1)
{
  dist = norm(closestPointOnTriangle(b, t.v[0], t.v[1], t.v[2]).point - b);
  const double g = dist - rho;
  if (!(g > 0)) return HUGE_VAL;
  const double A = std::fabs(t.w) * 0.5 * norm(cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
  const double g2 = g * g;
  return remainderScale * 4 * A * rho * rho * rho / (g2 * g2 * g);
}

} // namespace detail::meshtosdf
} // namespace lvdif
