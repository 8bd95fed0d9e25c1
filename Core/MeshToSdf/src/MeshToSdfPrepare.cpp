// Mesh preparation for mesh to SDF: validation, degenerate triangles skipped
// and counted, face normals, angle-weighted pseudo-normals (Baerentzen &
// Aanaes, "Signed distance computation using the angle weighted
// pseudonormal", IEEE TVCG 2005) and the boundary chain used to bound the
// gradient of the winding number (MeshToSdf.cpp).
#include "MeshToSdfInternal.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>

#include <omp.h>

namespace lvdif
{
namespace detail::meshtosdf
{

namespace
{
/// Welds points of bitwise equal coordinates (as the hash map this replaced
/// did in effect: it hashed the bits; NaN is refused by validate()): ids in
/// order of first appearance. One flat open-addressing table filled by all
/// threads: a key's slot holds the smallest index seen with that key (CAS,
/// then atomic min), so when the fill ends every key holds its first
/// occurrence whatever the threads did; the ids follow by a prefix count.
std::uint32_t weldPoints(const std::vector<Vec3f>& points, std::vector<std::uint32_t>& weld, std::vector<std::uint32_t>& firstOf)
{
  constexpr std::uint32_t Empty = 0xffffffffu;
  const std::size_t n = points.size();
  std::size_t cap = 16;
  while (cap < 2 * n) cap *= 2;
  std::unique_ptr<std::atomic<std::uint32_t>[]> table(new std::atomic<std::uint32_t>[cap]);
  const std::int64_t capI = static_cast<std::int64_t>(cap), nI = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t s = 0; s < capI; ++s) table[s].store(Empty, std::memory_order_relaxed);
  auto slotOf = [&](const std::uint32_t* b) {
    std::uint64_t h = 1469598103934665603ull;
    for (int k = 0; k < 3; ++k) h = (h ^ b[k]) * 1099511628211ull;
    return static_cast<std::size_t>(h ^ (h >> 29)) & (cap - 1);
  };
  std::vector<std::size_t> slotOfPoint(n); // where point i's key lives
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nI; ++i)
  {
    const std::uint32_t me = static_cast<std::uint32_t>(i);
    std::uint32_t b[3];
    std::memcpy(b, points[static_cast<std::size_t>(i)].data(), sizeof(b));
    for (std::size_t slot = slotOf(b);; slot = (slot + 1) & (cap - 1))
    {
      std::uint32_t e = table[slot].load(std::memory_order_acquire);
      if (e == Empty)
      {
        if (table[slot].compare_exchange_strong(e, me, std::memory_order_acq_rel))
        {
          slotOfPoint[static_cast<std::size_t>(i)] = slot;
          break;
        }
        // another thread took the slot: e is its point, compare below
      }
      // a slot's key never changes (only its index, to a smaller one of the same key)
      if (std::memcmp(points[e].data(), b, sizeof(b)) != 0) continue;
      while (me < e && !table[slot].compare_exchange_weak(e, me, std::memory_order_acq_rel))
      {
      }
      slotOfPoint[static_cast<std::size_t>(i)] = slot;
      break;
    }
  }
  // rep = first occurrence of each point's key; ids = prefix count of firsts
  weld.resize(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nI; ++i) weld[i] = table[slotOfPoint[static_cast<std::size_t>(i)]].load(std::memory_order_relaxed);
  table.reset();
  std::vector<std::uint32_t> id(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) id[i + 1] = id[i] + (weld[i] == i ? 1 : 0);
  const std::uint32_t nv = id[n];
  firstOf.resize(nv);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nI; ++i)
  {
    if (weld[i] == static_cast<std::uint32_t>(i)) firstOf[id[i]] = static_cast<std::uint32_t>(i);
  }
  // weld[i] = id of its first occurrence (ids of firsts are set above: id[rep])
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nI; ++i) weld[i] = id[weld[i]];
  return nv;
}

/// Runs f(lo, hi) on every OpenMP thread with its own contiguous part
/// [lo, hi) of [0, n): each thread writes only the entries of its part, in
/// the order a serial loop would (no atomics, no per-thread copies).
template <typename F>
void ownerParts(std::size_t n, F&& f)
{
#pragma omp parallel
  {
    const std::size_t p = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t parts = static_cast<std::size_t>(omp_get_num_threads());
    f(n * p / parts, n * (p + 1) / parts);
  }
}

