// MeshToSdfPrepared: the prepared mesh's lazily built search structures
// (the CPU's NearestIndex, the winding-number closure, the GPU's tree and
// device copy), each built once under the prepared mesh's lock, and the host
// phase trace used by the benchmarks.
#include "MeshToSdfCuda.h"
#include "MeshToSdfFarBlocks.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfNearest.h"
#include "MeshToSdfSharpFeatures.h"
#include "MeshToSdfSolid.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <numeric>

namespace lvdif
{
namespace detail::meshtosdf
{
double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace
{
// per thread, so that concurrent calls with and without tracePhases do not mix
thread_local bool tracePhasesOn = false;
} // namespace

PhaseTraceScope::PhaseTraceScope(bool on)
  : previous(tracePhasesOn)
{
  tracePhasesOn = previous || on;
}

PhaseTraceScope::~PhaseTraceScope() { tracePhasesOn = previous; }

bool tracePhasesActive() { return tracePhasesOn; }

namespace
{
thread_local Interrupter* buildInterrupter = nullptr;
} // namespace

BuildInterruptScope::BuildInterruptScope(Interrupter& interrupter)
  : previous(buildInterrupter)
{
  buildInterrupter = &interrupter;
}

BuildInterruptScope::~BuildInterruptScope() { buildInterrupter = previous; }

void checkBuildInterrupt()
{
  if (buildInterrupter) buildInterrupter->checkInterrupt();
}

void trace(const char* what, double seconds)
{
  if (!tracePhasesOn) return;
  // one clock for every thread's lines (the check, the regions, the pass run
  // side by side): when each phase ended, from the process's first line
  static const double epoch = now();
  std::fprintf(stderr, "[mesh to SDF] %s: %.2f ms (ends at %.1f ms)\n", what, seconds * 1e3, (now() - epoch) * 1e3);
}
} // namespace detail::meshtosdf

using namespace detail::meshtosdf;

std::size_t MeshToSdfPrepared::triangles() const { return this->Pimpl->mesh.tris.size(); }
std::size_t MeshToSdfPrepared::degenerateSkipped() const { return this->Pimpl->mesh.degenerate; }
std::size_t MeshToSdfPrepared::boundaryEdges() const { return this->Pimpl->mesh.boundaryEdges; }
double MeshToSdfPrepared::prepareSeconds() const { return this->Pimpl->prepareSeconds; }

const NearestIndex& MeshToSdfPrepared::Impl::nearestIndex(double& seconds)
{
  std::lock_guard<std::mutex> lock(this->Lock);
  if (!this->nearest)
  {
    const double t0 = now();
    this->nearest = std::make_unique<NearestIndex>(this->mesh.tris);
    seconds += now() - t0;
    trace("nearest index", now() - t0);
  }
  return *this->nearest;
}

const Bvh& MeshToSdfPrepared::Impl::farTree(const std::vector<FarCone>*& cones, double& seconds)
{
  std::lock_guard<std::mutex> lock(this->Lock);
  const double t0 = now();
  this->meshBvhLocked();
  if (!this->FarConesOfBvh) this->FarConesOfBvh = std::make_unique<std::vector<FarCone>>(farCones(*this->bvh, this->mesh));
  seconds += now() - t0;
  trace("far-block tree", now() - t0);
  cones = this->FarConesOfBvh.get();
  return *this->bvh;
}

const Bvh& MeshToSdfPrepared::Impl::meshBvhLocked()
{
  if (!this->bvh && this->Winding) this->bvh = this->Winding->meshBvh();
  if (!this->bvh)
  {
    const double tb = now();
    this->bvh = std::make_shared<const Bvh>(this->mesh.tris);
    trace("mesh BVH", now() - tb);
  }
  return *this->bvh;
}

std::shared_ptr<const Bvh> MeshToSdfPrepared::Impl::meshBvh()
{
  std::lock_guard<std::mutex> lock(this->Lock);
  this->meshBvhLocked();
  return this->bvh;
}

const WindingSigner& MeshToSdfPrepared::Impl::windingSigner(double& seconds)
{
  std::lock_guard<std::mutex> lock(this->Lock);
  if (!this->Winding)
  {
    const double t0 = now();
    this->Winding = std::make_unique<WindingSigner>(this->mesh, this->bvh);
    seconds += now() - t0;
  }
  return *this->Winding;
}

void MeshToSdfPrepared::Impl::pseudoNormals(double& seconds)
{
  std::lock_guard<std::mutex> lock(this->Lock);
  if (this->mesh.pseudoNormals) return;
  const double t0 = now();
  addPseudoNormals(this->mesh);
  seconds += now() - t0;
  trace("pseudo-normals (first Normal/PseudoNormal call)", now() - t0);
}

bool MeshToSdfPrepared::Impl::hasWindingSigner()
{
  std::lock_guard<std::mutex> lock(this->Lock);
  return this->Winding != nullptr;
}

namespace
{
/// Union-find over the vertices for all threads at once: a root is linked
/// only to a smaller index (so no cycle can form, whatever the order of the
/// links), by a compare-and-swap that fails when another thread linked it
/// first; paths are halved on the way up, which only ever moves a vertex's
/// parent to one of its ancestors. (The usual lock-free union-find, e.g.
/// Anderson and Woll, "Wait-free parallel algorithms for the union-find
/// problem", STOC 1991.)
class ConcurrentUnionFind
{
public:
  explicit ConcurrentUnionFind(std::size_t n)
    : parent(n)
  {
    const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
    for (std::int64_t v = 0; v < count; ++v)
      parent[static_cast<std::size_t>(v)].store(static_cast<std::uint32_t>(v), std::memory_order_relaxed);
  }

