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

#include "MeshToSdfDipoleDecide.h" // clusterValue (the value at the centre is the same term), DipoleView
#include "MeshToSdfDipoleTree.h"

#include <cmath>
#include <cstdint>
#include <vector>

// The terms below are host/device functions: the CPU's localBounds (a
// priority queue) and the GPU's dipoleLocalBlock (a stack and a tolerance
// per unit of mass, MeshToSdfCudaDipole.cuh) expand, bound and evaluate with
// the same definitions.

namespace lvdif
{
namespace detail::meshtosdf
{

/// Index of entry (k, l) of a symmetric 3x3 stored as xx, xy, xz, yy, yz, zz.
LVDIF_HD int symIndex(int k, int l)
{
  const int a = k < l ? k : l, b = k < l ? l : k;
  return a == 0 ? b : (a == 1 ? 2 + b : 5);
}

/// A quadratic in the offset x = p - b from the block's centre b:
/// v + g.x + x'Hx / 2 (H symmetric: xx, xy, xz, yy, yz, zz). In units of 4 pi.
struct LocalPoly
{
  double v = 0, g[3] = {}, H[6] = {};
  LVDIF_HD void add(const LocalPoly& o, double sign)
  {
    this->v += sign * o.v;
    for (int i = 0; i < 3; ++i) this->g[i] += sign * o.g[i];
    for (int i = 0; i < 6; ++i) this->H[i] += sign * o.H[i];
  }
  /// the quadratic form from its 6 distinct products
  LVDIF_HD double at(V3 x) const
  {
    const double q = this->H[0] * x.x * x.x + this->H[3] * x.y * x.y + this->H[5] * x.z * x.z +
      2 * (this->H[1] * x.x * x.y + this->H[2] * x.x * x.z + this->H[4] * x.y * x.z);
    return this->v + (this->g[0] * x.x + this->g[1] * x.y + this->g[2] * x.z) + 0.5 * q;
  }
};

/// The Taylor expansion about b of a cluster's multipole term (order 1: the
/// dipole; order 2: plus the second-order term; y0 = c - b).
LVDIF_HD LocalPoly clusterLocal(const DipoleTree::Node& nd, V3 y0, int order)
{
  // With phi = 1 / |y| and y = c - p, the cluster's term is
  //   m(y) = -D_i phi_i(y) - T_ij phi_ij(y)   (clusterValue: D.y / r^3 + tr T / r^3 - 3 y.T.y / r^5),
  // and p = b + x gives y = y0 - x: m = m(y0) - grad m . x + x' Hess m x / 2 + O(|x|^3).
  // The derivative tensors of 1/|y| (Kronecker deltas d):
  //   phi_ij   = 3 y_i y_j / r^5 - d_ij / r^3
  //   phi_ijk  = -15 y_i y_j y_k / r^7 + 3 (d_ij y_k + d_ik y_j + d_jk y_i) / r^5
  //   phi_ijkl = 105 y_i y_j y_k y_l / r^9 - 15 (d_ij y_k y_l + 5 more pairs) / r^7 + 3 (d_ij d_kl + d_ik d_jl + d_il d_jk) / r^5
  // contracted with D and T in closed form (a = y.T.y, t = tr T, u = T y, v = T' y):
  //   D_i phi_ik    = 3 (D.y) y_k / r^5 - D_k / r^3
  //   D_i phi_ikl   = -15 (D.y) y_k y_l / r^7 + 3 (D_k y_l + D_l y_k + d_kl D.y) / r^5
  //   T_ij phi_ijk  = -15 a y_k / r^7 + 3 (t y_k + u_k + v_k) / r^5
  //   T_ij phi_ijkl = 105 a y_k y_l / r^9 - 15 (t y_k y_l + (u + v)_k y_l + (u + v)_l y_k + d_kl a) / r^7
  //                   + 3 (d_kl t + T_kl + T_lk) / r^5
  const double y[3] = { y0.x, y0.y, y0.z };
  const double r2 = y0.x * y0.x + y0.y * y0.y + y0.z * y0.z, r = std::sqrt(r2);
  const double i3 = 1 / (r2 * r), i5 = i3 / r2, i7 = i5 / r2, i9 = i7 / r2;
  const double D[3] = { nd.dipole.x, nd.dipole.y, nd.dipole.z };
  const double Dy = D[0] * y[0] + D[1] * y[1] + D[2] * y[2];
  const double* T = nd.quad;
  double a = 0, t = 0, w[3] = { 0, 0, 0 }; // w = u + v
  if (order == 2)
  {
    t = T[0] + T[4] + T[8];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        a += y[i] * T[3 * i + j] * y[j];
        w[i] += T[3 * i + j] * y[j];
        w[j] += T[3 * i + j] * y[i];
      }
  }
  LocalPoly p;
  double mag = 0;
  p.v = clusterValue(nd, y0, r, order, mag);
  for (int k = 0; k < 3; ++k)
  {
    double gk = -(3 * Dy * y[k] * i5 - D[k] * i3); // grad_y m
    if (order == 2) gk -= -15 * a * y[k] * i7 + 3 * (t * y[k] + w[k]) * i5;
    p.g[k] = -gk; // d/dx = -d/dy
  }
  for (int k = 0; k < 3; ++k)
    for (int l = k; l < 3; ++l)
    {
      const double dkl = k == l ? 1.0 : 0.0;
      double h = -(-15 * Dy * y[k] * y[l] * i7 + 3 * (D[k] * y[l] + D[l] * y[k] + dkl * Dy) * i5);
      if (order == 2)
        h -= 105 * a * y[k] * y[l] * i9 - 15 * (t * y[k] * y[l] + w[k] * y[l] + w[l] * y[k] + dkl * a) * i7 +
          3 * (dkl * t + T[3 * k + l] + T[3 * l + k]) * i5;
      p.H[symIndex(k, l)] = h;
    }
  return p;
}

/// sum |T_ij| of a cluster's second-order term
LVDIF_HD double quadAbsSum(const DipoleTree::Node& nd)
{
  double t = 0;
  for (int i = 0; i < 9; ++i) t += std::fabs(nd.quad[i]);
  return t;
}

/// The bound of the expansion's Taylor remainder at every point of the ball
/// (b, rho), from |D| and sum |T_ij| (its third derivatives: |D^k (1/|y|)|
/// <= k! / |y|^(k+1), the multilinear norm of a symmetric form being its
/// largest value on one unit direction).
LVDIF_HD double localRemainder(double dipoleNorm, double quadAbs, double rMin, double rho, int order)
{
  // |x|^3 / 3! times the third derivatives: |D| 4! / rMin^5 (dipole), sum |T_ij| 5! / rMin^6 (second order)
  const double r5 = rMin * rMin * rMin * rMin * rMin;
  double third = 24 * dipoleNorm / r5;
  if (order == 2) third += 120 * quadAbs / (r5 * rMin);
  return rho * rho * rho * third / 6;
}

LVDIF_HD double clusterLocalRemainder(const DipoleTree::Node& nd, double rMin, double rho, int order)
{
  return localRemainder(norm(nd.dipole), order == 2 ? quadAbsSum(nd) : 0.0, rMin, rho, order);
}

/// The error over the ball (b, rho) of the cluster's best local option, r0 =
/// |c - b| (order 0: no polynomial, error A / d^2; order 1/2: the
/// expansion's truncation at any point of the ball, 2 A R / d^3 or
/// 3 A R^2 / d^4 with d = r0 - rho - R, plus the Taylor remainder times
/// remainderScale, which only a test sets below 1). Infinite when d <= 0.
LVDIF_HD double clusterLocalError(const DipoleTree::Node& nd, double r0, double rho, int& order, double remainderScale = 1)
{
  const double d = r0 - rho - nd.r;
  order = 0;
  if (!(d > 0)) return HUGE_VAL;
  const double rMin = r0 - rho, R = nd.r, A = nd.mass;
  const double dn = norm(nd.dipole), qa = quadAbsSum(nd);
  const double e0 = A / (d * d);
  const double e1 = 2 * A * R / (d * d * d) + remainderScale * localRemainder(dn, qa, rMin, rho, 1);
  const double e2 = 3 * A * R * R / (d * d * d * d) + remainderScale * localRemainder(dn, qa, rMin, rho, 2);
  order = e2 < e1 ? (e2 < e0 ? 2 : 0) : (e1 < e0 ? 1 : 0);
  return order == 2 ? e2 : (order == 1 ? e1 : e0);
}

/// A generous bound of every term's size in an expansion's sums (for the
/// rounding slack), rMin = |c - b| - rho.
LVDIF_HD double clusterLocalMag(const DipoleTree::Node& nd, double rMin, double rho)
{
  const double s = rho / rMin;
  return 200 * (nd.mass / (rMin * rMin) + quadAbsSum(nd) / (rMin * rMin * rMin)) * (1 + s + s * s);
}

/// Triangle t on its own as a cluster about its centroid (second-order term
/// 0, radius its farthest vertex): a leaf too near for its own expansion is
/// first split into its triangles, and only those still too near are summed.
LVDIF_HD DipoleTree::Node triangleCluster(const WeightedTri& t, std::int32_t index)
{
  DipoleTree::Node n;
  n.c = (1.0 / 3.0) * (t.v[0] + t.v[1] + t.v[2]);
  const V3 an = 0.5 * cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
  n.dipole = t.w * an;
  n.mass = std::fabs(t.w) * norm(an);
  for (int i = 0; i < 3; ++i)
  {
    const double d = norm(t.v[i] - n.c);
    n.r = d > n.r ? d : n.r;
  }
  n.r *= 1 + 1e-12; // rounding of the distances above
  n.first = index;
  n.count = 1;
  return n;
}

/// solidAngle (Van Oosterom & Strackee 1983) for the near triangles' sums:
/// atan(num / den) where den > 0 (the same angle within an ulp or two, far
/// inside the slack's 1e-9; libm's atan2 was 15 % of patch30's time).
LVDIF_HD double nearSolidAngle(V3 p, V3 a, V3 b, V3 c)
{
  const V3 x = a - p, y = b - p, z = c - p;
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = dot(x, cross(y, z));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(x, z) * ly + dot(y, z) * lx;
  return 2.0 * (den > 0 ? std::atan(num / den) : std::atan2(num, den));
}

/// The interval of s at a point from the sums (units of 4 pi): v the far
/// polynomial at the point plus its near triangles, err the far clusters'
/// error; the rounding slack 1e-9 + 1e-12 (farMag + err + directMag)
/// (terms + 1) (farMag: the clusters' clusterLocalMag summed; 1 / (4 pi)
/// multiplied, within an ulp of the division, far inside the slack).
LVDIF_HD void localInterval(double v, double err, double farMag, double directMag, long long terms, double& lo, double& hi)
{
  constexpr double InvFourPi = 1.0 / FourPi;
  const double slack = 1e-9 + 1e-12 * static_cast<double>(terms + 1) * (farMag + err + directMag);
  lo = (v - err) * InvFourPi - slack;
  hi = (v + err) * InvFourPi + slack;
}

/// Whether [lo, hi] lies inside (m - 1/2, m + 1/2) for an integer m.
LVDIF_HD bool avoidsHalfIntegers(double lo, double hi)
{
  const double m = std::floor(0.5 * (lo + hi) + 0.5);
  return lo > m - 0.5 && hi < m + 0.5;
}

// The GPU's local step (dipoleLocalKernel, MeshToSdfCudaDipole.cuh; the
// tests run it on the CPU too): the 4^3 blocks whose ball bound fails get
// one rigorous interval of s per voxel, as the CPU's localBounds gives them,
// but traversed as the GPU's other bounds are (boundDipole): a stack, and a
// tolerance per unit of mass lowered pass by pass, instead of a priority
// queue. A cluster whose local error over the ball (clusterLocalError) is at
// most the tolerance x its mass joins the block's polynomial; others are
// opened, a leaf into its triangles (triangleCluster), and a triangle still
// too near is summed exactly at each voxel (nearSolidAngle).

/// The edge of the blocks expanded (the level of DipoleEdges whose failed
/// blocks are listed for it) and the voxels of one.
constexpr int DipoleLocalEdge = 4;
constexpr int DipoleLocalVoxels = DipoleLocalEdge * DipoleLocalEdge * DipoleLocalEdge;
/// At most this many passes (tolerance lowered 4x a pass or to what the
/// open voxels need); what stays open is refined voxel by voxel.
constexpr int DipoleLocalPasses = 3;
/// The traversal's stack (as boundDipole's; deeper trees fail: no intervals).
constexpr int DipoleLocalStack = 64;
/// No pass below this margin: a voxel whose s lies that near a half-integer
/// is left to the per-voxel refinement (and its canonical sum).
constexpr double DipoleLocalMinMargin = 1e-3;

/// The voxels of a block as the rows position them: voxel (a, b, c), a < n[0]
/// etc., slot a + 4 (b + 4 c), at rowStart[b + 4 c] + (x0 + a) h (the row's
/// start plus its index times the spacing, as signDipoleKernel computes it).
struct DipoleLocalBlockVoxels
{
  V3 rowStart[DipoleLocalEdge * DipoleLocalEdge];
  double h = 0;
  long long x0 = 0;
  int n[3] = { 0, 0, 0 };
  LVDIF_HD bool has(int v) const
  {
    return v % DipoleLocalEdge < n[0] && (v / DipoleLocalEdge) % DipoleLocalEdge < n[1] &&
      v / (DipoleLocalEdge * DipoleLocalEdge) < n[2];
  }
  LVDIF_HD V3 at(int v) const
  {
    return rowStart[v / DipoleLocalEdge] + V3{ static_cast<double>(x0 + v % DipoleLocalEdge) * h, 0, 0 };
  }
};

/// The near triangles listed at a time (the GPU's scratch list per block in
/// flight): a full list is summed at the voxels, emptied, and the walk goes on.
constexpr int DipoleLocalNearCap = 256;

/// A pass's sums over a block that do not depend on the voxel: the far
/// clusters' polynomial, their error and size bound (rounding slack), the
/// terms counted (near triangles included), and the near triangles listed
/// since the list was last emptied.
struct DipoleLocalFar
{
  LocalPoly poly;
  double err = 0, mag = 0;
  long long terms = 0;
  int near = 0; // listed (entry i at list[i * stride])
};

/// One pass's walk over the clusters about a block's ball, resumable where
/// the near list fills up. A stack entry is a node and whether the previous
/// pass reached it too (opened every ancestor): the tolerance only falls
/// from pass to pass, so what the previous pass opened this one opens too,
/// and a triangle it summed exactly is summed again here; such a triangle is
/// not listed (its sums at the voxels carry over), only counted.
struct DipoleLocalWalk
{
  int stack[DipoleLocalStack]; // node << 1 | reached by the previous pass
  int top = 0;
  int leafNext = 0, leafEnd = 0; // the triangles of the leaf being opened not tried yet
  bool leafBefore = false;       // the previous pass opened that leaf too
  bool overflow = false;         // the stack overflowed: no interval
  DipoleLocalFar far;
  /// previous: a pass ran before (its tolerance passed to dipoleLocalWalk)
  LVDIF_HD void start(bool previous)
  {
    *this = DipoleLocalWalk{};
    this->stack[this->top++] = previous ? 1 : 0;
  }
};

/// Walks on about the ball (centre, rho) at tolPerMass: a cluster whose local
/// error over the ball (clusterLocalError) is at most tolPerMass x its mass
/// joins the polynomial, others are opened, a leaf into its triangles
/// (triangleCluster), and a triangle still too near is listed (its index in
/// the tree's triangles) unless the previous pass (at prevTolPerMass)
/// summed it already. Returns false when the list is full (sum it at the
/// voxels, set w.far.near = 0 and call again), true when the walk is done
/// (w.overflow: the stack overflowed, no interval). errorScale multiplies
/// every cluster's error bound: only a test sets it below 1 (an error bound
/// too small, which the containment check must catch).
LVDIF_HD bool dipoleLocalWalk(const DipoleView& D, V3 centre, double rho, double tolPerMass, double prevTolPerMass,
  DipoleLocalWalk& w, int* list, int stride, double errorScale = 1)
{
  DipoleLocalFar& far = w.far;
  // accepted: the cluster's expansion joins the polynomial; openedBefore:
  // the previous pass reached it and opened it (or summed it, a triangle)
  auto consider = [&](const DipoleTree::Node& nd, bool reachedBefore, bool& openedBefore) {
    const V3 y = nd.c - centre;
    const double r0 = norm(y);
    int order = 0;
    const double e = errorScale * clusterLocalError(nd, r0, rho, order);
    openedBefore = reachedBefore && !(e <= prevTolPerMass * nd.mass);
    if (!(e <= tolPerMass * nd.mass)) return false;
    far.err += e;
    far.mag += clusterLocalMag(nd, r0 - rho, rho);
    if (order > 0) far.poly.add(clusterLocal(nd, y, order), 1);
    ++far.terms;
    return true;
  };
  while (true)
  {
    while (w.leafNext < w.leafEnd)
    {
      if (far.near == DipoleLocalNearCap) return false;
      const int t = w.leafNext++;
#ifndef __CUDA_ARCH__
      if (D.work) ++D.work->triBounds; // triangles tried as clusters
#endif
      bool summedBefore = false;
      if (consider(triangleCluster(D.tris[t], t), w.leafBefore, summedBefore)) continue;
      if (!summedBefore) list[static_cast<long long>(far.near++) * stride] = t;
      ++far.terms;
    }
    if (w.top == 0) return true;
    const int entry = w.stack[--w.top];
    const DipoleTree::Node nd = D.nodes[entry >> 1];
#ifndef __CUDA_ARCH__
    if (D.work) ++D.work->nodes;
#endif
    bool openedBefore = false;
    if (consider(nd, (entry & 1) != 0, openedBefore)) continue;
    if (nd.left >= 0)
    {
      if (w.top + 2 > DipoleLocalStack)
      {
        w.overflow = true;
        return true;
      }
      w.stack[w.top++] = (nd.left << 1) | (openedBefore ? 1 : 0);
      w.stack[w.top++] = (nd.right << 1) | (openedBefore ? 1 : 0);
      continue;
    }
    w.leafNext = nd.first;
    w.leafEnd = nd.first + nd.count;
    w.leafBefore = openedBefore;
  }
}

/// Adds the listed near triangles' solid angles at p (count of them, entry i
/// at list[i * stride]) to its running sums, in list order.
LVDIF_HD void dipoleLocalNearSum(const DipoleView& D, const int* list, int stride, int count, V3 p, double& direct, double& directMag)
{
  for (int i = 0; i < count; ++i)
  {
    const WeightedTri& tri = D.tris[list[static_cast<long long>(i) * stride]];
    const double a = tri.w * nearSolidAngle(p, tri.v[0], tri.v[1], tri.v[2]);
    direct += a;
    directMag += std::fabs(a);
  }
#ifndef __CUDA_ARCH__
  if (D.work) D.work->tris += static_cast<unsigned long long>(count); // triangle x voxel solid angles
#endif
}

/// The interval [lo, hi] of s at the voxel p of the block from its pass's far
/// sums and its near triangles' sums.
LVDIF_HD void dipoleLocalFinish(const DipoleLocalFar& far, V3 p, V3 centre, double direct, double directMag, double& lo, double& hi)
{
  localInterval(far.poly.at(p - centre) + direct, far.err, std::fabs(far.mag), directMag, far.terms, lo, hi);
}

/// A voxel's interval after a pass: 0 decided (inside (m - 1/2, m + 1/2)
/// for an integer m), 1 open for another pass (gap then takes the distance
/// of its midpoint to the nearest half-integer, if smaller), 2 open but
/// within DipoleLocalMinMargin of a half-integer (left to the voxel's own
/// refinement: such a voxel must not drag the block's tolerance down).
LVDIF_HD int dipoleLocalVoxelState(double lo, double hi, double& gap)
{
  if (avoidsHalfIntegers(lo, hi)) return 0;
  const double c = 0.5 * (lo + hi);
  const double g = 0.5 - std::fabs(c - std::floor(c + 0.5));
  if (!(g > DipoleLocalMinMargin)) return 2;
  gap = g < gap ? g : gap;
  return 1;
}

/// The next pass's margin (the tolerance the open voxels need, as
/// insideDipolePass lowers it), and whether there is one.
LVDIF_HD bool dipoleLocalNextPass(int pass, bool anyOpen, double gap, double& margin)
{
  margin = std::fmin(0.25 * margin, gap);
  return anyOpen && pass + 1 < DipoleLocalPasses && margin > DipoleLocalMinMargin;
}

/// A block's voxels (X, inside the ball (centre, rho)) pass by pass from
/// DipoleFirstMargin, as dipoleLocalKernel runs them (the same clusters
/// visited, accepted and listed; the kernel's warp adds them in another
/// order, so its intervals may differ in the last bits) (list: room for
/// DipoleLocalNearCap entries): each gets an interval of s in [lo[v], hi[v]]
/// (lo > hi: none); a voxel whose interval avoids every half-integer is decided whatever its
/// crossing count and takes no further pass. Returns the voxels so decided,
/// -1 when a pass failed (then no intervals at all). errorScale: as
/// dipoleLocalWalk's.
LVDIF_HD int dipoleLocalBlock(const DipoleView& D, const DipoleLocalBlockVoxels& X, V3 centre, double rho, double* lo,
  double* hi, int* list, double errorScale = 1)
{
  unsigned long long open = 0;
  int present = 0;
  for (int v = 0; v < DipoleLocalVoxels; ++v)
  {
    lo[v] = 1;
    hi[v] = 0;
    if (X.has(v))
    {
      open |= 1ull << v;
      ++present;
    }
  }
  unsigned long long undecided = 0; // open voxels too near a half-integer for another pass
  double margin = DipoleFirstMargin, prevMargin = 0;
  double direct[DipoleLocalVoxels], directMag[DipoleLocalVoxels]; // the near sums, carried from pass to pass
  for (int v = 0; v < DipoleLocalVoxels; ++v) direct[v] = directMag[v] = 0;
  DipoleLocalWalk w;
  for (int pass = 0;; ++pass)
  {
#ifndef __CUDA_ARCH__
    if (D.work) ++D.work->calls; // passes
#endif
    w.start(pass > 0);
    while (true)
    {
      const bool done = dipoleLocalWalk(D, centre, rho, dipoleTolerance(D, margin), pass > 0 ? dipoleTolerance(D, prevMargin) : 0.0,
        w, list, 1, errorScale);
      if (w.overflow) break;
#ifndef __CUDA_ARCH__
      // the kernel's warp: lane l sums at voxels l and l + 32, those open
      if (D.work) D.work->laneTris += static_cast<unsigned long long>(w.far.near) * ((open & (open >> 32) & 0xffffffffull) ? 2 : 1);
#endif
      for (int v = 0; v < DipoleLocalVoxels; ++v)
        if ((open >> v) & 1) dipoleLocalNearSum(D, list, 1, w.far.near, X.at(v), direct[v], directMag[v]);
      w.far.near = 0;
      if (done) break;
    }
    if (w.overflow)
    {
      for (int v = 0; v < DipoleLocalVoxels; ++v)
      {
        lo[v] = 1;
        hi[v] = 0;
      }
      return -1;
    }
    double gap = margin;
    unsigned long long still = 0;
    for (int v = 0; v < DipoleLocalVoxels; ++v)
      if ((open >> v) & 1)
      {
        dipoleLocalFinish(w.far, X.at(v), centre, direct[v], directMag[v], lo[v], hi[v]);
        const int state = dipoleLocalVoxelState(lo[v], hi[v], gap);
        if (state == 1) still |= 1ull << v;
        if (state == 2) undecided |= 1ull << v;
      }
    open = still;
    prevMargin = margin;
    if (!dipoleLocalNextPass(pass, open != 0, gap, margin)) break;
  }
  undecided |= open;
  int undecidedCount = 0;
  for (int v = 0; v < DipoleLocalVoxels; ++v) undecidedCount += static_cast<int>((undecided >> v) & 1);
  return present - undecidedCount;
}

/// s at each of the points pts[0, n) (all within rho of centre): rigorous
/// intervals [lo[i], hi[i]] from far clusters summed as one local
/// polynomial and near triangles summed exactly at each point (a leaf is
/// first split into its triangles, each a cluster about its centroid).
/// Clusters are opened largest error first (starting from `start`, a cut as
/// DipoleTree::refine's, else the root) until every interval lies inside
/// (m - 1/2, m + 1/2) for an integer m (which decides the point whatever its
/// crossing count), or the work (node expansions + triangles x points)
/// passes `budget`. Returns the number of points so decided; every interval
/// holds either way (those not decided are returned too). A near triangle
/// is first replaced by its exact solid angle's Taylor polynomial about the
/// centre where that bound is tighter (triangleTaylor,
/// MeshToSdfTriangleLocal.h), and summed exactly only when opened again.
/// remainderScale multiplies the Taylor remainders (only a test sets it
/// below 1); counts (optional) is added to.
struct LocalBoundsCounts
{
  std::int64_t triangleTaylors = 0;  // triangles expanded about the centre
  std::int64_t exactSolidAngles = 0; // triangle x point solid angles summed exactly
  void add(const LocalBoundsCounts& o);
};
int localBounds(const DipoleTree& tree, V3 centre, double rho, const V3* pts, int n, double* lo, double* hi,
  std::int64_t budget, const std::vector<std::int32_t>* start = nullptr, double remainderScale = 1,
  LocalBoundsCounts* counts = nullptr);


} // namespace detail::meshtosdf
} // namespace lvdif