/// Counting sort of the 3n corners c = 3t + k into nb buckets by
/// bucketOf(c) (CSR: start gets nb + 1 offsets), each bucket in corner order
/// as a serial counting sort leaves it: every thread owns a range of buckets
/// and scans all corners for them (the scans are cheap, the scattered writes
/// are split). Returns valueOf(c) bucket by bucket.
template <typename Value, typename BucketOf, typename ValueOf>
std::vector<Value> bucketCorners(std::size_t n, std::size_t nb, std::vector<std::uint32_t>& start, BucketOf&& bucketOf,
  ValueOf&& valueOf)
{
  const std::uint32_t nc = static_cast<std::uint32_t>(3 * n);
  start.assign(nb + 1, 0);
  ownerParts(nb, [&](std::size_t lo, std::size_t hi) {
    for (std::uint32_t c = 0; c < nc; ++c)
    {
      const std::size_t b = bucketOf(c);
      if (b - lo < hi - lo) ++start[b + 1];
    }
  });
  for (std::size_t b = 0; b < nb; ++b) start[b + 1] += start[b];
  std::vector<Value> out;
  resizeLarge(out, nc);
  ownerParts(nb, [&](std::size_t lo, std::size_t hi) {
    std::vector<std::uint32_t> fill(start.begin() + static_cast<std::ptrdiff_t>(lo), start.begin() + static_cast<std::ptrdiff_t>(hi));
    for (std::uint32_t c = 0; c < nc; ++c)
    {
      const std::size_t b = bucketOf(c);
      if (b - lo < hi - lo) out[fill[b - lo]++] = valueOf(c);
    }
  });
  return out;
}

double angleAt(V3 p, V3 q, V3 r) // angle at p of triangle p q r
{
  const V3 u = normalized(q - p), v = normalized(r - p);
  double c = dot(u, v);
  c = c > 1 ? 1 : (c < -1 ? -1 : c);
  return std::acos(c);
}

/// Per welded vertex: the sum of its corners' angle-weighted face normals,
/// in triangle order (deterministic): each thread owns a range of vertices
/// and adds only to those.
std::vector<V3> vertexNormalSums(const PreparedMesh& out, std::size_t nv,
  const std::vector<std::array<double, 3>>& angles)
{
  std::vector<V3> vertexNormal;
  resizeLarge(vertexNormal, nv);
  const std::size_t n = out.tris.size();
  ownerParts(nv, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t t = 0; t < n; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const std::size_t v = out.welded[t][k];
        if (v - lo < hi - lo) vertexNormal[v] = vertexNormal[v] + angles[t][k] * out.tris[t].n;
      }
    }
  });
  return vertexNormal;
}

/// Edges grouped by their smaller welded vertex: entry = (larger vertex,
/// corner (t, k) whose edge goes w[k] -> w[k+1]), each group then sorted, so
/// that an edge's corners are consecutive, in triangle order. Then per
/// vertex: the distinct edges, their summed normals (triangle order, written
/// to en when `normals`) and oriented multiplicities (the boundary chain when
/// weldPos is given); boundary edges collected per vertex, then in vertex
/// order so the chain does not depend on the threads.
void edgePass(PreparedMesh& out, std::size_t nv, const std::vector<V3>* weldPos, bool normals,
  const std::function<void(const char*)>& lap)
{
  const std::size_t n = out.tris.size();
  const auto& welded = out.welded;
  std::vector<std::uint32_t> start;
  std::vector<std::uint64_t> corners = bucketCorners<std::uint64_t>(n, nv, start,
    [&](std::uint32_t c) {
      const auto& w = welded[c / 3];
      return std::min(w[c % 3], w[(c % 3 + 1) % 3]);
    },
    [&](std::uint32_t c) {
      const auto& w = welded[c / 3];
      return static_cast<std::uint64_t>(std::max(w[c % 3], w[(c % 3 + 1) % 3])) << 32 | c;
    });
  lap("prepare: edge grouping");

  const bool boundary = weldPos != nullptr;
  std::vector<std::vector<std::array<V3, 2>>> boundaryOf(boundary ? nv : 0);
  std::vector<double> lengthOf(boundary ? nv : 0, 0);
  std::vector<std::uint32_t> edgesOf(boundary ? nv : 0, 0);
  const std::int64_t nvI = static_cast<std::int64_t>(nv);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t v = 0; v < nvI; ++v)
  {
    const std::uint32_t b0 = start[v], b1 = start[v + 1];
    std::sort(corners.begin() + b0, corners.begin() + b1);
    for (std::uint32_t e = b0; e < b1;)
    {
      const std::uint32_t hiE = static_cast<std::uint32_t>(corners[e] >> 32);
      std::uint32_t e1 = e;
      V3 en;
      int mult = 0;
      for (; e1 < b1 && static_cast<std::uint32_t>(corners[e1] >> 32) == hiE; ++e1)
      {
        const std::uint32_t cf = static_cast<std::uint32_t>(corners[e1]);
        if (normals) en = en + out.tris[cf / 3].n;
        mult += welded[cf / 3][cf % 3] < hiE ? 1 : -1; // a -> b with a < b counts +1
      }
      if (normals)
      {
        const V3 enu = normalized(en);
        for (std::uint32_t f = e; f < e1; ++f)
        {
          const std::uint32_t cf = static_cast<std::uint32_t>(corners[f]);
          out.tris[cf / 3].en[cf % 3] = enu; // each corner is in exactly one list
        }
      }
      e = e1;
      if (boundary && mult != 0)
      {
        const V3 a = (*weldPos)[v], b = (*weldPos)[hiE];
        lengthOf[v] += std::abs(mult) * norm(b - a);
        ++edgesOf[v];
        for (int k = 0; k < std::abs(mult); ++k)
        {
          // key (lo, hi) with positive multiplicity means lo -> hi
          boundaryOf[v].push_back(mult > 0 ? std::array<V3, 2>{ a, b } : std::array<V3, 2>{ b, a });
        }
      }
    }
  }
  if (boundary)
  {
    for (std::size_t v = 0; v < nv; ++v)
    {
      out.boundaryLength += lengthOf[v];
      out.boundaryEdges += edgesOf[v];
      out.boundary.insert(out.boundary.end(), boundaryOf[v].begin(), boundaryOf[v].end());
    }
  }
  lap(boundary ? "prepare: edges and boundary" : "prepare: edge normals");
}

