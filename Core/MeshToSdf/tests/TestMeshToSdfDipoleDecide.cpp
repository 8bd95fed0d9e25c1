// The GPU's winding-sign decision for damaged meshes (MeshToSdfDipoleDecide.h:
// the CPU's closure and dipole tree, traversed by a stack with a tolerance
// lowered pass by pass instead of the CPU's priority queue, blocks of 4^3
// voxels bounded first, the canonical sum where w is within rounding of
// +-1/2), run here on the CPU exactly as the CUDA kernel runs it per voxel,
// against meshToSdf on the CPU: the same sign on every voxel of the volume
// (the claim that lets Device::Auto keep every mesh on the GPU; the CUDA
// test compares the real kernel the same way). Also the brute-force solid
// angle oracle on far voxels, and portableAtan2 against long double atan2.
#include "../src/MeshToSdfDipoleDecide.h"
#include "../src/MeshToSdfDipoleLocal.h"
#include "../src/MeshToSdfInternal.h"
#include "MeshToSdfDamagedMeshes.h"
#include "MeshToSdfOracle.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace lvdif;
using namespace lvdif::detail::meshtosdf;

namespace
{
using oracle::damagedMeshes;

struct Emulated
{
  std::vector<char> inside;
  unsigned long long evaluated = 0, full = 0, blocksBounded = 0, fromCoarse = 0;
  // the local step (dipoleLocalKernel): 4^3 blocks expanded, failed (no
  // intervals), voxels their intervals decide in the sign kernel; the blocks
  // of the failed list left to the 2^3 balls (beyond the pool's capacity)
  unsigned long long localBlocks = 0, localFailed = 0, localDecided = 0, localOverflow = 0;
  DipoleWork local;           // passes (calls), nodes visited, triangle x voxel solid angles (tris)
  unsigned long long intervalsChecked = 0, intervalMisses = 0; // LocalStep::checkIntervals
  unsigned long long simtLocal = 0; // dipoleLocalKernel: the traversals' warp maxima (a lane per block) + the warps' sums
  unsigned long long simtLocalWalks = 0; // the first part alone
  DipoleWork blocks[DipoleLevels], voxels; // tree nodes and triangles visited by the two phases
  // SIMT cost: per warp of 32 threads, the most work of one lane, summed over
  // the warps; "raster": one thread per block of a level and per voxel of a
  // row (the kernels before the work lists), "listed": one per listed block
  // (children of the parents without a bound) and per listed voxel
  unsigned long long simtBlocks = 0, simtVoxels = 0, simtBlocksListed = 0, simtVoxelsListed = 0;
  // listed pass by pass (the items that need another pass listed again)
  unsigned long long simtBlocksPasses = 0, simtVoxelsPasses = 0;
  unsigned long long blockVisits() const
  {
    unsigned long long v = 0;
    for (const DipoleWork& w : blocks) v += w.nodes + w.tris + w.triBounds;
    return v;
  }
  unsigned long long voxelVisits() const { return voxels.nodes + voxels.tris + voxels.triBounds; }
};
unsigned long long workOf(const DipoleWork& w) { return w.nodes + w.tris + w.triBounds; }

/// Sum over consecutive groups of 32 of the largest entry.
unsigned long long simtOf(const std::vector<unsigned long long>& work, std::size_t from, std::size_t to)
{
  unsigned long long sum = 0;
  for (std::size_t a = from; a < to; a += 32)
    sum += *std::max_element(work.begin() + static_cast<std::ptrdiff_t>(a),
      work.begin() + static_cast<std::ptrdiff_t>(std::min(to, a + 32)));
  return sum;
}

/// The CUDA sign path, on the CPU over the whole grid, with its work lists
/// (the same helpers as the kernels): dipoleBlockKernel (the coarsest level
/// bounds every block, the others take their parent's bound, none or one),
/// dipoleListedBlockKernel (the blocks under a listed parent) and
/// dipoleBlockPassKernel (the blocks' further passes) level by level, then
/// signDipoleKernel (crossings; a voxel its block decides, else listed) and
/// dipoleRefineKernel (the listed voxels, pass by pass); with the local
/// step, dipoleLocalKernel on the 4^3 blocks left without a bound (up to the
/// pool's capacity; the 2^3 level then bounds only the children of the
/// others) and the sign kernel's look-up of their voxels' intervals. Every block and
/// voxel runs the passes the kernels run, in the order of their lists, and
/// the work of each pass is counted for the SIMT estimates.
/// The local step as the session sets it: on or off (LVDIF_CUDA_DIPOLE_LOCAL=0),
/// the pool's capacity in 4^3 blocks (the rest go to the 2^3 balls), and
/// errorScale (only the negative control sets it below 1).
struct LocalStep
{
  bool on = true;
  long long cap = 1ll << 40;
  double errorScale = 1;
  bool checkIntervals = false; // every voxel interval against DipoleTree::exact (Emulated::intervalMisses)
};

Emulated emulateGpu(const WindingSigner& w, const GridGeometry& g, bool blocksOnly = false, bool reoriented = false,
  const LocalStep& localStep = LocalStep{})
{
  const WindingSigner::Closure& c = w.cpuClosure(reoriented);
  const DipoleTree* s = w.cpuCorrection(reoriented);
  DipoleView D;
  if (s)
  {
    D.nodes = s->nodes().data();
    D.tris = s->tris().data();
    D.count = static_cast<int>(s->tris().size());
    D.rootMass = s->nodes()[0].mass;
  }
  Emulated e;
  const std::int64_t nx = g.dims[0], ny = g.dims[1], nz = g.dims[2];
  auto position = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return V3{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
  };
  e.inside.assign(static_cast<std::size_t>(g.count()), 0);
  std::vector<double> parent, bounds;
  std::vector<long long> parents, listed; // blocks without a bound of the level above / of this level
  std::vector<unsigned long long> work, listedWork;
  std::int64_t px = 0, py = 0, bx = 0, by = 0;
  // the local step's level (its failed blocks), slots and pool (MeshToSdfCuda.cu's LocalLevel, DipoleLocalLists)
  const int localLevel = 1;
  static_assert(DipoleEdges[1] == DipoleLocalEdge, "the local step's blocks");
  std::int64_t localTaken = 0, localBx = 0, localBy = 0;
  std::vector<int> localSlot;
  std::vector<double> localPool;
  for (int level = 0; level < DipoleLevels; ++level)
  {
    const std::int64_t edge = DipoleEdges[level], ratio = level ? DipoleEdges[level - 1] / edge : 1;
    bx = (nx + edge - 1) / edge;
    by = (ny + edge - 1) / edge;
    const std::int64_t bz = (nz + edge - 1) / edge;
    bounds.assign(static_cast<std::size_t>(2 * bx * by * bz), 0.0);
    work.assign(static_cast<std::size_t>(bx * by * bz), 0);
    listedWork.clear();
    D.work = &e.blocks[level];
    std::vector<unsigned long long> passWork[DipoleBlockPasses];
    auto bound = [&](std::int64_t b) {
      const std::int64_t ix = b % bx, iy = (b / bx) % by, iz = b / (bx * by);
      const std::int64_t x0 = edge * ix, y0 = edge * iy, z0 = edge * iz;
      double lo = 1, hi = 0;
      const unsigned long long before = workOf(e.blocks[level]);
      if (s)
      {
        // dipoleBlockBound pass by pass
        V3 centre;
        double rho = 0, margin = DipoleFirstMargin;
        dipoleBlockBall(position(x0, y0, z0),
          position(std::min(x0 + edge - 1, nx - 1), std::min(y0 + edge - 1, ny - 1), std::min(z0 + edge - 1, nz - 1)),
          centre, rho);
        for (int pass = 0; pass < DipoleBlockPasses; ++pass)
        {
          const unsigned long long w0 = workOf(e.blocks[level]);
          const int r = dipoleBlockPass(D, centre, rho, margin, lo, hi);
          passWork[pass].push_back(workOf(e.blocks[level]) - w0);
          if (r != 0) break;
        }
      }
      work[static_cast<std::size_t>(b)] = workOf(e.blocks[level]) - before;
      bounds[static_cast<std::size_t>(2 * b)] = lo;
      bounds[static_cast<std::size_t>(2 * b + 1)] = hi;
      if (!(lo <= hi) && level + 1 < DipoleLevels) listed.push_back(b);
    };
    for (std::int64_t b = 0; b < bx * by * bz; ++b)
    {
      if (!level)
      {
        bound(b);
        continue;
      }
      const std::size_t p = static_cast<std::size_t>((b % bx) / ratio + px * (((b / bx) % by) / ratio + py * ((b / (bx * by)) / ratio)));
      bounds[static_cast<std::size_t>(2 * b)] = parent[2 * p];
      bounds[static_cast<std::size_t>(2 * b + 1)] = parent[2 * p + 1];
      if (level == DipoleLevels - 1) e.fromCoarse += parent[2 * p] <= parent[2 * p + 1];
    }
    const std::int64_t r3 = ratio * ratio * ratio;
    // the parents the local step took have no children bounded here (dipoleListedBlockKernel's skipParents)
    const std::int64_t skip = level == localLevel + 1 ? localTaken : 0;
    for (std::int64_t t = 0; level && t < (static_cast<std::int64_t>(parents.size()) - skip) * r3; ++t)
    {
      const long long b = dipoleChildBlock(parents[static_cast<std::size_t>(skip + t / r3)], t % r3, ratio, px, py, bx, by, bz);
      if (b >= 0) bound(b);
      listedWork.push_back(b >= 0 ? work[static_cast<std::size_t>(b)] : 0);
    }
    e.simtBlocks += simtOf(work, 0, work.size());
    for (const auto& pw : passWork) e.simtBlocksPasses += simtOf(pw, 0, pw.size());
    e.simtBlocksListed += level ? simtOf(listedWork, 0, listedWork.size()) : simtOf(work, 0, work.size());
    if (level == DipoleLevels - 1)
      for (std::size_t b = 0; b < work.size(); ++b) e.blocksBounded += bounds[2 * b] <= bounds[2 * b + 1];
    if (level == localLevel && s && localStep.on)
    {
      // dipoleLocalKernel: the failed blocks of this level, in list order, up to the capacity
      localBx = bx;
      localBy = by;
      localSlot.assign(static_cast<std::size_t>(bx * by * bz), -1);
      localTaken = std::min<std::int64_t>(static_cast<std::int64_t>(listed.size()), localStep.cap);
      localPool.assign(static_cast<std::size_t>(2 * DipoleLocalVoxels * localTaken), 0.0);
      e.localOverflow = listed.size() - static_cast<std::size_t>(localTaken);
      D.work = &e.local;
      std::vector<unsigned long long> traversalWork;
      std::vector<int> nearList(DipoleLocalNearCap);
      unsigned long long sumWork = 0;
      for (std::int64_t t = 0; t < localTaken; ++t)
      {
        const long long b = listed[static_cast<std::size_t>(t)];
        const std::int64_t ix = b % bx, iy = (b / bx) % by, iz = b / (bx * by);
        DipoleLocalBlockVoxels X;
        X.h = g.spacing[0];
        X.x0 = DipoleLocalEdge * ix;
        X.n[0] = static_cast<int>(std::min<std::int64_t>(DipoleLocalEdge, nx - DipoleLocalEdge * ix));
        X.n[1] = static_cast<int>(std::min<std::int64_t>(DipoleLocalEdge, ny - DipoleLocalEdge * iy));
        X.n[2] = static_cast<int>(std::min<std::int64_t>(DipoleLocalEdge, nz - DipoleLocalEdge * iz));
        for (int c = 0; c < X.n[2]; ++c)
          for (int r = 0; r < X.n[1]; ++r)
            X.rowStart[r + DipoleLocalEdge * c] = position(0, DipoleLocalEdge * iy + r, DipoleLocalEdge * iz + c);
        V3 centre;
        double rho = 0;
        const std::int64_t x0 = edge * ix, y0 = edge * iy, z0 = edge * iz;
        dipoleBlockBall(position(x0, y0, z0),
          position(std::min(x0 + edge - 1, nx - 1), std::min(y0 + edge - 1, ny - 1), std::min(z0 + edge - 1, nz - 1)),
          centre, rho);
        // dipoleLocalKernel's passes over this block (the same functions in the same order)
        const DipoleWork w0 = e.local;
        double* out = localPool.data() + 2 * DipoleLocalVoxels * t;
        const int r = dipoleLocalBlock(D, X, centre, rho, out, out + DipoleLocalVoxels, nearList.data(), localStep.errorScale);
        // a lane walks the block's clusters (32 blocks per warp), the warp sums its near triangles
        traversalWork.push_back((e.local.nodes - w0.nodes) + (e.local.triBounds - w0.triBounds));
        sumWork += e.local.laneTris - w0.laneTris;
        for (int v = 0; localStep.checkIntervals && v < DipoleLocalVoxels; ++v)
        {
          if (!(out[v] <= out[DipoleLocalVoxels + v])) continue;
          const double exact = s->exact(X.at(v)); // the plain double sum: within 1e-12, far inside the slack
          ++e.intervalsChecked;
          e.intervalMisses += !(out[v] <= exact && exact <= out[DipoleLocalVoxels + v]);
        }
        if (r >= 0)
        {
          localSlot[static_cast<std::size_t>(b)] = static_cast<int>(t);
          ++e.localBlocks;
        }
        else
        {
          ++e.localFailed;
        }
      }
      e.simtLocalWalks = simtOf(traversalWork, 0, traversalWork.size());
      e.simtLocal = e.simtLocalWalks + sumWork;
      D.work = &e.blocks[level];
    }
    parents.swap(listed);
    listed.clear();
    parent.swap(bounds);
    px = bx;
    py = by;
  }
  bounds.swap(parent);
  D.work = &e.voxels;
  const V3 oblique = normalized(V3{ 0.5773502691896258, 0.5780, 0.5767 });
  std::vector<Bvh::RayHit> hits;
  std::vector<unsigned long long> queue;
  std::vector<unsigned long long> voxelWork(static_cast<std::size_t>(s ? g.count() : 0), 0);
  std::vector<std::vector<unsigned long long>> voxelPasses;
  auto refine = [&](std::int64_t v, int K, V3 p) {
    const unsigned long long before = workOf(e.voxels);
    // insideDipole pass by pass
    double margin = DipoleFirstMargin;
    bool inside = false;
    for (std::size_t pass = 0;; ++pass)
    {
      if (voxelPasses.size() <= pass) voxelPasses.emplace_back();
      const unsigned long long w0 = workOf(e.voxels);
      const int r = insideDipolePass(D, K, p, margin, inside);
      voxelPasses[pass].push_back(workOf(e.voxels) - w0);
      if (r > 0) break;
      if (r < 0)
      {
        ++e.full;
        inside = dipoleInsideOf(K - dipoleExactCanonical(D, p));
        break;
      }
    }
    e.inside[static_cast<std::size_t>(v)] = inside;
    voxelWork[static_cast<std::size_t>(v)] = workOf(e.voxels) - before;
  };
  const double h = g.spacing[0];
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
    {
      const V3 start = position(0, j, k);
      hits.clear(); // rayHits appends
      const bool ok = c.bvh->rayHits(start - V3{ 0.5 * h, 0, 0 }, V3{ 1, 0, 0 }, 0.0, hits);
      std::sort(hits.begin(), hits.end(), [](const Bvh::RayHit& a, const Bvh::RayHit& b) { return a.t < b.t; });
      int ahead = 0;
      for (const auto& x : hits) ahead += x.sign;
      std::size_t next = 0;
      const double* blockRow = bounds.data() + 2 * bx * (j / DipoleBlock + by * (k / DipoleBlock));
      for (std::int64_t i = 0; i < nx; ++i)
      {
        const V3 p = start + V3{ static_cast<double>(i) * h, 0, 0 };
        const std::int64_t v = g.index(i, j, k);
        char& out = e.inside[static_cast<std::size_t>(v)];
        int K = 0;
        double lo = 1, hi = 0;
        if (ok)
        {
          const double ti = 0.5 * h + static_cast<double>(i) * h;
          while (next < hits.size() && hits[next].t <= ti) ahead -= hits[next++].sign;
          K = ahead;
          lo = blockRow[2 * (i / DipoleBlock)];
          hi = blockRow[2 * (i / DipoleBlock) + 1];
        }
        else
        {
          std::vector<Bvh::RayHit> oh;
          if (!c.bvh->rayHits(p, oblique, 0.0, oh))
          {
            out = std::fabs(w.evaluate(p)) >= 0.5; // every solid angle of M (canonical)
            ++e.full;
            continue;
          }
          for (const auto& x : oh) K += x.sign;
        }
        if (!s)
        {
          out = std::abs(K) >= 1;
          continue;
        }
        bool inside = false;
        if (dipoleBlockDecides(K, lo, hi, inside))
        {
          out = inside;
          continue;
        }
        // signDipoleKernel: the voxel's interval from its 4^3 block's local expansion
        const int slot = ok && !localSlot.empty()
          ? localSlot[static_cast<std::size_t>(i / DipoleLocalEdge + localBx * (j / DipoleLocalEdge + localBy * (k / DipoleLocalEdge)))]
          : -1;
        if (slot >= 0)
        {
          const double* in = localPool.data() + 2 * DipoleLocalVoxels * static_cast<std::int64_t>(slot) +
            DipoleLocalEdge * (j % DipoleLocalEdge + DipoleLocalEdge * (k % DipoleLocalEdge)) + i % DipoleLocalEdge;
          if (dipoleBlockDecides(K, in[0], in[DipoleLocalVoxels], inside))
          {
            out = inside;
            ++e.localDecided;
            continue;
          }
        }
        ++e.evaluated;
        if (blocksOnly) continue;
        if (dipoleListable(K)) queue.push_back(dipoleListVoxel(v, K));
        else refine(v, K, p);
      }
    }
  // dipoleRefineKernel: the listed voxels, positions as the rows compute them
  std::vector<unsigned long long> listedVoxelWork;
  for (const unsigned long long q : queue)
  {
    long long v = 0;
    int K = 0;
    dipoleListedVoxel(q, v, K);
    const std::int64_t i = v % nx, row = v / nx;
    const V3 start = position(0, row % ny, row / ny);
    refine(v, K, start + V3{ static_cast<double>(i) * h, 0, 0 });
    listedVoxelWork.push_back(voxelWork[static_cast<std::size_t>(v)]);
  }
  for (std::size_t row = 0; s && row < voxelWork.size(); row += static_cast<std::size_t>(nx))
    e.simtVoxels += simtOf(voxelWork, row, row + static_cast<std::size_t>(nx));
  e.simtVoxelsListed = simtOf(listedVoxelWork, 0, listedVoxelWork.size());
  for (const auto& pw : voxelPasses) e.simtVoxelsPasses += simtOf(pw, 0, pw.size());
  return e;
}

/// Every voxel of the grid: the emulated GPU decision = meshToSdf's sign on
/// the CPU; the oracle on far voxels. Returns the emulation (its counts).
/// reorient: of the re-oriented mesh M+ (reorientFaces), with the structures
/// the GPU then takes; no oracle (it sums M as given). local: the local step's settings.
Emulated compareWithCpu(const std::string& name, const TriangleMesh& m, int res, int& reoriented, int& capsOverM,
  bool reorient = false, const LocalStep& local = LocalStep{})
{
  const GridGeometry g = fitGridToMesh(m, res, 2);
  VoxelBox all;
  all.hi = { g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1 };
  std::vector<float> cpu(static_cast<std::size_t>(g.count()));
  MeshToSdfOptions o;
  o.sign = SignMode::WindingNumber;
  o.device = Device::Cpu;
  o.bandWidth = std::numeric_limits<float>::infinity();
  o.reorientFaces = reorient;
  meshToSdf(m, g, all, cpu.data(), o);

  const PreparedMesh prepared = prepareMesh(m);
  const WindingSigner w(prepared);
  EXPECT_TRUE(w.gpuTakesCpuClosure(reorient)) << name;
  // (the intersecting pair is closed: no correction, K alone)
  if (!reorient) EXPECT_EQ(w.cpuCorrection() == nullptr, name == "pair") << name;
  reoriented += w.closesReorientedMesh();
  capsOverM += w.cpuCorrection() && !w.closesReorientedMesh();
  const Emulated e = emulateGpu(w, g, false, reorient, local);
  std::int64_t differ = 0, inside = 0, far = 0, wrong = 0;
  std::mt19937 rng(11);
  const std::uint32_t sample = static_cast<std::uint32_t>(std::max<std::int64_t>(16, g.count() / 1600));
  for (std::int64_t v = 0; v < g.count(); ++v)
  {
    const bool a = std::signbit(cpu[static_cast<std::size_t>(v)]), b = e.inside[static_cast<std::size_t>(v)] != 0;
    differ += a != b;
    inside += a;
    // brute-force oracle on a sample of the voxels farther than 1 voxel
    if (!reorient && std::fabs(cpu[static_cast<std::size_t>(v)]) > 1.0f && rng() % sample == 0)
    {
      const std::int64_t i = v % g.dims[0], j = (v / g.dims[0]) % g.dims[1], k = v / (g.dims[0] * g.dims[1]);
      const oracle::P p{ g.origin[0] + i * g.spacing[0], g.origin[1] + j * g.spacing[1], g.origin[2] + k * g.spacing[2] };
      ++far;
      wrong += (std::fabs(oracle::winding(m, p)) >= 0.5) != b;
    }
  }
  std::printf("[ gpu decision ] %-14s%s %lld voxels, %lld inside, %lld differ from the CPU; %llu blocks bounded (%llu by their coarse block), "
              "local step %s: %llu blocks of 4^3 (%llu failed, %llu left to the 2^3 balls), %llu voxels decided by them; "
              "%llu voxels refined, %llu canonical; oracle: %lld wrong of %lld far\n",
    name.c_str(), reorient ? " (re-oriented)" : "", static_cast<long long>(g.count()), static_cast<long long>(inside), static_cast<long long>(differ),
    e.blocksBounded, e.fromCoarse, local.on ? "on" : "off", e.localBlocks, e.localFailed, e.localOverflow, e.localDecided,
    e.evaluated, e.full, static_cast<long long>(wrong), static_cast<long long>(far));
  EXPECT_EQ(differ, 0) << name;
  EXPECT_EQ(wrong, 0) << name;
  EXPECT_GT(inside, g.count() / 50) << name; // the guard: the mesh encloses something
  if (!reorient) EXPECT_GT(far, 500) << name;
  return e;
}
} // namespace

