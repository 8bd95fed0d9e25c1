// BVH for mesh to SDF: exact nearest-triangle queries (branch and bound on
// box distances) and ray crossings for the winding-number signs.
#include "MeshToSdfInternal.h"

#include "lvdif/Memory.h"

#include <algorithm>
#include <cmath>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
constexpr int LeafSize = 4;
} // namespace

/// Nodes of a subtree over `count` triangles (median splits, leaves of at
/// most LeafSize): lets parallel tasks place their nodes deterministically.
/// The counts of one depth differ by at most one, so the recursion meets
/// O(log n) distinct counts: they are computed once (memo) and looked up
/// read-only by the build's tasks (recomputing them per node visited every
/// node of the left subtree again: O(n log n)). (Depth never reaches 60: 31
/// halvings bring any int32 count to LeafSize.)
class BvhSubtreeNodes
{
public:
  explicit BvhSubtreeNodes(std::int32_t n) { this->of(n); }
  std::int32_t operator()(std::int32_t count) const
  {
    for (const auto& e : this->Memo)
      if (e.first == count) return e.second;
    return 1; // count <= LeafSize (never stored)
  }

private:
  std::int32_t of(std::int32_t count)
  {
    if (count <= LeafSize) return 1;
    for (const auto& e : this->Memo)
      if (e.first == count) return e.second;
    const std::int32_t half = count / 2;
    const std::int32_t nodes = 1 + this->of(half) + this->of(count - half);
    this->Memo.push_back({ count, nodes });
    return nodes;
  }
  std::vector<std::pair<std::int32_t, std::int32_t>> Memo;
};

/// Centroids computed once in parallel; the recursive build then touches
/// only this compact array (the triangle records are 328 bytes each), and the
/// median splits permute the centroids themselves (contiguous, no
/// indirection; the same permutation as sorting indices by them). Subtrees of
/// more than 2048 triangles build as OpenMP tasks; the node layout (preorder)
/// does not depend on the threads. The boxes come last, bottom-up, from the
/// leaf-ordered compact copies (exact min/max: the same bits as boxes taken
/// during the build).
Bvh::Bvh(const TriList& tris)
  : Tris(tris)
{
  const std::int32_t n = static_cast<std::int32_t>(tris.size());
  // fresh arrays first touched by resize(), serially: huge pages (Memory.h)
  resizeLarge(this->Order, tris.size());
  BuildData d;
  resizeLarge(d.ref, tris.size());
#pragma omp parallel for schedule(static)
  for (std::int32_t i = 0; i < n; ++i)
  {
    const Tri& t = tris[i];
    auto& r = d.ref[i];
    for (int a = 0; a < 3; ++a) r.c[a] = t.v[0][a] + t.v[1][a] + t.v[2][a];
    r.tri = i;
  }
  const BvhSubtreeNodes nodesOf(n);
  d.subtreeNodes = &nodesOf;
  resizeLarge(this->Nodes, static_cast<std::size_t>(nodesOf(n)));
#pragma omp parallel
#pragma omp single
  this->build(d, 0, 0, n, 0);
  resizeLarge(this->Leaves, tris.size());
#pragma omp parallel for schedule(static)
  for (std::int32_t i = 0; i < n; ++i)
  {
    this->Order[i] = d.ref[i].tri;
    const Tri& t = tris[this->Order[i]];
    LeafTri& l = this->Leaves[i];
    for (int k = 0; k < 3; ++k) l.v[k] = t.v[k];
    l.n = t.n;
  }
  // leaf boxes in parallel, then the inner nodes from their children
  // (preorder: children come after their parent)
  const std::int64_t nodeCount = static_cast<std::int64_t>(this->Nodes.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t id = 0; id < nodeCount; ++id)
  {
    Node& node = this->Nodes[id];
    if (node.left >= 0) continue;
    for (int a = 0; a < 3; ++a)
    {
      node.lo[a] = 1e300;
      node.hi[a] = -1e300;
    }
    for (std::int32_t i = node.first; i < node.first + node.count; ++i)
    {
      const V3* v = this->Leaves[i].v;
      for (int a = 0; a < 3; ++a)
      {
        // the triangle's box first (the order of a build that kept boxes:
        // min/max of +0 and -0 depend on it)
        node.lo[a] = std::min(node.lo[a], std::min(v[0][a], std::min(v[1][a], v[2][a])));
        node.hi[a] = std::max(node.hi[a], std::max(v[0][a], std::max(v[1][a], v[2][a])));
      }
    }
  }
  for (std::int64_t id = nodeCount - 1; id >= 0; --id)
  {
    Node& node = this->Nodes[id];
    if (node.left < 0) continue;
    const Node &l = this->Nodes[node.left], &r = this->Nodes[node.right];
    for (int a = 0; a < 3; ++a)
    {
      node.lo[a] = std::min(l.lo[a], r.lo[a]);
      node.hi[a] = std::max(l.hi[a], r.hi[a]);
    }
  }
}