/// vn from the vertex sums; a pseudo-normal that cancels (e.g. a face and its
/// flipped duplicate) falls back to the face normal: the sign there is
/// ambiguous anyway.
void finishPseudoNormals(PreparedMesh& out, const std::vector<V3>& vertexNormal)
{
  const std::int64_t nI = static_cast<std::int64_t>(out.tris.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nI; ++t)
  {
    Tri& tri = out.tris[t];
    for (int k = 0; k < 3; ++k)
    {
      tri.vn[k] = normalized(vertexNormal[out.welded[t][k]]);
      if (dot(tri.vn[k], tri.vn[k]) == 0) tri.vn[k] = tri.n;
      if (dot(tri.en[k], tri.en[k]) == 0) tri.en[k] = tri.n;
    }
  }
  out.pseudoNormals = true;
}
} // namespace

PreparedMesh prepareMesh(const TriangleMesh& mesh, bool pseudoNormals)
{
  PreparedMesh out;
  prepareMesh(mesh, out, pseudoNormals, {});
  return out;
}

void prepareMesh(const TriangleMesh& mesh, PreparedMesh& out, bool pseudoNormals,
  const std::function<void()>& recordsReady)
{
  double tp = now(); // sub-phase times on the trace (tracePhases)
  const std::function<void(const char*)> lap = [&tp](const char* what) {
    const double t = now();
    trace(what, t - tp);
    tp = t;
  };
  mesh.validate();
  out = PreparedMesh();
  const std::size_t nt = mesh.triangles.size();

  // Weld by exact position so pseudo-normals and the boundary chain see the
  // surface's topology even in a soup with duplicated points.
  std::vector<std::uint32_t> weld, firstOf;
  const std::size_t nv = weldPoints(mesh.points, weld, firstOf);
  out.vertices = nv;
  auto toV3 = [](const Vec3f& p) { return V3{ p[0], p[1], p[2] }; };
  std::vector<V3> weldPos;
  resizeLarge(weldPos, nv);
  const std::int64_t nvAll = static_cast<std::int64_t>(nv);
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < nvAll; ++v) weldPos[v] = toV3(mesh.points[firstOf[v]]);
  lap("prepare: validate and weld");

  // triangle records and corner angles, in parallel, written straight to
  // their final (compacted) place: which triangles are kept is known first
  const std::int64_t ntI = static_cast<std::int64_t>(nt);
  auto faceCross = [&](std::int64_t t, V3* v) {
    const auto& ix = mesh.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) v[k] = toV3(mesh.points[ix[k]]);
    return cross(v[1] - v[0], v[2] - v[0]);
  };
  std::vector<std::uint32_t> slot(nt + 1, 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < ntI; ++t)
  {
    V3 v[3];
    slot[t + 1] = norm(faceCross(t, v)) > 0 ? 1 : 0;
  }
  for (std::size_t t = 0; t < nt; ++t) slot[t + 1] += slot[t];
  const std::size_t n = slot[nt];
  out.degenerate = nt - n;
  require(n > 0, "mesh has no triangle of non-zero area (" + std::to_string(out.degenerate) +
      " degenerate triangles)");
  // the records (328 bytes each: 273 MB for 832k triangles) are first
  // touched by resize(), serially: huge pages make that 512x fewer faults
  resizeLarge(out.tris, n);
  resizeLarge(out.welded, n);
  std::vector<std::array<double, 3>> keptAngles;
  if (pseudoNormals) resizeLarge(keptAngles, n);
  lap("prepare: records allocated");
  // bounds of the kept triangles on the way: min/max are exact, so the
  // parallel reduction gives the same values
  constexpr double Inf = std::numeric_limits<double>::infinity();
  double lx = Inf, ly = Inf, lz = Inf, hx = -Inf, hy = -Inf, hz = -Inf;