TEST(MeshToSdfDipoleDecide, PortableAtan2IsWithinAFewUlps)
{
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int i = 0; i < 200000; ++i)
  {
    double y = u(rng) * std::pow(10.0, 4 * u(rng)), x = u(rng) * std::pow(10.0, 4 * u(rng));
    if (i % 13 == 0) x = 0;
    if (i % 17 == 0) y = 0;
    const long double ref = std::atan2(static_cast<long double>(y), static_cast<long double>(x));
    const double got = portableAtan2(y, x);
    const double ulp = std::fabs(std::nextafter(static_cast<double>(ref), 10.0) - static_cast<double>(ref));
    if (ref != 0) worst = std::max(worst, static_cast<double>(std::fabs(got - ref)) / ulp);
    else EXPECT_EQ(got, 0.0);
  }
  EXPECT_LT(worst, 8.0);
  EXPECT_EQ(portableAtan2(0.0, -1.0), 3.141592653589793);
  EXPECT_EQ(portableAtan2(-0.0, -1.0), -3.141592653589793);
  EXPECT_EQ(portableAtan2(2.0, 0.0), 1.5707963267948966);
  EXPECT_EQ(portableAtan2(-2.0, -0.0), -1.5707963267948966);
}

TEST(MeshToSdfDipoleDecide, GpuDecisionEqualsCpuOnEveryVoxelOfDamagedMeshes)
{
  int reoriented = 0, capsOverM = 0;
  for (const auto& [name, m] : damagedMeshes()) compareWithCpu(name, m, 32, reoriented, capsOverM);
  // both closures are exercised: M+ (scattered reversals, duplicates) and M closed by caps (patches, holes)
  EXPECT_GT(reoriented, 0);
  EXPECT_GT(capsOverM, 0);
}