void Bvh::build(BuildData& d, std::int32_t id, std::int32_t first, std::int32_t count, int depth)
{
  Node& node = this->Nodes[id];
  node.first = first;
  node.count = count;
  if (count > LeafSize && depth < 60)
  {
    double clo[3] = { 1e300, 1e300, 1e300 }, chi[3] = { -1e300, -1e300, -1e300 };
    for (std::int32_t i = first; i < first + count; ++i)
    {
      const double* c = d.ref[i].c;
      for (int a = 0; a < 3; ++a)
      {
        clo[a] = std::min(clo[a], c[a]);
        chi[a] = std::max(chi[a], c[a]);
      }
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
    }
    const std::int32_t half = count / 2;
    std::nth_element(d.ref.begin() + first, d.ref.begin() + first + half, d.ref.begin() + first + count,
      [axis](const BuildData::Ref& x, const BuildData::Ref& y) { return x.c[axis] < y.c[axis]; });
    node.left = id + 1;
    node.right = id + 1 + (*d.subtreeNodes)(half);
    if (count > 2048)
    {
      // shared(d): by default a task takes a firstprivate COPY of the object
      // a reference refers to (the centroids, per task)
#pragma omp task shared(d)
      this->build(d, node.left, first, half, depth + 1);
#pragma omp task shared(d)
      this->build(d, node.right, first + half, count - half, depth + 1);
#pragma omp taskwait
    }
    else
    {
      this->build(d, node.left, first, half, depth + 1);
      this->build(d, node.right, first + half, count - half, depth + 1);
    }
    return;
  }
  node.left = node.right = -1;
}

NearestResult Bvh::nearest(V3 p, std::int32_t hint, double maxDist2) const
{
  NearestResult best;
  best.dist2 = maxDist2;
  if (hint >= 0)
  {
    const Tri& t = this->Tris[hint];
    const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
    const V3 d = c.point - p;
    const double d2 = dot(d, d);
    if (d2 <= best.dist2)
    {
      best.dist2 = d2;
      best.tri = hint;
      best.closest = c;
    }
  }
  struct Item
  {
    std::int32_t node;
    double d2;
  };
  Item stack[128];
  int top = 0;
  stack[top++] = { 0, pointBoxDist2(p, this->Nodes[0].lo, this->Nodes[0].hi) };
  while (top > 0)
  {
    const Item it = stack[--top];
    if (it.d2 > best.dist2)
    {
      continue;
    }
    const Node& n = this->Nodes[it.node];
    if (n.left < 0)
    {
      for (std::int32_t i = n.first; i < n.first + n.count; ++i)
      {
        const std::int32_t ti = this->Order[i];
        if (ti == best.tri) continue;
        const Tri& t = this->Tris[ti];
        const Closest c = closestPointOnTriangle(p, t.v[0], t.v[1], t.v[2]);
        const V3 d = c.point - p;
        const double d2 = dot(d, d);
        // ties go to the lowest index, so every accelerator (and the GPU) picks
        // the same triangle, whose normal Normal mode uses
        if (d2 < best.dist2 || (d2 == best.dist2 && (best.tri < 0 || ti < best.tri)))
        {
          best.dist2 = d2;
          best.tri = ti;
          best.closest = c;
        }
      }
      continue;
    }
    const Node &l = this->Nodes[n.left], &r = this->Nodes[n.right];
    const double dl = pointBoxDist2(p, l.lo, l.hi), dr = pointBoxDist2(p, r.lo, r.hi);
    // push the farther child first so the nearer one is searched first
    if (dl <= dr)
    {
      if (dr <= best.dist2) stack[top++] = { n.right, dr };
      if (dl <= best.dist2) stack[top++] = { n.left, dl };
    }
    else
    {
      if (dl <= best.dist2) stack[top++] = { n.left, dl };
      if (dr <= best.dist2) stack[top++] = { n.right, dr };
    }
  }
  return best;
}

