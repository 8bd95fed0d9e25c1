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
#include <cstdint>
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
/// a[i] = a[0] + ... + a[i] for i < n on the threads: each part's sum, the
/// parts' offsets, then each part again from its offset (integers: the same
/// as the serial loop).
void inclusiveSum(std::uint32_t* a, std::size_t n)
{
  const int parts = omp_get_max_threads();
  auto lo = [&](int p) { return n * static_cast<std::size_t>(p) / static_cast<std::size_t>(parts); };
  std::vector<std::uint32_t> offset(static_cast<std::size_t>(parts) + 1, 0);
#pragma omp parallel for schedule(static, 1)
  for (int p = 0; p < parts; ++p)
  {
    std::uint32_t sum = 0;
    for (std::size_t i = lo(p); i < lo(p + 1); ++i) sum += a[i];
    offset[static_cast<std::size_t>(p) + 1] = sum;
  }
  for (int p = 0; p < parts; ++p) offset[static_cast<std::size_t>(p) + 1] += offset[static_cast<std::size_t>(p)];
#pragma omp parallel for schedule(static, 1)
  for (int p = 0; p < parts; ++p)
  {
    std::uint32_t sum = offset[static_cast<std::size_t>(p)];
    for (std::size_t i = lo(p); i < lo(p + 1); ++i) a[i] = sum += a[i];
  }
}