// The re-oriented mesh M+ (reorientFaces), which CUDA now computes from the
// CPU's re-oriented closure and correction: the same decision on every voxel.
TEST(MeshToSdfDipoleDecide, GpuDecisionOfTheReorientedMeshEqualsCpu)
{
  int reoriented = 0, capsOverM = 0;
  for (const auto& [name, m] : damagedMeshes()) compareWithCpu(name, m, 32, reoriented, capsOverM, true);
}

// A finer grid, where the coarse blocks (16 voxels) bound s too
TEST(MeshToSdfDipoleDecide, GpuDecisionEqualsCpuOnAFinerGrid)
{
  int reoriented = 0, capsOverM = 0;
  const auto meshes = damagedMeshes();
  EXPECT_GT(compareWithCpu(meshes[0].first, meshes[0].second, 80, reoriented, capsOverM).fromCoarse, 0u);
}

// The local step (dipoleLocalKernel's decision, run here on the CPU): the
// damaged meshes decided with and without it, every voxel = the CPU (and
// the oracle on far voxels) both ways; with it the voxels refined one by one
// must fall and its intervals must decide voxels. With the pool cut to 5
// blocks, the blocks beyond it go to the 2^3 balls as before: still = the CPU.
TEST(MeshToSdfDipoleDecide, LocalStepDecidesWhatTheBallsLeave)
{
  int reoriented = 0, capsOverM = 0;
  unsigned long long refinedOff = 0, refinedOn = 0, decidedOn = 0, blocksOn = 0, overflowCut = 0, failedOn = 0;
  unsigned long long intervals = 0, passes = 0;
  int index = 0;
  for (const auto& [name, m] : damagedMeshes())
  {
    LocalStep off;
    off.on = false;
    const Emulated a = compareWithCpu(name, m, 36, reoriented, capsOverM, false, off);
    LocalStep checked;
    checked.checkIntervals = true;
    const Emulated b = compareWithCpu(name, m, 36, reoriented, capsOverM, false, checked);
    EXPECT_EQ(b.intervalMisses, 0u) << name; // every interval holds the exact s
    intervals += b.intervalsChecked;
    passes += b.local.calls;
    EXPECT_EQ(a.localBlocks + a.localDecided, 0u) << name;
    EXPECT_LE(b.evaluated, a.evaluated) << name;
    EXPECT_EQ(b.localFailed, 0u) << name; // only a stack overflow fails a block (the near lists are summed when full)
    failedOn += b.localFailed;
    refinedOff += a.evaluated;
    refinedOn += b.evaluated;
    decidedOn += b.localDecided;
    blocksOn += b.localBlocks;
    if (index++ >= 3) continue; // the cut pool on the first meshes only (the test's time)
    LocalStep cut;
    cut.cap = 5;
    const Emulated c = compareWithCpu(name, m, 36, reoriented, capsOverM, false, cut);
    overflowCut += c.localOverflow;
    EXPECT_LE(c.localBlocks, 5u) << name;
  }
  std::printf("[ local step ] voxels refined one by one: %llu without it, %llu with it; %llu blocks expanded (%llu failed), "
              "%llu voxels decided by their intervals; %llu passes; %llu intervals checked against the exact s; pool of 5: %llu "
              "blocks left to the 2^3 balls\n",
    refinedOff, refinedOn, blocksOn, failedOn, decidedOn, passes, intervals, overflowCut);
  EXPECT_GT(passes, blocksOn + blocksOn / 10); // later passes (their carried near sums) ran and were checked
  EXPECT_GT(decidedOn, 0u);
  EXPECT_LT(refinedOn * 2, refinedOff); // at least halved over the damaged meshes
  EXPECT_GT(overflowCut, 0u);           // the cut pool was exercised
}

