// The GPU's decision of the winding sign with the correction s (w = K - s,
// MeshToSdfCudaDipole.cuh), as host/device functions: the CUDA kernels call
// them, and the tests run them on the CPU too (the whole volume against
// WindingSigner::signRow, bit for bit) where no GPU is at hand.
//
// Why the signs equal the CPU's bit for bit although the traversal differs
// (a stack and a tolerance per unit of mass lowered pass by pass, instead of
// the CPU's priority queue warm-started from the previous voxel), and
// although the blocks and voxels are bounded in another order (the GPU's
// work lists, below) and the two sides bound different blocks (CPU: balls
// about 16^3 and 4^3, then the voxels of a failed 4^3 block one by one from
// a local expansion, MeshToSdfDipoleLocal.h; GPU: 16^3, 4^3, then a local
// expansion per failed 4^3 block and 2^3 balls beyond its pool): both
// sides decide a voxel only when a
// rigorous interval of w (it contains the exact value: per-cluster bounds
// that are all rigorous, DipoleTree::refine's, localBounds' and the ones below, the leaf's
// per-triangle bound over a ball on both sides, and a slack of 1e-9 and more
// for the rounding) lies on one side of +-1/2, so two decided intervals
// cannot disagree, whichever block or pass produced them. A voxel neither
// side can decide so (w within ~1e-9 of +-1/2, every face summed) is
// decided by the canonical sum: every
// face of s in tree order with solidAngleCanonical (portableAtan2: only +, -,
// *, /, sqrt, so the same bits on both; DipoleTree::exactCanonical). If only
// one side decides by an interval, the canonical value lies within rounding
// of the exact one and so on the same side. Contraction is off on both
// sides (--fmad=false, -ffp-contract=off).
#pragma once

#include "MeshToSdfDipoleTree.h"
#include "MeshToSdfGeometry.h"

#include <cmath>

