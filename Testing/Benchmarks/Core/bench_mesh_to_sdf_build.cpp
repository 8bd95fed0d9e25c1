// Host build phases of mesh to SDF, one by one: prepareMesh (weld, records,
// pseudo-normals, boundary), the binary Bvh (the GPU's mesh tree), the
// winding structures (WindingSigner: orientation pass, closure, its Bvh,
// dipole tree) and the CPU's NearestIndex; the median of REPEATS runs each,
// and a hash of what each phase built (equal hashes: the same structure, e.g.
// for two thread counts or two versions of the code run back to back).
// prepare also times prepareMesh without the pseudo-normals (what the
// WindingNumber and Unsigned signs build) and addPseudoNormals after it.
// usage: bench_mesh_to_sdf_build [DAMAGE:]MESH [REPEATS=3] [PHASES=prepare,bvh,winding,gpuhost,nearest,touch]
// (beside: prepareMesh without pseudo-normals with the mesh Bvh on its own thread beside the
// edge pass, as the one-call CUDA route builds them; serialhead: one median split on one
// thread over all triangles and over a subtree's 2^19 - 1; gpuhost: the three host builds of the one-call CUDA WindingNumber path in a row; touch:
// the first touch of 256 MB of fresh memory by 1 thread, by all, and by one
// with transparent huge pages asked for)
// (DAMAGE as in bench_mesh_to_sdf, e.g. sub2:armadillo.off for 832k triangles)
#include "BenchCommon.h"
#include "SignQualityMeshes.h"

#include "../../../Core/MeshToSdf/src/MeshToSdfInternal.h"
#include "../../../Core/MeshToSdf/src/MeshToSdfNearest.h"
#include "lvdif/MeshFile.h"

#include <omp.h>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <future>
#include <memory>
#include <string>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
/// FNV-1a over raw bytes, 8 at a time (structures of plain doubles and ints)
struct Hash
{
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* p, std::size_t n)
  {
    const auto* b = static_cast<const unsigned char*>(p);
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8)
    {
      std::uint64_t w;
      std::memcpy(&w, b + i, 8);
      h = (h ^ w) * 1099511628211ull;
    }
    for (; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  template <typename T, typename A>
  void addVector(const std::vector<T, A>& v)
  {
    if (!v.empty()) this->add(v.data(), v.size() * sizeof(T));
  }
  std::string hex() const
  {
    char s[17];
    std::snprintf(s, sizeof(s), "%016llx", static_cast<unsigned long long>(h));
    return s;
  }
};

/// Median ms of `repeats` calls of build(); drop() (not timed) frees the
/// previous result first, so that no call pays for freeing the last one.
template <typename D, typename B>
double medianBuildMs(int repeats, D&& drop, B&& build)
{
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i)
  {
    drop();
    bench::Stopwatch w;
    build();
    t.push_back(w.ms());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

std::string hashBvh(const Bvh& b)
{
  Hash h;
  for (const Bvh::Node& n : b.nodes())
  {
    h.add(n.lo, sizeof(n.lo));
    h.add(n.hi, sizeof(n.hi));
    h.add(&n.left, sizeof(n.left));
    h.add(&n.right, sizeof(n.right));
    h.add(&n.first, sizeof(n.first));
    h.add(&n.count, sizeof(n.count));
  }
  h.addVector(b.order());
  return h.hex();
}

std::string hashPrepared(const PreparedMesh& m)
{
  // per triangle in the order of the one 328-byte record they once were
  // (zeros for the normals not computed): the same hashes as before the split
  Hash h;
  const TriNormals none{};
  const CornerNormals noCorners{};
  for (std::size_t i = 0; i < m.tris.size(); ++i)
  {
    const Tri& t = m.tris[i];
    const TriNormals& pn = m.normals.empty() ? none : m.normals[i];
    const CornerNormals& nv = m.cornerNormals.empty() ? noCorners : m.cornerNormals[i];
    h.add(t.v, sizeof(t.v));
    h.add(&t.n, sizeof(t.n));
    h.add(pn.en, sizeof(pn.en));
    h.add(pn.vn, sizeof(pn.vn));
    h.add(nv.n, sizeof(nv.n));
    h.add(&t.area, sizeof(t.area));
    h.add(&t.source, sizeof(t.source));
  }
  h.addVector(m.welded);
  h.addVector(m.boundary);
  h.add(&m.boundaryLength, sizeof(m.boundaryLength));
  h.add(m.lo, sizeof(m.lo));
  h.add(m.hi, sizeof(m.hi));
  return h.hex();
}
} // namespace