/// Welds points of bitwise equal coordinates (as the hash map this replaced
/// did in effect: it hashed the bits; NaN is refused by validate()): ids in
/// order of first appearance. One flat open-addressing table filled by all
/// threads: a key's slot holds the smallest index seen with that key (CAS,
/// then atomic min), so when the fill ends every key holds its first
/// occurrence whatever the threads did; the ids follow by a prefix count.
std::uint32_t weldPoints(const std::vector<Vec3f>& points, LargeVector<std::uint32_t>& weld, LargeVector<std::uint32_t>& firstOf)
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
  LargeVector<std::size_t> slotOfPoint; // where point i's key lives
  resizeLargeForOverwrite(slotOfPoint, n);
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
  resizeLargeForOverwrite(weld, n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nI; ++i) weld[i] = table[slotOfPoint[static_cast<std::size_t>(i)]].load(std::memory_order_relaxed);
  table.reset();
  LargeVector<std::uint32_t> id; // id[i] = firsts before i
  resizeLargeForOverwrite(id, n + 1);
  id[0] = 0;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nI; ++i) id[i + 1] = weld[i] == static_cast<std::uint32_t>(i) ? 1 : 0;
  inclusiveSum(id.data() + 1, n);
  const std::uint32_t nv = id[n];
  resizeLargeForOverwrite(firstOf, nv);
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
/// weldPos is given), in vertex order, so nothing depends on the threads.
/// The grouping is a two-level counting sort (MSD radix by the smaller
/// vertex): the corners into about 4096 buckets of consecutive vertices, on
/// the threads by per-part counts (each part's corners in order: a stable
/// scatter); then each bucket on its own (a task of the loop) counted into
/// its vertices, whose groups are sorted and walked while they are in the
/// cache. The groups, their order and every sum are those of the one-level
/// counting sort this replaced (each thread scanned all 3n corners for its
/// own vertices: 16 threads read every corner 32 times).
/// `degenerate`: the welded ids of the skipped zero-area triangles, whose
/// edges count in the boundary (not in the normals): an ear of three collinear
/// polygon corners (a, b, c) closes a-b and b-c against the neighbouring faces
/// and a-c against the next ear; skipped from the edges, such ears left
/// boundary edges on a closed mesh (a polygon of float corners far from the
/// origin or on a fine circle). Its edges still cancel geometrically (a-b + b-c
/// = a-c on the line), so the chain and the winding numbers lose nothing.
void edgePass(PreparedMesh& out, std::size_t nv, const LargeVector<V3>* weldPos, bool normals,
  const std::function<void(const char*)>& lap, const std::vector<std::array<std::uint32_t, 3>>* degenerate = nullptr)
{
  const std::size_t n = out.tris.size();
  const auto& welded = out.welded;
  const std::size_t nk = 3 * n; // corners of kept triangles (normals)
  const std::size_t nc = nk + (degenerate ? 3 * degenerate->size() : 0);
  int shift = 0;
  while ((nv >> shift) > 4096) ++shift;
  const std::size_t nb = ((nv - 1) >> shift) + 1; // buckets of 2^shift vertices
  struct Entry
  {
    std::uint64_t key; // larger vertex << 32 | corner
    std::uint32_t lo;  // smaller vertex
    std::int32_t dir;  // +1: the corner's edge runs lo -> hi
  };
  auto edgeOf = [&](std::size_t c) {
    const auto& w = c < nk ? welded[c / 3] : (*degenerate)[(c - nk) / 3];
    const std::uint32_t a = w[c % 3], b = w[(c % 3 + 1) % 3];
    // a == b (two corners of a degenerate triangle at one point): no edge
    return Entry{ static_cast<std::uint64_t>(std::max(a, b)) << 32 | c, std::min(a, b), a < b ? 1 : (a > b ? -1 : 0) };
  };
  const int parts = omp_get_max_threads();
  auto partLo = [&](int p) { return nc * static_cast<std::size_t>(p) / static_cast<std::size_t>(parts); };
  std::vector<std::size_t> at(static_cast<std::size_t>(parts) * nb, 0); // per part and bucket: count, then place
#pragma omp parallel for schedule(static, 1)
  for (int p = 0; p < parts; ++p)
  {
    std::size_t* count = at.data() + static_cast<std::size_t>(p) * nb;
    for (std::size_t c = partLo(p); c < partLo(p + 1); ++c) ++count[edgeOf(c).lo >> shift];
  }
  std::vector<std::size_t> bucketStart(nb + 1);
  std::size_t o = 0;
  for (std::size_t b = 0; b < nb; ++b)
  {
    bucketStart[b] = o;
    for (int p = 0; p < parts; ++p)
    {
      const std::size_t k = at[static_cast<std::size_t>(p) * nb + b];
      at[static_cast<std::size_t>(p) * nb + b] = o;
      o += k;
    }
  }
  bucketStart[nb] = o;
  LargeVector<Entry> entries;
  resizeLargeForOverwrite(entries, nc); // every entry placed by the scatter below
#pragma omp parallel for schedule(static, 1)
  for (int p = 0; p < parts; ++p)
  {
    std::size_t* place = at.data() + static_cast<std::size_t>(p) * nb;
    for (std::size_t c = partLo(p); c < partLo(p + 1); ++c)
    {
      const Entry e = edgeOf(c);
      entries[place[e.lo >> shift]++] = e;
    }
  }
  lap("prepare: edge grouping");

  const bool boundary = weldPos != nullptr;
  struct BucketBoundary
  {
    std::vector<std::array<V3, 2>> segments; // in vertex order
    std::vector<double> lengthOf;            // per vertex with boundary edges, in vertex order
    std::size_t edges = 0;
    std::size_t seams = 0; // edges of two faces that run them the same way (one of the two is reversed)
    std::size_t crowded = 0; // edges of more than two (kept) faces
  };
  std::vector<BucketBoundary> bucketBoundary(boundary ? nb : 0);
  const std::int64_t nbI = static_cast<std::int64_t>(nb);
#pragma omp parallel
  {
    std::vector<std::uint32_t> end;
    std::vector<Entry> group;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t b = 0; b < nbI; ++b)
    {
      const std::size_t e0 = bucketStart[b], e1 = bucketStart[b + 1];
      const std::size_t v0 = static_cast<std::size_t>(b) << shift;
      const std::size_t vCount = std::min(nv - v0, std::size_t(1) << shift);
      // counting sort of the bucket by vertex (stable: corner order)
      end.assign(vCount + 1, 0);
      for (std::size_t e = e0; e < e1; ++e) ++end[entries[e].lo - v0 + 1];
      for (std::size_t i = 0; i < vCount; ++i) end[i + 1] += end[i];
      group.resize(e1 - e0);
      for (std::size_t e = e0; e < e1; ++e) group[end[entries[e].lo - v0]++] = entries[e];
      // now end[i] is the end of vertex v0 + i's group
      for (std::size_t i = 0, g0 = 0; i < vCount; g0 = end[i], ++i)
      {
        const std::size_t v = v0 + i, g1 = end[i];
        std::sort(group.begin() + static_cast<std::ptrdiff_t>(g0), group.begin() + static_cast<std::ptrdiff_t>(g1),
          [](const Entry& x, const Entry& y) { return x.key < y.key; });
        double length = 0;
        std::size_t edges = 0;
        for (std::size_t e = g0; e < g1;)
        {
          const std::uint32_t hiE = static_cast<std::uint32_t>(group[e].key >> 32);
          std::size_t e1g = e;
          V3 en;
          int mult = 0;
          std::size_t faces = 0; // uses by kept (non-degenerate) triangles
          for (; e1g < g1 && static_cast<std::uint32_t>(group[e1g].key >> 32) == hiE; ++e1g)
          {
            const std::uint32_t cf = static_cast<std::uint32_t>(group[e1g].key);
            if (normals && cf < nk) en = en + out.tris[cf / 3].n;
            faces += cf < nk;
            mult += group[e1g].dir; // a -> b with a < b counts +1
          }
          if (boundary) bucketBoundary[b].crowded += faces > 2;
          if (normals)
          {
            const V3 enu = normalized(en);
            for (std::size_t f = e; f < e1g; ++f)
            {
              const std::uint32_t cf = static_cast<std::uint32_t>(group[f].key);
              if (cf < nk) out.normals[cf / 3].en[cf % 3] = enu; // each corner is in exactly one group
            }
          }
          const std::size_t uses = e1g - e;
          e = e1g;
          if (boundary && mult != 0)
          {
            const V3 a = (*weldPos)[v], bv = (*weldPos)[hiE];
            length += std::abs(mult) * norm(bv - a);
            ++edges;
            bucketBoundary[b].seams += uses == 2 && std::abs(mult) == 2;
            for (int k = 0; k < std::abs(mult); ++k)
            {
              // key (lo, hi) with positive multiplicity means lo -> hi
              bucketBoundary[b].segments.push_back(mult > 0 ? std::array<V3, 2>{ a, bv } : std::array<V3, 2>{ bv, a });
            }
          }
        }
        if (edges > 0)
        {
          bucketBoundary[b].lengthOf.push_back(length);
          bucketBoundary[b].edges += edges;
        }
      }
    }
  }
  if (boundary)
  {
    // the vertices' lengths added in vertex order, as one loop over the
    // vertices did (those without boundary edges added +0)
    for (const BucketBoundary& bb : bucketBoundary)
    {
      for (const double l : bb.lengthOf) out.boundaryLength += l;
      out.boundaryEdges += bb.edges;
      out.orientationSeams += bb.seams;
      out.crowdedEdges += bb.crowded;
      out.boundary.insert(out.boundary.end(), bb.segments.begin(), bb.segments.end());
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
    const Tri& tri = out.tris[t];
    TriNormals& pn = out.normals[t];
    for (int k = 0; k < 3; ++k)
    {
      pn.vn[k] = normalized(vertexNormal[out.welded[t][k]]);
      if (dot(pn.vn[k], pn.vn[k]) == 0) pn.vn[k] = tri.n;
      if (dot(pn.en[k], pn.en[k]) == 0) pn.en[k] = tri.n;
    }
  }
  out.pseudoNormals = true;
}
/// TriangleMesh::validate()'s checks of every point and index on the
/// threads (a coordinate finite and within +-MaxWorldCoordinate:
/// isWorldCoordinate); where one fails (or the cheap checks do), validate()
/// itself runs and throws its message (the mesh's bounds, or the first bad
/// point or index).
void validateOnThreads(const TriangleMesh& mesh)
{
  const std::int64_t np = static_cast<std::int64_t>(mesh.points.size());
  const std::int64_t nt = static_cast<std::int64_t>(mesh.triangles.size());
  const std::size_t points = mesh.points.size();
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(| : bad)
  for (std::int64_t i = 0; i < np; ++i)
    for (float c : mesh.points[static_cast<std::size_t>(i)]) bad |= isWorldCoordinate(c) ? 0 : 1;
#pragma omp parallel for schedule(static) reduction(| : bad)
  for (std::int64_t t = 0; t < nt; ++t)
    for (std::uint32_t v : mesh.triangles[static_cast<std::size_t>(t)]) bad |= v < points ? 0 : 1;
  if (bad || nt == 0 || (!mesh.normals.empty() && mesh.normals.size() != points)) mesh.validate();
}
} // namespace