namespace lvdif
{
namespace detail::meshtosdf
{

/// Work of the decision, counted on the host only (the tests' work counts).
struct DipoleWork
{
  unsigned long long nodes = 0, tris = 0, triBounds = 0; // nodes visited; triangles summed exactly / bounded over a ball
  unsigned long long calls = 0;                          // boundDipole traversals
  // dipoleLocalBlock: per pass its near triangles x the voxels of the
  // busiest lane of the near sums (lane l: voxels l, l + 32)
  unsigned long long laneTris = 0;
};

struct DipoleView
{
  const DipoleTree::Node* nodes = nullptr; // node 0 the root
  const WeightedTri* tris = nullptr;       // in tree order
  int count = 0;                           // triangles (0: no correction)
  double rootMass = 0;
  DipoleWork* work = nullptr;               // host only (work counts of the tests)
};

// The blocks of voxels bounded as a whole, coarse to fine (edges in voxels,
// each a multiple of the next): a block whose parent has a bound takes it
// (it holds over the child too), the others are bounded themselves, the ball
// and so the error floor halving with the edge; the sign kernel reads the
// finest level.
constexpr int DipoleEdges[] = { 16, 4, 2 };
constexpr int DipoleLevels = static_cast<int>(sizeof(DipoleEdges) / sizeof(DipoleEdges[0]));
constexpr int DipoleBlock = DipoleEdges[DipoleLevels - 1];

LVDIF_HD bool dipoleDecided(double lo, double hi) { return !(lo < 0.5 && hi >= 0.5) && !(lo <= -0.5 && hi > -0.5); }
LVDIF_HD bool dipoleInsideOf(double w) { return std::fabs(w) >= 0.5; }

/// Distance from q to the segment ab.
LVDIF_HD double segmentDistance(V3 q, V3 a, V3 b)
{
  const V3 ab = b - a;
  const double l2 = dot(ab, ab);
  double t = l2 > 0 ? dot(q - a, ab) / l2 : 0.0;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return norm(q - (a + t * ab));
}

/// An upper bound L of |grad Omega_t| over the ball (q, rho), true when the
/// ball misses the triangle (Omega_t is smooth there). Two bounds, the
/// smaller taken: the boundary integral (grad Omega = the Biot-Savart
/// integral over the triangle's edges, |.| <= sum_e len_e / dist(p, e)^2;
/// small near the middle of a large face) and the area one (|grad| of the
/// integrand n.y/|y|^3 is <= 2/|y|^3, so <= 2 a / dist^3).
LVDIF_HD bool triangleLipschitz(const WeightedTri& t, V3 q, double rho, double& L)
{
  const V3 a = t.v[0], b = t.v[1], c = t.v[2];
  const double da = segmentDistance(q, a, b), db = segmentDistance(q, b, c), dc = segmentDistance(q, c, a);
  const V3 n = cross(b - a, c - a);
  const double nn = norm(n);
  double dist = da < db ? da : db;
  dist = dc < dist ? dc : dist;
  if (nn > 0 && dot(cross(b - a, q - a), n) >= 0 && dot(cross(c - b, q - b), n) >= 0 && dot(cross(a - c, q - c), n) >= 0)
  {
    const double plane = std::fabs(dot(q - a, n)) / nn; // q projects inside the face
    dist = plane < dist ? plane : dist;
  }
  if (!(dist > rho)) return false;
  const double ea = da - rho, eb = db - rho, ec = dc - rho, g = dist - rho;
  const double edges = norm(b - a) / (ea * ea) + norm(c - b) / (eb * eb) + norm(a - c) / (ec * ec);
  const double area = nn / (g * g * g); // 2 (nn / 2) / g^3
  L = edges < area ? edges : area;
  return true;
}

/// The error of a cluster's best rigorous bound over the ball (q, rho), r =
/// |c - q|, d = r - rho - R > 0 (R the cluster's radius, A its mass), the
/// smallest of three: 0 (order 0: |Omega| <= A / d^2), the dipole term at q
/// (order 1: error 2 A (R + rho) / d^3, |grad (y / |y|^3)| <= 2 / |y|^3) and
/// the dipole plus the second-order term (order 2, Barill et al.'s: the
/// Taylor remainder 3 A R^2 / (r - R)^4, |D^3 (1/|y|)| <= 3! / |y|^4, moved
/// over the ball by the Lipschitz bound 2 A / d^3). In units of 4 pi.
LVDIF_HD double clusterError(const DipoleTree::Node& nd, double r, double rho, double d, int& order)
{
  const double dq = r - nd.r;
  const double e0 = nd.mass / (d * d), e1 = 2 * nd.mass * (nd.r + rho) / (d * d * d);
  const double e2 = 3 * nd.mass * nd.r * nd.r / (dq * dq * dq * dq) + 2 * nd.mass * rho / (d * d * d);
  order = e2 < e1 ? (e2 < e0 ? 2 : 0) : (e1 < e0 ? 1 : 0);
  return order == 2 ? e2 : (order == 1 ? e1 : e0);
}

/// The value of that bound's expansion at q (y = c - q, r = |y|) and a bound
/// mag of its terms' magnitudes (for the rounding slack). In units of 4 pi.
LVDIF_HD double clusterValue(const DipoleTree::Node& nd, V3 y, double r, int order, double& mag)
{
  mag = 0;
  if (order == 0) return 0;
  const double r3 = r * r * r;
  double v = dot(nd.dipole, y) / r3;
  mag = std::fabs(v);
  if (order == 2)
  {
    // sum_ij T_ij d(y_i / |y|^3)/d y_j = tr T / r^3 - 3 y.T.y / r^5
    const double* T = nd.quad;
    const double yy[3] = { y.x, y.y, y.z };
    double yTy = 0, yTyAbs = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
      {
        const double t = yy[i] * T[3 * i + j] * yy[j];
        yTy += t;
        yTyAbs += std::fabs(t);
      }
    const double r5 = r3 * r * r;
    v += (T[0] + T[4] + T[8]) / r3 - 3 * yTy / r5;
    mag += (std::fabs(T[0]) + std::fabs(T[4]) + std::fabs(T[8])) / r3 + 3 * yTyAbs / r5;
  }
  return v;
}

/// boundDipole's step on one node over the ball (q, rho): 0 taken (its
/// terms added to the sums: the cluster's bound when its error is at most
/// tolPerMass x its mass, else a leaf summed exactly (rho == 0) or bounded
/// however loosely (rho > 0)), 1 opened (an inner node: its children are
/// next), -1 the ball meets a leaf's triangle (no bound at all).
LVDIF_HD int boundDipoleNode(const DipoleView& D, const DipoleTree::Node& nd, V3 q, double rho, double tolPerMass,
  double& value, double& err, double& mag, long long& terms, bool& approx)
{
  const V3 y = nd.c - q;
  const double r = norm(y);
  const double d = r - rho - nd.r;
  if (d > 0)
  {
    int order = 0;
    const double e = clusterError(nd, r, rho, d, order);
    if (e <= tolPerMass * nd.mass)
    {
      double m = 0;
      const double v = clusterValue(nd, y, r, order, m);
      value += v;
      err += e;
      mag += m;
      ++terms;
      approx = true;
      return 0;
    }
  }
  if (nd.left >= 0) return 1;
  if (rho > 0)
  {
    // a leaf over the ball: each triangle's exact value at q, plus its
    // Lipschitz bound over the ball (no d^-3 R term, so the error vanishes
    // with rho); none when the ball meets a triangle
#ifndef __CUDA_ARCH__
    if (D.work) D.work->triBounds += nd.count;
#endif
    for (int i = nd.first; i < nd.first + nd.count; ++i)
    {
      const WeightedTri& t = D.tris[i];
      double e = 0;
      if (!triangleLipschitz(t, q, rho, e)) return -1;
      const double a = t.w * solidAngle(q, t.v[0], t.v[1], t.v[2]);
      value += a;
      err += std::fabs(t.w) * rho * e;
      mag += std::fabs(a);
      ++terms;
    }
    approx = true;
    return 0;
  }
#ifndef __CUDA_ARCH__
  if (D.work) D.work->tris += nd.count;
#endif
  for (int i = nd.first; i < nd.first + nd.count; ++i)
  {
    const WeightedTri& t = D.tris[i];
    const double a = t.w * solidAngle(q, t.v[0], t.v[1], t.v[2]);
    value += a;
    mag += std::fabs(a);
    ++terms;
  }
  return 0;
}

/// boundDipole's interval from its sums: the rounding of the sums and of the
/// exact solid angles (the CPU's slack, with every term counted instead of
/// the open clusters: never smaller; it bounds the rounding of any order of
/// the sums, so the GPU's warp bound shares it).
LVDIF_HD void boundDipoleInterval(double value, double err, double mag, long long terms, double& sLo, double& sHi)
{
  const double slack = 1e-9 + 1e-12 * (mag + err) * static_cast<double>(terms + 1);
  sLo = (value - err) / FourPi - slack;
  sHi = (value + err) / FourPi + slack;
}

/// A rigorous interval [sLo, sHi] of s over the ball (q, rho). Clusters at
/// d > 0 whose error is at most tolPerMass x their mass are taken as bounds
/// (DipoleTree::refine's formulas), others opened; leaves are summed exactly
/// (rho == 0) or bounded however loosely (rho > 0; false when one is too
/// close). approx: some cluster was bounded, not summed (refining can help).
LVDIF_HD bool boundDipole(const DipoleView& D, V3 q, double rho, double tolPerMass, double& sLo, double& sHi,
  bool& approx)
{
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  double value = 0, err = 0, mag = 0;
  long long terms = 0;
  approx = false;
#ifndef __CUDA_ARCH__
  if (D.work) ++D.work->calls;
#endif
  while (top > 0)
  {
    const DipoleTree::Node nd = D.nodes[stack[--top]];
#ifndef __CUDA_ARCH__
    if (D.work) ++D.work->nodes;
#endif
    const int step = boundDipoleNode(D, nd, q, rho, tolPerMass, value, err, mag, terms, approx);
    if (step < 0) return false;
    if (step > 0)
    {
      if (top + 2 > 64) return false;
      stack[top++] = nd.left;
      stack[top++] = nd.right;
    }
  }
  boundDipoleInterval(value, err, mag, terms, sLo, sHi);
  return true;
}

/// DipoleTree::exactCanonical: the same terms in the same order.
LVDIF_HD double dipoleExactCanonical(const DipoleView& D, V3 p)
{
  double s = 0;
  for (int i = 0; i < D.count; ++i)
  {
    const WeightedTri& t = D.tris[i];
    s += t.w * solidAngleCanonical(p, t.v[0], t.v[1], t.v[2]);
  }
  return s / FourPi;
}

/// Tolerance per unit of mass that keeps the total error of a bound below
/// margin / 2 (in units of the winding number).
LVDIF_HD double dipoleTolerance(const DipoleView& D, double margin) { return 0.5 * margin * FourPi / D.rootMass; }

/// What one pass of insideDipole makes of its bound (ok: boundDipole's
/// result, the interval [lo, hi] of s at p and approx; the GPU's warp bound
/// shares it): 1 decided (inside set), 0 not yet (margin lowered for the
/// next pass), -1 no interval will decide (the canonical sum does).
LVDIF_HD int insideDipoleDecide(bool ok, double lo, double hi, bool approx, int K, double& margin, bool& inside)
{
  if (!ok) return -1;
  if (dipoleDecided(K - hi, K - lo))
  {
    inside = dipoleInsideOf(0.5 * ((K - hi) + (K - lo)));
    return 1;
  }
  if (!approx) return -1; // everything summed exactly, within rounding of +-1/2
  const double c = K - 0.5 * (lo + hi);
  const double left = std::fmin(std::fabs(c - 0.5), std::fabs(c + 0.5));
  margin = std::fmin(0.25 * margin, left);
  return margin > 1e-10 ? 0 : -1;
}

/// One pass of insideDipole at the given margin (insideDipoleDecide's results).
LVDIF_HD int insideDipolePass(const DipoleView& D, int K, V3 p, double& margin, bool& inside)
{
  double lo = 0, hi = 0;
  bool approx = false;
  const bool ok = boundDipole(D, p, 0, dipoleTolerance(D, margin), lo, hi, approx);
  return insideDipoleDecide(ok, lo, hi, approx, K, margin, inside);
}

/// The first pass's margin: a loose tolerance decides most voxels cheaply (w mostly near 0 or 1).
constexpr double DipoleFirstMargin = 0.8;

/// Inside or not at p, whose closed chain has K crossings: w = K - s decided
/// by rigorous intervals, the tolerance lowered 4x a pass (or to the margin
/// the last estimate left), else by the canonical sum (counted in full).
/// margin: the pass to start with (a listed voxel's next pass).
LVDIF_HD bool insideDipole(const DipoleView& D, int K, V3 p, unsigned long long& full, double margin = DipoleFirstMargin)
{
  bool inside = false;
  while (true)
  {
    const int r = insideDipolePass(D, K, p, margin, inside);
    if (r > 0) return inside;
    if (r < 0) break;
  }
  ++full;
  return dipoleInsideOf(K - dipoleExactCanonical(D, p));
}

/// The ball around the voxels p0 .. p1 (a block); rho also covers the
/// rounding of the voxel positions as the rows compute them.
LVDIF_HD void dipoleBlockBall(V3 p0, V3 p1, V3& centre, double& rho)
{
  centre = 0.5 * (p0 + p1);
  const double half = 0.5 * norm(p1 - p0);
  rho = half + 1e-9 * (half + std::fabs(centre.x) + std::fabs(centre.y) + std::fabs(centre.z));
}

/// At most this many passes bound a block.
constexpr int DipoleBlockPasses = 2;

/// What one pass of dipoleBlockBound makes of its bound (ok: boundDipole's
/// result over the ball, [l, u] and approx; the GPU's warp bound shares it):
/// 1 a bound [lo, hi], 0 not yet (margin lowered for the next pass), -1 none.
LVDIF_HD int dipoleBlockDecide(bool ok, double l, double u, bool approx, double& margin, double& lo, double& hi)
{
  if (!ok) return -1;
  const double c = 0.5 * (l + u), n = std::floor(c + 0.5);
  if (l > n - 0.5 && u < n + 0.5)
  {
    lo = l;
    hi = u;
    return 1;
  }
  const double left = 0.5 - std::fabs(c - n);
  if (!approx || left < 0.05) return -1; // the voxels will do better
  margin = std::fmin(0.25 * margin, left);
  return 0;
}

/// One pass of dipoleBlockBound at the given margin (dipoleBlockDecide's results).
LVDIF_HD int dipoleBlockPass(const DipoleView& D, V3 centre, double rho, double& margin, double& lo, double& hi)
{
  double l = 0, u = 0;
  bool approx = false;
  const bool ok = boundDipole(D, centre, rho, dipoleTolerance(D, margin), l, u, approx);
  return dipoleBlockDecide(ok, l, u, approx, margin, lo, hi);
}

/// s over the ball about the voxels p0 .. p1 (a block): [lo, hi] when it lies
/// inside (n - 1/2, n + 1/2) for an integer n (no half-integer inside), which
/// decides every voxel of the block whatever its crossing count K (K - s
/// then avoids +-1/2; n = 0 is the CPU's boundCorrection over blocks; s near
/// 1 occurs inside caps over reversed patches); lo > hi: none.
LVDIF_HD void dipoleBlockBound(const DipoleView& D, V3 p0, V3 p1, double& lo, double& hi)
{
  V3 centre;
  double rho = 0;
  dipoleBlockBall(p0, p1, centre, rho);
  lo = 1;
  hi = 0;
  double margin = DipoleFirstMargin;
  for (int pass = 0; pass < DipoleBlockPasses; ++pass)
  {
    const int r = dipoleBlockPass(D, centre, rho, margin, lo, hi);
    if (r != 0) return;
  }
}

// Work lists. On the GPU the blocks of a level whose parent has no bound,
// and the voxels their block leaves undecided, are listed first and then
// bounded or refined, each by a whole warp (boundDipoleWarp, since session
// 17; one per thread of full warps before): with one thread per block of
// the level or per voxel of the row, most lanes of a warp idled while a few
// refined (MeshToSdfDipoleDecide.WorkCounts: the warps' largest work summed,
// 2-3x the listed order's on damaged armadillos). Only the order of the work
// changes: each block's bound and each voxel's decision is the same function
// of the same inputs (the tests run these helpers too; the warp adds the
// same terms in another order, inside the slack).

/// Block c (0 .. ratio^3 - 1, x fastest) inside the block `parent` of the
/// level above (pbx x pby blocks per layer): its index at this level (bx x by
/// x bz blocks), -1 when it lies outside the grid.
LVDIF_HD long long dipoleChildBlock(long long parent, long long c, long long ratio, long long pbx, long long pby,
  long long bx, long long by, long long bz)
{
  const long long x = (parent % pbx) * ratio + c % ratio, y = ((parent / pbx) % pby) * ratio + (c / ratio) % ratio;
  const long long z = (parent / (pbx * pby)) * ratio + c / (ratio * ratio);
  return x < bx && y < by && z < bz ? x + bx * (y + by * z) : -1;
}

/// A listed voxel: its index in the slab and its crossing count in one word
/// (|K| < 2^19: larger counts are decided where they are found).
constexpr int DipoleKBits = 20;
LVDIF_HD bool dipoleListable(int K) { return K > -(1 << (DipoleKBits - 1)) && K < (1 << (DipoleKBits - 1)); }
LVDIF_HD unsigned long long dipoleListVoxel(long long v, int K)
{
  return (static_cast<unsigned long long>(v) << DipoleKBits) | static_cast<unsigned long long>(K + (1 << (DipoleKBits - 1)));
}
LVDIF_HD void dipoleListedVoxel(unsigned long long e, long long& v, int& K)
{
  v = static_cast<long long>(e >> DipoleKBits);
  K = static_cast<int>(e & ((1ull << DipoleKBits) - 1)) - (1 << (DipoleKBits - 1));
}

/// A voxel of a row whose +x ray gave K crossings, decided by its block's
/// bound (lo > hi: none) when that bound decides it; else false and the
/// voxel is refined (insideDipole).
LVDIF_HD bool dipoleBlockDecides(int K, double lo, double hi, bool& inside)
{
  if (!(lo <= hi && dipoleDecided(K - hi, K - lo))) return false;
  inside = dipoleInsideOf(0.5 * ((K - hi) + (K - lo)));
  return true;
}

} // namespace detail::meshtosdf
} // namespace lvdif