static int benchMain(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: %s [DAMAGE:]MESH [REPEATS=3] [PHASES=prepare,bvh,winding,gpuhost,nearest,touch]\n", argv[0]);
    return 2;
  }
  const signquality::DamagedPath input = signquality::parseDamagedPath(argv[1]);
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const std::string phases = argc > 3 ? argv[3] : "prepare,bvh,winding,gpuhost,nearest,touch";
  auto wants = [&](const char* p) { return phases.find(p) != std::string::npos; };
  const TriangleMesh mesh = input.load([](const std::string& p) { return loadMesh(p); });
  std::printf("machine: %s\n", bench::machineDescription().c_str());
  std::printf("mesh: %s (%zu points, %zu triangles), median of %d\n", argv[1], mesh.points.size(),
    mesh.triangles.size(), repeats);

  std::vector<std::vector<std::string>> rows;
  const PhaseTraceScope tracing(std::getenv("LVDIF_BUILD_TRACE") != nullptr);
  PreparedMesh pm = prepareMesh(mesh); // kept for the later phases
  if (wants("prepare"))
  {
    PreparedMesh x;
    const double ms = medianBuildMs(repeats, [&] { x = PreparedMesh(); }, [&] { x = prepareMesh(mesh); });
    rows.push_back({ "prepareMesh", bench::fmt(ms, 1), hashPrepared(x) });
    // what the WindingNumber and Unsigned signs prepare (no pseudo-normals),
    // and the pseudo-normals added later (first Normal/PseudoNormal call):
    // the hash must then be prepareMesh's
    const double msLean = medianBuildMs(repeats, [&] { x = PreparedMesh(); }, [&] { x = prepareMesh(mesh, false); });
    rows.push_back({ "prepareMesh without pseudo-normals", bench::fmt(msLean, 1), hashPrepared(x) });
    std::vector<PreparedMesh> lean(static_cast<std::size_t>(repeats));
    for (PreparedMesh& l : lean) l = prepareMesh(mesh, false);
    std::size_t next = 0;
    const double msAdd = medianBuildMs(repeats, [] {}, [&] { addPseudoNormals(lean[next++]); });
    rows.push_back({ "  then addPseudoNormals", bench::fmt(msAdd, 1), hashPrepared(lean.back()) });
  }
  if (wants("bvh"))
  {
    std::unique_ptr<Bvh> b;
    const double ms = medianBuildMs(repeats, [&] { b.reset(); }, [&] { b = std::make_unique<Bvh>(pm.tris); });
    rows.push_back({ "mesh Bvh", bench::fmt(ms, 1), hashBvh(*b) });
  }
  if (wants("beside"))
  {
    // the one-call CUDA WindingNumber route's host build before the upload
    // (prepareInternal): prepareMesh without the pseudo-normals, the mesh
    // tree on its own thread from when the records are final, beside the
    // edge pass
    PreparedMesh x;
    std::unique_ptr<Bvh> b;
    const double ms = medianBuildMs(repeats, [&] { b.reset(), x = PreparedMesh(); }, [&] {
      std::future<std::unique_ptr<Bvh>> tree;
      const int threads = omp_get_max_threads();
      const bool tracing = tracePhasesActive();
      prepareMesh(mesh, x, false, [&] {
        tree = std::async(std::launch::async, [&x, threads, tracing] {
          omp_set_num_threads(threads);
          const PhaseTraceScope scope(tracing);
          const double tb = now();
          auto t = std::make_unique<Bvh>(x.tris);
          trace("mesh BVH (beside the edge pass)", now() - tb);
          return t;
        });
      });
      b = tree.get();
    });
    rows.push_back({ "prepareMesh, the tree beside the edge pass (one-call CUDA route)", bench::fmt(ms, 1),
      hashPrepared(x) + " " + hashBvh(*b) });
  }
  if (wants("serialhead"))
  {
    // the serial head of a median-split build: one split of m triangles on
    // one thread (centroid bounds, then std::nth_element by the coordinate),
    // as the tree's root split ran before the top splits went parallel (m =
    // all triangles) and as the largest split that still runs on one thread
    // does now (a subtree's root, m < 2^19 = Bvh::DefaultParallelSplitMin;
    // spelled out so that this file also builds against older code)
    struct Ref
    {
      double c[3];
      std::int32_t tri;
    };
    std::vector<Ref> all(pm.tris.size());
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      for (int a = 0; a < 3; ++a) all[i].c[a] = pm.tris[i].v[0][a] + pm.tris[i].v[1][a] + pm.tris[i].v[2][a];
      all[i].tri = static_cast<std::int32_t>(i);
    }
    for (const std::size_t m : { all.size(), std::min(all.size(), (std::size_t(1) << 19) - 1) })
    {
      std::vector<Ref> r;
      const double ms = medianBuildMs(repeats, [&] { r.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(m)); }, [&] {
        double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
        for (const Ref& x : r)
          for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], x.c[a]), hi[a] = std::max(hi[a], x.c[a]);
        int axis = 0;
        for (int a = 1; a < 3; ++a)
          if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
        std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(m / 2), r.end(),
          [axis](const Ref& x, const Ref& y) { return x.c[axis] < y.c[axis]; });
      });
      rows.push_back({ "one split on one thread, " + std::to_string(m) + " triangles", bench::fmt(ms, 1), "" });
    }
  }
  if (wants("winding"))
  {
    std::unique_ptr<WindingSigner> w;
    const double ms = medianBuildMs(repeats, [&] { w.reset(); }, [&] { w = std::make_unique<WindingSigner>(pm); });
    rows.push_back({ "WindingSigner", bench::fmt(ms, 1),
      hashBvh(*w->cpuClosure().bvh) + " (closure: " + std::to_string(w->cpuClosure().bvh->order().size()) +
        " triangles, correction " + std::to_string(w->cpuCorrection() ? w->cpuCorrection()->size() : 0) + ")" });
  }
  if (wants("gpuhost"))
  {
    // what the one-call CUDA path builds on the host before and beside the
    // upload: preparation, the mesh's tree, the winding structures (a
    // closed mesh's closure takes the mesh's tree)
    PreparedMesh x;
    std::shared_ptr<const Bvh> b;
    std::unique_ptr<WindingSigner> w;
    const double ms = medianBuildMs(repeats, [&] { w.reset(), b.reset(), x = PreparedMesh(); }, [&] {
      x = prepareMesh(mesh, false); // a WindingNumber call prepares no pseudo-normals
      b = std::make_shared<const Bvh>(x.tris);
      w = std::make_unique<WindingSigner>(x, b);
    });
    rows.push_back({ "GPU path host build (prepareMesh + Bvh + WindingSigner)", bench::fmt(ms, 1),
      hashBvh(*w->cpuClosure().bvh) });
    // the same with the pseudo-normals built too (as every call did before): the ratio in one run
    const double msFull = medianBuildMs(repeats, [&] { w.reset(), b.reset(), x = PreparedMesh(); }, [&] {
      x = prepareMesh(mesh, true);
      b = std::make_shared<const Bvh>(x.tris);
      w = std::make_unique<WindingSigner>(x, b);
    });
    rows.push_back({ "  the same with the pseudo-normals (before)", bench::fmt(msFull, 1), hashBvh(*w->cpuClosure().bvh) });
  }
  if (wants("nearest"))
  {
    std::unique_ptr<NearestIndex> n;
    const double ms = medianBuildMs(repeats, [&] { n.reset(); }, [&] { n = std::make_unique<NearestIndex>(pm.tris); });
    Hash x;
    x.addVector(n->nodes());
    rows.push_back({ "NearestIndex", bench::fmt(ms, 1), x.hex() });
  }
  if (wants("touch"))
  {
    // How the host's page faults scale: the first touch of fresh memory (as
    // the 273 MB of triangle records of 832k triangles get) by one thread
    // and by all; if all are much faster, a parallel first touch of the
    // large arrays would shorten the serial part of the build.
    constexpr std::size_t Bytes = std::size_t(256) << 20;
    for (int all = 0; all < 2; ++all)
    {
      const int threads = all ? omp_get_max_threads() : 1;
      const double ms = medianBuildMs(repeats, [] {}, [&] {
        std::unique_ptr<unsigned char[]> m(new unsigned char[Bytes]);
        const std::int64_t pages = static_cast<std::int64_t>(Bytes / 4096);
#pragma omp parallel for schedule(static) num_threads(threads)
        for (std::int64_t i = 0; i < pages; ++i) m[static_cast<std::size_t>(i) * 4096] = 1;
      });
      rows.push_back({ "first touch of 256 MB, " + std::to_string(threads) + " thread(s) (incl. free)", bench::fmt(ms, 1), "" });
    }
#ifdef __linux__
    // the same with transparent huge pages asked for (madvise): 512x fewer faults
    const double ms = medianBuildMs(repeats, [] {}, [&] {
      void* p = mmap(nullptr, Bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (p == MAP_FAILED) return;
      madvise(p, Bytes, MADV_HUGEPAGE);
      auto* m = static_cast<unsigned char*>(p);
      for (std::size_t i = 0; i < Bytes; i += 4096) m[i] = 1;
      munmap(p, Bytes);
    });
    rows.push_back({ "first touch of 256 MB, 1 thread, MADV_HUGEPAGE (incl. unmap)", bench::fmt(ms, 1), "" });
#endif
  }
  bench::printTable({ "phase", "ms", "hash of the result" }, rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