  std::uint32_t find(std::uint32_t a)
  {
    for (;;)
    {
      std::uint32_t p = parent[a].load(std::memory_order_relaxed);
      if (p == a) return a;
      const std::uint32_t g = parent[p].load(std::memory_order_relaxed);
      if (g != p) parent[a].compare_exchange_weak(p, g, std::memory_order_relaxed);
      a = g;
    }
  }

  void unite(std::uint32_t a, std::uint32_t b)
  {
    for (;;)
    {
      a = this->find(a);
      b = this->find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      std::uint32_t expected = a; // a is still a root: link it below b
      if (parent[a].compare_exchange_strong(expected, b, std::memory_order_relaxed)) return;
    }
  }

private:
  std::vector<std::atomic<std::uint32_t>> parent;
};

void atomicMin(std::atomic<float>& x, float v)
{
  float old = x.load(std::memory_order_relaxed);
  while (v < old && !x.compare_exchange_weak(old, v, std::memory_order_relaxed)) {}
}

void atomicMax(std::atomic<float>& x, float v)
{
  float old = x.load(std::memory_order_relaxed);
  while (v > old && !x.compare_exchange_weak(old, v, std::memory_order_relaxed)) {}
}
} // namespace

const MeshParts& MeshToSdfPrepared::Impl::partsLocked()
{
  if (this->PartsOfVertices) return *this->PartsOfVertices;
  const double t0 = now();
  const PreparedMesh& m = this->mesh;
  const std::size_t nv = m.vertices;
  const auto nt = static_cast<std::int64_t>(m.welded.size());
  // every step runs on all threads: a one-call run of a 10M-triangle mesh
  // pays for this once, before its first result
  ConcurrentUnionFind sets(nv);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nt; ++t)
  {
    const auto& f = m.welded[static_cast<std::size_t>(t)];
    sets.unite(f[0], f[1]);
    sets.unite(f[0], f[2]);
  }
  // each used vertex's root; the roots of used vertices numbered in index order
  constexpr std::uint8_t usedVertex = 1, usedRoot = 2;
  constexpr std::uint32_t unused = MeshParts::NoPart;
  std::vector<std::atomic<std::uint8_t>> flags(nv);
  const auto count = static_cast<std::int64_t>(nv);
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < count; ++v) flags[static_cast<std::size_t>(v)].store(0, std::memory_order_relaxed);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) flags[m.welded[static_cast<std::size_t>(t)][k]].fetch_or(usedVertex, std::memory_order_relaxed);
  auto parts = std::make_unique<MeshParts>();
  std::vector<std::uint32_t>& label = parts->partOfVertex;
  label.assign(nv, unused);
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < count; ++v)
  {
    const auto i = static_cast<std::size_t>(v);
    if (!(flags[i].load(std::memory_order_relaxed) & usedVertex)) continue;
    label[i] = sets.find(static_cast<std::uint32_t>(v));
    flags[label[i]].fetch_or(usedRoot, std::memory_order_relaxed);
  }
  std::vector<std::uint32_t> partOfRoot(nv, unused);
  for (std::size_t v = 0; v < nv; ++v)
    if (flags[v].load(std::memory_order_relaxed) & usedRoot) partOfRoot[v] = parts->count++;
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < count; ++v)
  {
    const auto i = static_cast<std::size_t>(v);
    if (label[i] != unused) label[i] = partOfRoot[label[i]];
  }
  trace("the mesh's connected parts (first use)", now() - t0);
  this->PartsOfVertices = std::move(parts);
  return *this->PartsOfVertices;
}

const MeshParts& MeshToSdfPrepared::Impl::parts()
{
  std::lock_guard<std::mutex> lock(this->PartsLock);
  return this->partsLocked();
}