// dipoleLocalBlock's intervals against the long-double sum of the solid
// angles (a soup of weight-2 triangles, blocks of 4^3 voxels near and inside
// it, some clipped): every interval holds, a voxel reported decided avoids
// the half-integers; with every cluster's error bound a hundredth of itself
// (the negative control) some interval misses.
TEST(MeshToSdfDipoleDecide, LocalStepIntervalsHoldAgainstLongDoubleSolidAngles)
{
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<float> uf(-1, 1), sf(-0.1f, 0.1f);
  std::vector<WeightedTri> tris(500);
  TriangleMesh ref; // each triangle twice (weight 2)
  for (auto& t : tris)
  {
    const float cx = uf(rng), cy = uf(rng), cz = 0.3f * uf(rng);
    for (auto& v : t.v) v = V3{ cx + sf(rng), cy + sf(rng), cz + sf(rng) };
    t.w = 2;
    for (int copy = 0; copy < 2; ++copy)
    {
      const std::uint32_t b = static_cast<std::uint32_t>(ref.points.size());
      for (const auto& v : t.v) ref.points.push_back({ static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z) });
      ref.triangles.push_back({ b, b + 1, b + 2 });
    }
  }
  const DipoleTree tree(tris);
  const DipoleView D{ tree.nodes().data(), tree.tris().data(), static_cast<int>(tree.size()), tree.nodes()[0].mass };
  long long checked = 0, misses = 0, decided = 0, reported = 0, missesScaled = 0;
  for (int n = 0; n < 90; ++n)
  {
    const double h = n % 3 == 0 ? 0.01 : (n % 3 == 1 ? 0.04 : 0.1);
    const V3 corner{ 1.4 * u(rng), 1.4 * u(rng), (n % 2 ? 0.3 : 1.2) * u(rng) };
    DipoleLocalBlockVoxels X;
    X.h = h;
    X.x0 = 3;
    for (int a = 0; a < 3; ++a) X.n[a] = n % 5 == 0 ? 1 + (n / 5 + a) % DipoleLocalEdge : DipoleLocalEdge;
    const V3 rowOrigin = corner - V3{ 3 * h, 0, 0 };
    for (int c = 0; c < X.n[2]; ++c)
      for (int r = 0; r < X.n[1]; ++r) X.rowStart[r + DipoleLocalEdge * c] = rowOrigin + V3{ 0, r * h, c * h };
    V3 centre;
    double rho = 0;
    dipoleBlockBall(corner, corner + V3{ (X.n[0] - 1) * h, (X.n[1] - 1) * h, (X.n[2] - 1) * h }, centre, rho);
    for (const double scale : { 1.0, 0.01 })
    {
      double lo[DipoleLocalVoxels], hi[DipoleLocalVoxels];
      std::vector<int> list(DipoleLocalNearCap);
      const int k = dipoleLocalBlock(D, X, centre, rho, lo, hi, list.data(), scale);
      ASSERT_GE(k, 0);
      int avoid = 0;
      for (int v = 0; v < DipoleLocalVoxels; ++v)
      {
        if (!X.has(v))
        {
          EXPECT_GT(lo[v], hi[v]); // no voxel there: no interval
          continue;
        }
        ASSERT_LE(lo[v], hi[v]);
        const V3 p = X.at(v);
        ASSERT_LE(norm(p - centre), rho);
        const double w = oracle::winding(ref, { p.x, p.y, p.z });
        const bool miss = !(lo[v] <= w && w <= hi[v]);
        if (scale == 1.0)
        {
          misses += miss;
          avoid += avoidsHalfIntegers(lo[v], hi[v]);
          ++checked;
        }
        else
        {
          missesScaled += miss;
        }
      }
      if (scale == 1.0)
      {
        EXPECT_EQ(k, avoid); // the decided count is the voxels whose interval avoids the half-integers
        decided += k;
        reported += X.n[0] * X.n[1] * X.n[2];
      }
    }
  }
  std::printf("[ local step ] %lld voxel intervals checked, %lld misses, %lld of %lld decided; with a hundredth of the error: "
              "%lld misses\n", checked, misses, decided, reported, missesScaled);
  EXPECT_EQ(misses, 0);
  EXPECT_GT(checked, 3000);
  EXPECT_GT(decided, reported / 2);
  EXPECT_GT(missesScaled, 0) << "the negative control: an error bound too small must miss somewhere";
}