double Bvh::windingExact(V3 p) const
{
  double omega = 0;
  for (const Tri& t : this->Tris)
  {
    omega += solidAngle(p, t.v[0], t.v[1], t.v[2]);
  }
  return omega / FourPi;
}

bool Bvh::rayHits(V3 o, V3 dir, double tmin, std::vector<RayHit>& hits) const
{
  // slab test per node; Moeller-Trumbore per triangle, with a relative
  // tolerance that reports near-edge / near-vertex crossings as ambiguous
  constexpr double Eps = 1e-9;
  const double inv[3] = { 1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z };
  std::int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const Node& n = this->Nodes[stack[--top]];
    double t0 = tmin, t1 = 1e300;
    bool miss = false;
    for (int a = 0; a < 3 && !miss; ++a)
    {
      const double da = dir[a];
      if (da == 0)
      {
        miss = o[a] < n.lo[a] || o[a] > n.hi[a];
        continue;
      }
      double ta = (n.lo[a] - o[a]) * inv[a], tb = (n.hi[a] - o[a]) * inv[a];
      if (ta > tb) std::swap(ta, tb);
      const double pad = 1e-9 * (std::fabs(ta) + std::fabs(tb)) + 1e-300;
      t0 = std::max(t0, ta - pad);
      t1 = std::min(t1, tb + pad);
      miss = t0 > t1;
    }
    if (miss) continue;
    if (n.left >= 0)
    {
      stack[top++] = n.left;
      stack[top++] = n.right;
      continue;
    }
    for (std::int32_t i = n.first; i < n.first + n.count; ++i)
    {
      const std::int32_t ti = this->Order[i];
      const Tri& t = this->Tris[ti];
      const V3 e1 = t.v[1] - t.v[0], e2 = t.v[2] - t.v[0];
      const V3 pv = cross(dir, e2);
      const double det = dot(e1, pv);
      const double scale = norm(e1) * norm(e2) * norm(dir);
      const V3 tv = o - t.v[0];
      if (std::fabs(det) <= Eps * scale)
      {
        // parallel: ambiguous only if the ray lies in the triangle's plane
        if (std::fabs(dot(tv, t.n)) <= Eps * (norm(tv) + norm(e1))) return false;
        continue;
      }
      const double invDet = 1.0 / det;
      const double u = dot(tv, pv) * invDet;
      const V3 qv = cross(tv, e1);
      const double v = dot(dir, qv) * invDet;
      const double tt = dot(e2, qv) * invDet;
      const double w = 1 - u - v;
      if (u < -Eps || v < -Eps || w < -Eps) continue; // clear miss
      const double tScale = 1e-9 * (std::fabs(tt) + std::fabs(tmin) + norm(e1) / norm(dir));
      if (tt < tmin - tScale) continue;
      if (u <= Eps || v <= Eps || w <= Eps || std::fabs(tt - tmin) <= tScale) return false;
      hits.push_back({ tt, ti, static_cast<std::int8_t>(dot(dir, t.n) > 0 ? 1 : -1) });
    }
  }
  return true;
}

} // namespace detail::meshtosdf
} // namespace lvdif