std::uint64_t preparedBytes(std::uint64_t triangles, bool pseudoNormals, bool winding, bool nearestIndex)
{
  const std::uint64_t perTriangle = PreparedBytesPerTriangle + (pseudoNormals ? PseudoNormalBytesPerTriangle : 0) +
    (winding ? WindingBytesPerTriangle : 0) + (nearestIndex ? NearestIndexBytesPerTriangle : 0);
  return checkedMultiply(triangles, perTriangle, "mesh to SDF: the prepared mesh");
}

void requirePreparedMemory(const TriangleMesh& mesh, bool pseudoNormals, bool winding, bool nearestIndex)
{
  const std::uint64_t n = mesh.triangles.size();
  std::string parts = "triangle records";
  if (pseudoNormals) parts += ", pseudo-normals";
  if (winding) parts += ", winding-number structures";
  if (nearestIndex) parts += ", nearest-triangle index";
  requireMemory(preparedBytes(n, pseudoNormals, winding, nearestIndex),
    "mesh to SDF: preparing " + std::to_string(n) + " triangles (" + parts + ")");
}

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
    checkBuildInterrupt();
  };
  validateOnThreads(mesh);
  out = PreparedMesh();
  const std::size_t nt = mesh.triangles.size();

  // Weld by exact position so pseudo-normals and the boundary chain see the
  // surface's topology even in a soup with duplicated points.
  LargeVector<std::uint32_t> weld, firstOf;
  const std::size_t nv = weldPoints(mesh.points, weld, firstOf);
  out.vertices = nv;
  auto toV3 = [](const Vec3f& p) { return V3{ p[0], p[1], p[2] }; };
  LargeVector<V3> weldPos;
  resizeLargeForOverwrite(weldPos, nv);
  resizeLargeForOverwrite(out.points, nv);
  const std::int64_t nvAll = static_cast<std::int64_t>(nv);
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < nvAll; ++v)
  {
    out.points[v] = mesh.points[firstOf[v]];
    weldPos[v] = toV3(out.points[v]);
  }
  lap("prepare: validate and weld");

  // triangle records and corner angles, in parallel, written straight to
  // their final (compacted) place: which triangles are kept is known first
  const std::int64_t ntI = static_cast<std::int64_t>(nt);
  auto crossOf = [&](std::int64_t t, V3* v) {
    const auto& ix = mesh.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) v[k] = toV3(mesh.points[ix[k]]);
    return faceCross(v);
  };
  LargeVector<std::uint32_t> slot; // slot[t] = kept triangles before t
  resizeLargeForOverwrite(slot, nt + 1);
  slot[0] = 0;
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < ntI; ++t)
  {
    V3 v[3];
    slot[t + 1] = norm(crossOf(t, v)) > 0 ? 1 : 0;
  }
  inclusiveSum(slot.data() + 1, nt);
  const std::size_t n = slot[nt];
  out.degenerate = nt - n;
  // one sentence, its count in the right number ("no triangle of non-zero area (1 degenerate triangles)")
  require(n > 0, (nt == 1 ? std::string("the mesh's only triangle has zero area (its corners coincide or lie on one line)")
                          : "all " + std::to_string(nt) + " triangles of the mesh have zero area (the corners of each "
                            "coincide or lie on one line)") +
      ", so there is no surface to convert: check the file's points and faces");
  // the records and welded ids are written whole below, on the threads,
  // which fault their pages in; the edge normals are sums (zero first)
  resizeLargeForOverwrite(out.tris, n);
  resizeLargeForOverwrite(out.welded, n);
  if (!mesh.normals.empty()) resizeLargeForOverwrite(out.cornerNormals, n);
  std::vector<std::array<double, 3>> keptAngles;
  if (pseudoNormals)
  {
    resizeLarge(keptAngles, n);
    resizeLarge(out.normals, n);
  }
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
    const V3 c = crossOf(t, tri.v);
    const double len = norm(c);
    tri.n = unitFaceNormal(c, len);
    tri.area = 0.5 * len;
    tri.source = static_cast<std::uint32_t>(t);
    if (!mesh.normals.empty())
    {
      for (int k = 0; k < 3; ++k)
      {
        out.cornerNormals[o].n[k] = normalized(toV3(mesh.normals[ix[k]]));
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
  // the skipped triangles' welded ids, for the boundary (while the corner
  // numbers fit the edge keys' 32 bits, as the kept ones must)
  std::vector<std::array<std::uint32_t, 3>> degenerate;
  if (out.degenerate > 0 && 3 * nt <= std::size_t(UINT32_MAX))
  {
    degenerate.reserve(out.degenerate);
    for (std::size_t t = 0; t < nt; ++t)
    {
      if (slot[t + 1] != slot[t]) continue;
      const auto& ix = mesh.triangles[t];
      degenerate.push_back({ weld[ix[0]], weld[ix[1]], weld[ix[2]] });
    }
  }
  edgePass(out, nv, &weldPos, pseudoNormals, lap, &degenerate);
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
  // no cancel here: this adds to a prepared mesh in place, which a stop half
  // way would leave half written
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
  resizeLarge(out.normals, out.tris.size());
  edgePass(out, out.vertices, nullptr, true, lap);
  finishPseudoNormals(out, vertexNormal);
  lap("prepare: pseudo-normals");
}

} // namespace detail::meshtosdf
} // namespace lvdif
