// MeshToSdfPrepared: the prepared mesh's lazily built search structures
// (the CPU's NearestIndex, the winding-number closure, the GPU's tree and
// device copy), each built once under the prepared mesh's lock, and the host
// phase trace used by the benchmarks.
#include "MeshToSdfCuda.h"
#include "MeshToSdfFarBlocks.h"
#include "MeshToSdfInternal.h"
#include "MeshToSdfNearest.h"

#include <algorithm>
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

void trace(const char* what, double seconds)
{
  if (tracePhasesOn) std::fprintf(stderr, "[mesh to SDF] %s: %.2f ms\n", what, seconds * 1e3);
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

const std::vector<std::array<float, 6>>& MeshToSdfPrepared::Impl::partBounds()
{
  std::lock_guard<std::mutex> lock(this->Lock);
  if (this->Parts) return *this->Parts;
  const double t0 = now();
  const PreparedMesh& m = this->mesh;
  const std::size_t nv = m.vertices, nt = m.welded.size();
  auto parts = std::make_unique<std::vector<std::array<float, 6>>>();
  std::vector<std::array<float, 6>>& box = *parts;
  // union-find over the welded vertices (path halving, the smaller root kept)
  std::vector<std::uint32_t> root(nv);
  std::iota(root.begin(), root.end(), 0u);
  auto find = [&](std::uint32_t a) {
    while (root[a] != a) a = root[a] = root[root[a]];
    return a;
  };
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 1; k < 3; ++k)
    {
      const std::uint32_t a = find(m.welded[t][0]), b = find(m.welded[t][k]);
      if (a != b) root[std::max(a, b)] = std::min(a, b);
    }
  // each part's bounds, indexed by a compact part number
  constexpr std::uint32_t none = 0xffffffffu;
  std::vector<std::uint32_t> part(nv, none);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t v = m.welded[t][k], r = find(v);
      const Vec3f& p = m.points[v];
      if (part[r] == none)
      {
        part[r] = static_cast<std::uint32_t>(box.size());
        box.push_back({ p[0], p[1], p[2], p[0], p[1], p[2] });
      }
      std::array<float, 6>& b = box[part[r]];
      for (int a = 0; a < 3; ++a)
      {
        b[a] = std::min(b[a], p[a]);
        b[3 + a] = std::max(b[3 + a], p[a]);
      }
    }
  trace("the mesh's connected parts (first call with something inside)", now() - t0);
  this->Parts = std::move(parts);
  return *this->Parts;
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