// The work lists' index helpers: the blocks inside the parents of a level
// cover every block of the level below exactly once (partial parents at the
// grid's end), and a listed voxel keeps its index and crossing count.
TEST(MeshToSdfDipoleDecide, WorkListsCoverEveryBlockOnceAndKeepTheirVoxels)
{
  for (const std::int64_t n : { 1, 5, 16, 37, 64 })
    for (int l = 1; l < DipoleLevels; ++l)
    {
      const std::int64_t ratio = DipoleEdges[l - 1] / DipoleEdges[l];
      const std::int64_t dims[3] = { n, n + 3, 2 * n + 1 }; // voxels
      std::int64_t b[3], p[3];
      for (int a = 0; a < 3; ++a)
      {
        b[a] = (dims[a] + DipoleEdges[l] - 1) / DipoleEdges[l];
        p[a] = (dims[a] + DipoleEdges[l - 1] - 1) / DipoleEdges[l - 1];
      }
      std::vector<int> seen(static_cast<std::size_t>(b[0] * b[1] * b[2]), 0);
      for (std::int64_t parent = 0; parent < p[0] * p[1] * p[2]; ++parent)
        for (std::int64_t c = 0; c < ratio * ratio * ratio; ++c)
        {
          const long long child = dipoleChildBlock(parent, c, ratio, p[0], p[1], b[0], b[1], b[2]);
          if (child < 0) continue;
          ASSERT_LT(child, b[0] * b[1] * b[2]);
          ++seen[static_cast<std::size_t>(child)];
          // the child lies inside its parent
          const std::int64_t x = child % b[0], y = (child / b[0]) % b[1], z = child / (b[0] * b[1]);
          EXPECT_EQ(x / ratio + p[0] * (y / ratio + p[1] * (z / ratio)), parent);
        }
      for (const int k : seen) ASSERT_EQ(k, 1) << n << " level " << l;
    }
  for (const long long v : { 0LL, 1LL, 12345678901LL, (1LL << 43) - 1 })
    for (const int K : { 0, 1, -1, 96, -96, (1 << 19) - 1, -(1 << 19) + 1 })
    {
      ASSERT_TRUE(dipoleListable(K));
      long long v2 = -1;
      int K2 = 0;
      dipoleListedVoxel(dipoleListVoxel(v, K), v2, K2);
      EXPECT_EQ(v2, v);
      EXPECT_EQ(K2, K);
    }
  EXPECT_FALSE(dipoleListable(1 << 19));
  EXPECT_FALSE(dipoleListable(-(1 << 19)));
}