const std::vector<std::array<float, 6>>& MeshToSdfPrepared::Impl::partBounds()
{
  std::lock_guard<std::mutex> lock(this->PartsLock);
  if (this->Parts) return *this->Parts;
  const MeshParts& labels = this->partsLocked();
  const double t0 = now();
  const PreparedMesh& m = this->mesh;
  const std::vector<std::uint32_t>& label = labels.partOfVertex;
  const std::uint32_t parts = labels.count;
  constexpr std::uint32_t unused = MeshParts::NoPart;
  const auto count = static_cast<std::int64_t>(m.vertices);
  // each part's bounds: a thread keeps a run of vertices of one part to itself
  // and merges it when the part changes (one merge per run, few for meshes of few parts)
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<std::atomic<float>> bound(6 * static_cast<std::size_t>(parts));
  for (std::size_t i = 0; i < bound.size(); ++i) bound[i].store(i % 6 < 3 ? inf : -inf, std::memory_order_relaxed);
#pragma omp parallel
  {
    std::uint32_t runPart = unused;
    std::array<float, 6> run{};
    auto flush = [&]() {
      if (runPart == unused) return;
      for (int a = 0; a < 3; ++a)
      {
        atomicMin(bound[6 * std::size_t{ runPart } + a], run[a]);
        atomicMax(bound[6 * std::size_t{ runPart } + 3 + a], run[3 + a]);
      }
    };
#pragma omp for schedule(static)
    for (std::int64_t v = 0; v < count; ++v)
    {
      const std::uint32_t part = label[static_cast<std::size_t>(v)];
      if (part == unused) continue;
      const Vec3f& p = m.points[static_cast<std::size_t>(v)];
      if (part != runPart)
      {
        flush();
        runPart = part;
        run = { p[0], p[1], p[2], p[0], p[1], p[2] };
      }
      for (int a = 0; a < 3; ++a)
      {
        run[a] = std::min(run[a], p[a]);
        run[3 + a] = std::max(run[3 + a], p[a]);
      }
    }
    flush();
  }
  auto box = std::make_unique<std::vector<std::array<float, 6>>>(parts);
  for (std::size_t i = 0; i < parts; ++i)
    for (int k = 0; k < 6; ++k) (*box)[i][k] = bound[6 * i + k].load(std::memory_order_relaxed);
  trace("the bounds of the mesh's connected parts (first call with something inside)", now() - t0);
  this->Parts = std::move(box);
  return *this->Parts;
}

const SolidBoundary& MeshToSdfPrepared::Impl::solidBoundary()
{
  std::call_once(this->SolidOnce, [this]() {
    const MeshParts& p = this->parts();
    const std::shared_ptr<const Bvh> tree = this->meshBvh();
    const double t0 = now();
    this->Solid = std::make_unique<SolidBoundary>(checkSolidBoundary(this->mesh, *tree, p));
    this->SolidKnown.store(true, std::memory_order_release);
    trace(this->Solid->solid ? "solid check: the mesh bounds a solid" : "solid check: not a solid's boundary", now() - t0);
  });
  return *this->Solid;
}

const SharpFeatures& MeshToSdfPrepared::Impl::sharpFeatures()
{
  std::call_once(this->SharpOnce, [this]() {
    const double t0 = now();
    this->Sharp = std::make_unique<SharpFeatures>(findSharpFeatures(this->mesh));
    trace(("sharp features: " + std::to_string(this->Sharp->sharpEdges) + " edges, " +
            std::to_string(this->Sharp->sharpVertices) + " vertices").c_str(),
      now() - t0);
  });
  return *this->Sharp;
}

const detail::meshtosdf_cuda::DeviceMesh& MeshToSdfPrepared::Impl::deviceMesh(
  bool winding, bool normals, double& seconds, bool windingLater, bool reoriented)
{
  const WindingSigner* w = winding ? &this->windingSigner(seconds) : nullptr;
  if (normals) this->pseudoNormals(seconds); // the device copy's normals are the host's
  // Sessions of other threads may use the copy: the winding parts are only
  // added (never replaced), and only sessions in WindingNumber mode read them.
  std::lock_guard<std::mutex> lock(this->Lock);
  const double t0 = now();
  // the GPU's tree: only the device path needs it (the CPU queries NearestIndex)
  this->meshBvhLocked();
  if (!this->Device)
  {
    this->Device =
      detail::meshtosdf_cuda::uploadMesh(this->mesh, *this->bvh, reoriented ? nullptr : w, normals, windingLater);
  }
  if (w && !this->Device->hasWinding(reoriented)) this->Device->addWinding(*w, reoriented);
  if (normals && !this->Device->hasNormals()) this->Device->addNormals();
  seconds += now() - t0;
  return *this->Device;
}

MeshToSdfPrepared::Impl::~Impl() = default;

} // namespace lvdif
