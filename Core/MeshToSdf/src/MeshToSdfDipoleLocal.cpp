// Local expansions of the correction s over a block: see MeshToSdfDipoleLocal.h.
#include "MeshToSdfDipoleLocal.h"

#include "MeshToSdfDipoleDecide.h" // clusterValue (the value at the centre is the same term)

#include <algorithm>
#include <cmath>
#include <limits>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
constexpr auto& Sym = LocalPoly::Sym;
// solidAngle (Van Oosterom & Strackee 1983) for the near triangles' sums
// here: atan(num / den) where den > 0 (the same angle within an ulp or two,
// far inside the check's 1e-9 slack; libm's atan2 was 15 % of patch30's time)
double nearSolidAngle(V3 p, V3 a, V3 b, V3 c)
{
  const V3 x = a - p, y = b - p, z = c - p;
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = dot(x, cross(y, z));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(x, z) * ly + dot(y, z) * lx;
  return 2.0 * (den > 0 ? std::atan(num / den) : std::atan2(num, den));
}
} // namespace

void LocalPoly::add(const LocalPoly& o, double sign)
{
  this->v += sign * o.v;
  for (int i = 0; i < 3; ++i) this->g[i] += sign * o.g[i];
  for (int i = 0; i < 6; ++i) this->H[i] += sign * o.H[i];
}

LocalPoly clusterLocal(const DipoleTree::Node& nd, V3 y0, int order)
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
  double a = 0, t = 0, w[3] = {}; // w = u + v
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
      p.H[Sym[k][l]] = h;
    }
  return p;
}

namespace
{
// sum |T_ij| of a cluster's second-order term
double quadAbsSum(const DipoleTree::Node& nd)
{
  double t = 0;
  for (const double q : nd.quad) t += std::fabs(q);
  return t;
}

// clusterLocalRemainder from |D| and sum |T_ij| (computed once per cluster by clusterLocalError)
double localRemainder(double dipoleNorm, double quadAbs, double rMin, double rho, int order)
{
  // |x|^3 / 3! times the third derivatives: |D| 4! / rMin^5 (dipole), sum |T_ij| 5! / rMin^6 (second order)
  const double r5 = rMin * rMin * rMin * rMin * rMin;
  double third = 24 * dipoleNorm / r5;
  if (order == 2) third += 120 * quadAbs / (r5 * rMin);
  return rho * rho * rho * third / 6;
}
} // namespace

double clusterLocalRemainder(const DipoleTree::Node& nd, double rMin, double rho, int order)
{
  return localRemainder(norm(nd.dipole), order == 2 ? quadAbsSum(nd) : 0.0, rMin, rho, order);
}

double clusterLocalError(const DipoleTree::Node& nd, double r0, double rho, int& order, double remainderScale)
{
  const double d = r0 - rho - nd.r;
  order = 0;
  if (!(d > 0)) return std::numeric_limits<double>::infinity();
  const double rMin = r0 - rho, R = nd.r, A = nd.mass;
  const double dn = norm(nd.dipole), qa = quadAbsSum(nd);
  const double e0 = A / (d * d);
  const double e1 = 2 * A * R / (d * d * d) + remainderScale * localRemainder(dn, qa, rMin, rho, 1);
  const double e2 = 3 * A * R * R / (d * d * d * d) + remainderScale * localRemainder(dn, qa, rMin, rho, 2);
  order = e2 < e1 ? (e2 < e0 ? 2 : 0) : (e1 < e0 ? 1 : 0);
  return order == 2 ? e2 : (order == 1 ? e1 : e0);
}