// Where w is within rounding of +-1/2 the canonical sum decides, on both
// sides: a point on a reversed face's plane, exactly inside the face.
TEST(MeshToSdfDipoleDecide, CanonicalSumDecidesTies)
{
  // one reversed face of weight 1 (a removed duplicate): at its centroid the
  // solid angle is +-2 pi, so s = +-1/2 exactly and no interval decides
  std::vector<WeightedTri> tris(1);
  tris[0].v[0] = { 0, 0, 0 };
  tris[0].v[1] = { 1, 0, 0 };
  tris[0].v[2] = { 0, 1, 0 };
  const DipoleTree tree(tris);
  DipoleView D{ tree.nodes().data(), tree.tris().data(), 1, tree.nodes()[0].mass };
  unsigned long long full = 0;
  const V3 p{ 1.0 / 3, 1.0 / 3, 0 };
  for (int K : { -1, 0, 1 })
  {
    const bool got = insideDipole(D, K, p, full);
    EXPECT_EQ(got, std::fabs(K - tree.exactCanonical(p)) >= 0.5) << K;
  }
  EXPECT_EQ(full, 2u); // K = 0 and the K that puts w on the other threshold
}

// The work of the GPU's decision, counted on the CPU (no comparison): the
// mesh in LVDIF_DIPOLE_WORK_MESH (e.g. the armadillo), damaged as the
// benchmarks damage it, at the resolutions in LVDIF_DIPOLE_WORK_RES
// (default "64 128"). Skipped when the variable is not set.
TEST(MeshToSdfDipoleDecide, WorkCounts)
{
  const char* path = std::getenv("LVDIF_DIPOLE_WORK_MESH");
  if (!path) GTEST_SKIP() << "set LVDIF_DIPOLE_WORK_MESH";
  const char* resText = std::getenv("LVDIF_DIPOLE_WORK_RES");
  const char* damages = std::getenv("LVDIF_DIPOLE_WORK_DAMAGES");
  std::vector<int> res;
  {
    std::string t = resText ? resText : "64 128";
    for (std::size_t a = 0; a < t.size();)
    {
      std::size_t b = t.find(' ', a);
      if (b == std::string::npos) b = t.size();
      if (b > a) res.push_back(std::stoi(t.substr(a, b - a)));
      a = b + 1;
    }
  }
  const TriangleMesh base = loadMesh(path);
  std::string ds = damages ? damages : "patch10 patch30 flip10 duprev20 holes40";
  for (std::size_t a = 0; a < ds.size();)
  {
    std::size_t b = ds.find(' ', a);
    if (b == std::string::npos) b = ds.size();
    const std::string d = ds.substr(a, b - a);
    a = b + 1;
    if (d.empty()) continue;
    const TriangleMesh m = signquality::damaged(base, d);
    const PreparedMesh prepared = prepareMesh(m);
    const WindingSigner w(prepared);
    for (int r : res)
    {
      const GridGeometry g = fitGridToMesh(m, r, 2);
      const auto t0 = std::chrono::steady_clock::now();
      LocalStep local; // LVDIF_CUDA_DIPOLE_LOCAL=0: without the local step, as the session
      const char* localEnv = std::getenv("LVDIF_CUDA_DIPOLE_LOCAL");
      local.on = !(localEnv && localEnv[0] == '0');
      const Emulated e = emulateGpu(w, g, std::getenv("LVDIF_DIPOLE_WORK_BLOCKS_ONLY") != nullptr, false, local);
      const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double n = static_cast<double>(g.count());
      std::printf("[ work ] %-9s %4d^3 %11lld voxels: %9llu blocks bounded (%9llu by coarse), %10llu voxels refined "
                  "(%.4f of all), %llu canonical; visits: blocks %.3g, voxels %.3g, per voxel %.2f; %.1f s\n",
        d.c_str(), r, static_cast<long long>(g.count()), e.blocksBounded, e.fromCoarse, e.evaluated,
        static_cast<double>(e.evaluated) / n, e.full, static_cast<double>(e.blockVisits()),
        static_cast<double>(e.voxelVisits()), static_cast<double>(e.blockVisits() + e.voxelVisits()) / n, sec);
      for (int l = 0; l < DipoleLevels; ++l)
        std::printf("[ work ]   blocks %2d^3: %.3g calls, %.3g nodes, %.3g triangles bounded, %.3g summed\n", DipoleEdges[l],
          static_cast<double>(e.blocks[l].calls), static_cast<double>(e.blocks[l].nodes),
          static_cast<double>(e.blocks[l].triBounds), static_cast<double>(e.blocks[l].tris));
      std::printf("[ work ]   local step %s: %llu blocks of 4^3 (%llu failed), %llu voxels decided by them; "
                  "%.3g nodes, %.3g triangle x voxel solid angles; SIMT (traversals a lane per block, sums a warp per block; per voxel) %.2f (walks %.2f)\n",
        local.on ? "on" : "off", e.localBlocks, e.localFailed, e.localDecided, static_cast<double>(e.local.nodes),
        static_cast<double>(e.local.tris), static_cast<double>(e.simtLocal) * 32 / n, static_cast<double>(e.simtLocalWalks) * 32 / n);
      std::printf("[ work ]   voxels: %.3g passes, %.3g nodes, %.3g triangles summed; SIMT (warp maxima, per voxel): "
                  "blocks %.2f, voxels %.2f; listed first: blocks %.2f, voxels %.2f; listed per pass: blocks %.2f, voxels %.2f\n",
        static_cast<double>(e.voxels.calls), static_cast<double>(e.voxels.nodes), static_cast<double>(e.voxels.tris),
        static_cast<double>(e.simtBlocks) * 32 / n, static_cast<double>(e.simtVoxels) * 32 / n,
        static_cast<double>(e.simtBlocksListed) * 32 / n, static_cast<double>(e.simtVoxelsListed) * 32 / n,
        static_cast<double>(e.simtBlocksPasses) * 32 / n, static_cast<double>(e.simtVoxelsPasses) * 32 / n);
      std::fflush(stdout);
    }
  }
}