#pragma omp parallel for schedule(static) reduction(min : lx, ly, lz) reduction(max : hx, hy, hz)
  for (std::int64_t t = 0; t < ntI; ++t)
  {
    if (slot[t + 1] == slot[t]) continue; // degenerate
    const std::size_t o = slot[t];
    const auto& ix = mesh.triangles[static_cast<std::size_t>(t)];
    Tri& tri = out.tris[o];
    const V3 c = faceCross(t, tri.v);
    const double len = norm(c);
    tri.n = (1.0 / len) * c;
    tri.area = 0.5 * len;
    tri.source = static_cast<std::uint32_t>(t);
    if (!mesh.normals.empty())
    {
      for (int k = 0; k < 3; ++k)
      {
        tri.nv[k] = normalized(toV3(mesh.normals[ix[k]]));
      }
    }
    if (pseudoNormals)
    {
      for (int k = 0; k < 3; ++k)
      {
        keptAngles[o][k] = angleAt(tri.v[k], tri.v[(k + 1) % 3], tri.v[(k + 2) % 3]);
      }
    }
    out.welded[o] = { weld[ix[0]], weld[ix[1]], weld[ix[2]] };
    for (const V3& v : tri.v)
    {
      lx = std::min(lx, v.x), ly = std::min(ly, v.y), lz = std::min(lz, v.z);
      hx = std::max(hx, v.x), hy = std::max(hy, v.y), hz = std::max(hz, v.z);
    }
  }
  out.lo[0] = lx, out.lo[1] = ly, out.lo[2] = lz;
  out.hi[0] = hx, out.hi[1] = hy, out.hi[2] = hz;
  lap("prepare: triangle records");
  // the records, welded ids and bounds are final: work that reads only those
  // (the mesh BVH) may start beside the edge pass
  if (recordsReady) recordsReady();

  std::vector<V3> vertexNormal;
  if (pseudoNormals)
  {
    vertexNormal = vertexNormalSums(out, nv, keptAngles);
    lap("prepare: vertex normals");
  }
  edgePass(out, nv, &weldPos, pseudoNormals, lap);
  if (pseudoNormals)
  {
    finishPseudoNormals(out, vertexNormal);
    lap("prepare: pseudo-normals");
  }
}

void addPseudoNormals(PreparedMesh& out)
{
  if (out.pseudoNormals) return;
  double tp = now();
  const std::function<void(const char*)> lap = [&tp](const char* what) {
    const double t = now();
    trace(what, t - tp);
    tp = t;
  };
  // the corner angles as prepareMesh computes them (from the same vertices)
  std::vector<std::array<double, 3>> angles;
  resizeLarge(angles, out.tris.size());
  const std::int64_t nI = static_cast<std::int64_t>(out.tris.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nI; ++t)
  {
    const Tri& tri = out.tris[t];
    for (int k = 0; k < 3; ++k) angles[t][k] = angleAt(tri.v[k], tri.v[(k + 1) % 3], tri.v[(k + 2) % 3]);
  }
  const std::vector<V3> vertexNormal = vertexNormalSums(out, out.vertices, angles);
  lap("prepare: vertex normals");
  edgePass(out, out.vertices, nullptr, true, lap);
  finishPseudoNormals(out, vertexNormal);
  lap("prepare: pseudo-normals");
}

} // namespace detail::meshtosdf
} // namespace lvdif
