// Dipole tree with rigorous error bounds: see MeshToSdfDipoleTree.h.
#include "MeshToSdfDipoleTree.h"

#include "MeshToSdfDipoleDecide.h" // triangleLipschitz, shared with the GPU's block bounds

#include <algorithm>
#include <cmath>
#include <limits>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
constexpr int LeafSize = 4;
} // namespace

DipoleTree::DipoleTree(std::vector<WeightedTri> tris)
  : Tris(std::move(tris))
{
  if (this->Tris.empty()) return;
  // top-down median splits on the longest axis of the centroid bounds
  struct Todo
  {
    std::int32_t node, first, count;
  };
  this->Nodes.reserve(2 * this->Tris.size() / LeafSize + 2);
  this->Nodes.emplace_back();
  std::vector<Todo> todo{ { 0, 0, static_cast<std::int32_t>(this->Tris.size()) } };
  auto centroid = [](const WeightedTri& t) { return (1.0 / 3.0) * (t.v[0] + t.v[1] + t.v[2]); };
  while (!todo.empty())
  {
    const Todo d = todo.back();
    todo.pop_back();
    V3 lo{ 1e300, 1e300, 1e300 }, hi{ -1e300, -1e300, -1e300 };
    for (std::int32_t i = d.first; i < d.first + d.count; ++i)
      for (const V3& v : this->Tris[i].v)
      {
        lo = { std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z) };
        hi = { std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z) };
      }
    Node nd;
    nd.c = 0.5 * (lo + hi);
    for (std::int32_t i = d.first; i < d.first + d.count; ++i)
    {
      const WeightedTri& t = this->Tris[i];
      const V3 an = 0.5 * cross(t.v[1] - t.v[0], t.v[2] - t.v[0]); // area times unit normal
      nd.dipole = nd.dipole + t.w * an;
      nd.mass += std::fabs(t.w) * norm(an);
      for (const V3& v : t.v) nd.r = std::max(nd.r, norm(v - nd.c));
      const V3 n = t.w * an, g = centroid(t) - nd.c;
      const double ni[3] = { n.x, n.y, n.z }, gj[3] = { g.x, g.y, g.z };
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) nd.quad[3 * i + j] += ni[i] * gj[j];
    }
    nd.r *= 1 + 1e-12; // rounding of the distances above
    if (d.count > LeafSize)
    {
      V3 clo{ 1e300, 1e300, 1e300 }, chi{ -1e300, -1e300, -1e300 };
      for (std::int32_t i = d.first; i < d.first + d.count; ++i)
      {
        const V3 c = centroid(this->Tris[i]);
        clo = { std::min(clo.x, c.x), std::min(clo.y, c.y), std::min(clo.z, c.z) };
        chi = { std::max(chi.x, c.x), std::max(chi.y, c.y), std::max(chi.z, c.z) };
      }
      const V3 ext = chi - clo;
      const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
      const std::int32_t half = d.count / 2;
      std::nth_element(this->Tris.begin() + d.first, this->Tris.begin() + d.first + half,
        this->Tris.begin() + d.first + d.count, [&](const WeightedTri& a, const WeightedTri& b) {
          return centroid(a)[axis] < centroid(b)[axis];
        });
      nd.left = static_cast<std::int32_t>(this->Nodes.size());
      nd.right = nd.left + 1;
      this->Nodes.emplace_back();
      this->Nodes.emplace_back();
      todo.push_back({ nd.left, d.first, half });
      todo.push_back({ nd.right, d.first + half, d.count - half });
    }
    nd.first = d.first;
    nd.count = d.count;
    this->Nodes[d.node] = nd;
  }
}