int localBounds(const DipoleTree& tree, V3 centre, double rho, const V3* pts, int n, double* lo, double* hi,
  std::int64_t budget, const std::vector<std::int32_t>* start, double remainderScale)
{
  for (int i = 0; i < n; ++i)
  {
    lo[i] = -std::numeric_limits<double>::infinity();
    hi[i] = std::numeric_limits<double>::infinity();
  }
  if (tree.empty())
  {
    std::fill(lo, lo + n, 0.0);
    std::fill(hi, hi + n, 0.0);
    return n;
  }
  const auto& nodes = tree.nodes();
  const auto& tris = tree.tris();
  struct Open
  {
    double err;
    std::int32_t node;
    int order;
    LocalPoly poly; // the cluster's expansion, subtracted again when it is opened
  };
  // the heap holds (error, slot in the pool): the sift moves 16 bytes, not
  // the 104 of an Open (the same comparisons, so the same order of opening)
  struct Key
  {
    double err;
    std::int32_t slot;
    bool operator<(const Key& o) const { return this->err < o.err; }
  };
  thread_local std::vector<Key> heapTL;
  thread_local std::vector<Open> poolTL;
  thread_local std::vector<double> directTL, directMagTL; // per point: exact sums of the near triangles
  thread_local std::vector<int> openTL; // the points not decided yet
  thread_local std::vector<V3> offTL; // per point: its offset from the centre
  // bound once: each use of a thread_local in the loops would look its address up again
  std::vector<Key>& heap = heapTL;
  std::vector<Open>& pool = poolTL;
  std::vector<double>& direct = directTL;
  std::vector<double>& directMag = directMagTL;
  std::vector<int>& open = openTL;
  std::vector<V3>& off = offTL;
  heap.clear();
  pool.clear();
  off.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) off[static_cast<std::size_t>(i)] = pts[i] - centre;
  direct.assign(static_cast<std::size_t>(n), 0.0);
  directMag.assign(static_cast<std::size_t>(n), 0.0);
  open.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) open[static_cast<std::size_t>(i)] = i;
  LocalPoly poly;            // the far clusters' expansions summed
  double err = 0, mag = 0;   // their error over the ball; a bound of their terms (rounding slack)
  int unbounded = 0, decided = 0;
  std::int64_t work = 0, terms = 0;
  auto magOf = [&](const DipoleTree::Node& nd, double rMin) {
    // generous bound of every term's size in the expansion's sums (the rounding slack)
    double t = 0;
    for (const double q : nd.quad) t += std::fabs(q);
    const double s = rho / rMin;
    return 200 * (nd.mass / (rMin * rMin) + t / (rMin * rMin * rMin)) * (1 + s + s * s);
  };
  // id >= 0: a node of the tree; id = -(t + 1): triangle t of a leaf on its
  // own, a cluster about its centroid (second-order term 0, radius its
  // farthest vertex), so a leaf too near for its own expansion is first
  // split into its triangles, and only those still too near are summed
  DipoleTree::Node triNode;
  auto nodeOf = [&](std::int32_t id) -> const DipoleTree::Node& {
    if (id >= 0) return nodes[static_cast<std::size_t>(id)];
    const WeightedTri& t = tris[static_cast<std::size_t>(-id - 1)];
    triNode = DipoleTree::Node{};
    triNode.c = (1.0 / 3.0) * (t.v[0] + t.v[1] + t.v[2]);
    const V3 an = 0.5 * cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    triNode.dipole = t.w * an;
    triNode.mass = std::fabs(t.w) * norm(an);
    for (const V3& v : t.v) triNode.r = std::max(triNode.r, norm(v - triNode.c));
    triNode.r *= 1 + 1e-12; // rounding of the distances above
    triNode.first = -id - 1;
    triNode.count = 1;
    return triNode;
  };
  auto visit = [&](std::int32_t id) {
    const DipoleTree::Node& nd = nodeOf(id);
    const V3 y = nd.c - centre;
    const double r0 = norm(y);
    Open o{ 0, id, 0, {} };
    o.err = clusterLocalError(nd, r0, rho, o.order, remainderScale);
    if (std::isfinite(o.err))
    {
      err += o.err;
      mag += magOf(nd, r0 - rho);
      if (o.order > 0)
      {
        o.poly = clusterLocal(nd, y, o.order);
        poly.add(o.poly, 1);
      }
    }
    else
    {
      ++unbounded;
    }
    work += 2;
    ++terms;
    heap.push_back(Key{ o.err, static_cast<std::int32_t>(pool.size()) });
    pool.push_back(o);
    std::push_heap(heap.begin(), heap.end());
  };
  auto close = [&](const Open& o) {
    if (!std::isfinite(o.err))
    {
      --unbounded;
      return;
    }
    err -= o.err; // mag keeps the closed terms: their rounding stays in the sums
    if (o.order > 0) poly.add(o.poly, -1);
  };
  if (start && !start->empty())
    for (const std::int32_t id : *start) visit(id);
  else
    visit(0);
  // intervals of every point not yet decided; checked again each time the
  // error has halved (a check costs a quadratic per point)
  double checkAt = std::numeric_limits<double>::infinity(), checkedErr = checkAt;
  auto check = [&] {
    // the rounding slack: 1e-9 + 1e-12 (|mag| + err + directMag) (terms + 1),
    // its common factors hoisted; 1 / (4 pi) multiplied (within an ulp of the
    // division, far inside the slack)
    const double slackBase = 1e-9, slackScale = 1e-12 * static_cast<double>(terms + 1), slackFar = std::fabs(mag) + err;
    constexpr double InvFourPi = 1.0 / FourPi;
    std::size_t kept = 0;
    for (const int i : open)
    {
      const auto k = static_cast<std::size_t>(i);
      const double v = poly.at(off[k]) + direct[k];
      const double slack = slackBase + slackScale * (slackFar + directMag[k]);
      const double l = (v - err) * InvFourPi - slack, u = (v + err) * InvFourPi + slack;
      lo[i] = l;
      hi[i] = u;
      if (avoidsHalfIntegers(l, u))
        ++decided;
      else
        open[kept++] = i;
    }
    work += static_cast<std::int64_t>(open.size()) / 8;
    open.resize(kept);
    checkAt = 0.5 * err;
    checkedErr = err;
  };
  while (decided < n)
  {
    // checked when the error has halved, and before a leaf is summed at
    // every open point if the error fell since (a check costs a quadratic
    // per point, a leaf a few solid angles per point)
    const bool leafNext = !heap.empty() && pool[static_cast<std::size_t>(heap.front().slot)].node < 0;
    if (unbounded == 0 && (err <= checkAt || heap.empty() || (leafNext && err < checkedErr)))
    {
      check();
      if (decided == n || heap.empty()) break;
    }
    if (work > budget) break;
    std::pop_heap(heap.begin(), heap.end());
    const Open o = pool[static_cast<std::size_t>(heap.back().slot)];
    heap.pop_back();
    close(o);
    const DipoleTree::Node& nd = nodeOf(o.node);
    if (nd.left >= 0)
    {
      visit(nd.left);
      visit(nd.right);
      continue;
    }
    if (o.node >= 0 && nd.count > 1)
    {
      for (std::int32_t t = nd.first; t < nd.first + nd.count; ++t) visit(-t - 1);
      continue;
    }
    // a near triangle (or a leaf of one): summed exactly at every open point
    for (std::int32_t t = nd.first; t < nd.first + nd.count; ++t)
    {
      const WeightedTri& tri = tris[static_cast<std::size_t>(t)];
      for (const int i : open)
      {
        const double a = tri.w * nearSolidAngle(pts[i], tri.v[0], tri.v[1], tri.v[2]);
        direct[static_cast<std::size_t>(i)] += a;
        directMag[static_cast<std::size_t>(i)] += std::fabs(a);
      }
      ++terms;
    }
    work += static_cast<std::int64_t>(nd.count) * static_cast<std::int64_t>(open.size());
    if (heap.empty()) err = 0; // nothing bounded left: drop the rounding of the running error
  }
  return decided;
}

} // namespace detail::meshtosdf
} // namespace lvdif