DipoleTree::Refined DipoleTree::refine(V3 q, double rho, const std::function<int(double, double)>& goal, double& sLo,
  double& sHi, std::int64_t& leafTris, std::vector<std::int32_t>* cut) const
{
  thread_local std::vector<std::int32_t> summed; // leaves summed exactly (part of the final cut)
  summed.clear();
  struct Open
  {
    double err, value, mag; // in units of 4 pi; mag bounds |value|'s terms (the rounding slack)
    std::int32_t node;
    bool operator<(const Open& o) const { return this->err < o.err; }
  };
  thread_local std::vector<Open> heap;
  heap.clear();
  // leaves bounded over the ball triangle by triangle (rho > 0): they cannot
  // get tighter, so they leave the heap but stay in the sums and the cut
  thread_local std::vector<Open> frozen;
  frozen.clear();
  double frozenErr = 0;
  double value = 0, err = 0, mag = 0; // sums over the open clusters (+ the exact leaves in value)
  int unbounded = 0;                  // open clusters too close for any bound
  bool heapOrder = true; // a starting cut is visited unordered, made a heap only when refined
  auto visit = [&](std::int32_t id) {
    const Node& nd = this->Nodes[id];
    const V3 y = nd.c - q;
    const double r = norm(y);
    const double d = r - rho - nd.r;
    Open o{ std::numeric_limits<double>::infinity(), 0, 0, id };
    if (d > 0)
    {
      // the GPU's bounds (order 0, 1 or 2: the second-order term shrinks the
      // error of a cluster a few radii away by (R + rho) / d against the
      // dipole's, so fewer clusters open where s must be known closely)
      int order = 0;
      o.err = clusterError(nd, r, rho, d, order);
      o.value = clusterValue(nd, y, r, order, o.mag);
      value += o.value;
      err += o.err;
      mag += o.mag;
    }
    else
    {
      ++unbounded;
    }
    heap.push_back(o);
    if (heapOrder) std::push_heap(heap.begin(), heap.end());
  };
  if (this->Nodes.empty())
  {
    sLo = sHi = 0;
    return goal(0, 0) > 0 ? Refined::Done : Refined::Exact;
  }
  if (cut && !cut->empty())
  {
    heapOrder = false;
    heap.reserve(cut->size() + 2);
    for (const std::int32_t id : *cut) visit(id);
  }
  else
  {
    visit(0);
  }
  auto finish = [&](Refined r) {
    if (cut)
    {
      cut->clear();
      for (const Open& o : heap) cut->push_back(o.node);
      for (const Open& o : frozen) cut->push_back(o.node);
      cut->insert(cut->end(), summed.begin(), summed.end());
    }
    return r;
  };
  while (true)
  {
    // slack: rounding of the running sums and of the exact solid angles
    const double slack = 1e-9 + 1e-12 * (mag + err) * static_cast<double>(heap.size() + frozen.size() + 1);
    if (unbounded == 0)
    {
      sLo = (value - err) / FourPi - slack;
      sHi = (value + err) / FourPi + slack;
      const int g = goal(sLo, sHi);
      if (g > 0) return finish(Refined::Done);
      if (g < 0) return finish(Refined::Failed);
      if (heap.empty()) return finish(frozen.empty() ? Refined::Exact : Refined::Failed);
    }
    if (!heapOrder)
    {
      std::make_heap(heap.begin(), heap.end());
      heapOrder = true;
    }
    std::pop_heap(heap.begin(), heap.end());
    const Open o = heap.back();
    heap.pop_back();
    if (std::isfinite(o.err))
    {
      value -= o.value;
      err -= o.err;
      mag -= o.mag;
    }
    else
    {
      --unbounded;
    }
    const Node& nd = this->Nodes[o.node];
    if (nd.left >= 0)
    {
      visit(nd.left);
      visit(nd.right);
      continue;
    }
    if (rho > 0)
    {
      // a leaf over the ball: each triangle's exact value at q plus rho times
      // a Lipschitz bound of its solid angle on the ball (the GPU's block
      // bound, MeshToSdfDipoleDecide.h: no error floor 2 A R / d^3, so it
      // shrinks with the ball), kept if tighter than the cluster's bound
      double v = 0, e = 0, m = 0;
      bool bounded = true;
      for (std::int32_t i = nd.first; i < nd.first + nd.count && bounded; ++i)
      {
        const WeightedTri& t = this->Tris[i];
        double L = 0;
        bounded = triangleLipschitz(t, q, rho, L);
        const double a = t.w * solidAngle(q, t.v[0], t.v[1], t.v[2]);
        v += a;
        e += std::fabs(t.w) * rho * L;
        m += std::fabs(a);
      }
      const bool tighter = bounded && e < o.err;
      const Open b = tighter ? Open{ e, v, m, o.node } : o;
      if (!std::isfinite(b.err))
      {
        heap.push_back(o); // the ball meets a triangle: keep the cut whole
        return finish(Refined::Failed);
      }
      value += b.value;
      err += b.err;
      mag += b.mag;
      frozen.push_back(b);
      frozenErr += b.err;
      // give up when even exact values for everything else would leave the
      // goal unmet (the frozen error alone around the present estimate):
      // only a guess (the estimate moves as clusters open), so it costs no
      // rigour, only the work a ball that cannot be bounded would waste
      const double slack = 1e-9 + 1e-12 * (mag + err) * static_cast<double>(heap.size() + frozen.size() + 1);
      if (goal((value - frozenErr) / FourPi - slack, (value + frozenErr) / FourPi + slack) <= 0)
        return finish(Refined::Failed);
      continue;
    }
    for (std::int32_t i = nd.first; i < nd.first + nd.count; ++i)
    {
      const WeightedTri& t = this->Tris[i];
      const double a = t.w * solidAngle(q, t.v[0], t.v[1], t.v[2]);
      value += a;
      mag += std::fabs(a);
    }
    leafTris += nd.count;
    summed.push_back(o.node);
    if (heap.empty() && frozen.empty()) err = 0; // only exact sums left: drop the rounding of the running error
  }
}

double DipoleTree::exact(V3 p) const
{
  double s = 0;
  for (const WeightedTri& t : this->Tris) s += t.w * solidAngle(p, t.v[0], t.v[1], t.v[2]);
  return s / FourPi;
}

double DipoleTree::exactCanonical(V3 p) const
{
  double s = 0;
  for (const WeightedTri& t : this->Tris) s += t.w * solidAngleCanonical(p, t.v[0], t.v[1], t.v[2]);
  return s / FourPi;
}

} // namespace detail::meshtosdf
} // namespace lvdif
