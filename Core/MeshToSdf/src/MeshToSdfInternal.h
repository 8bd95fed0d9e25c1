// Internal structures of mesh to SDF: the prepared triangle list, the BVH
// (nearest triangle and fast winding numbers) and the paper's uniform grid of
// overlapping boxes ("faithful" mode). See MeshToSdf.h for the algorithm.
#pragma once

#include "MeshToSdfDipoleTree.h"
#include "MeshToSdfGeometry.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/TriangleMesh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// Seconds of a steady clock; host phase times on stderr while a
/// PhaseTraceScope with MeshToSdfOptions::tracePhases is alive on this thread
/// (benchmarks). MeshToSdfPrepared.cpp.
double now();
void trace(const char* what, double seconds);
/// Whether this thread traces (a thread started by a call passes it on).
bool tracePhasesActive();
class PhaseTraceScope
{
public:
  explicit PhaseTraceScope(bool on);
  ~PhaseTraceScope();
  PhaseTraceScope(const PhaseTraceScope&) = delete;
  PhaseTraceScope& operator=(const PhaseTraceScope&) = delete;

private:
  bool previous;
};

/// The interrupter of the meshToSdf call running on this thread (one scope
/// per call): the structures a call builds on first use (the prepared mesh,
/// the trees, the nearest index, the winding structures, the solid check)
/// have no interrupter of their own and poll this one between their phases,
/// so a cancel during a large mesh's build takes effect at the next phase
/// (seconds on two cores for 832k triangles, not the whole build). A build
/// stopped so publishes nothing: the next call builds it again. Threads a
/// call starts poll nothing (their phases are short or joined by the caller).
class BuildInterruptScope
{
public:
  explicit BuildInterruptScope(Interrupter& interrupter);
  ~BuildInterruptScope();
  BuildInterruptScope(const BuildInterruptScope&) = delete;
  BuildInterruptScope& operator=(const BuildInterruptScope&) = delete;

private:
  Interrupter* previous;
};
/// Throws Error(Cancelled) when this thread's call was cancelled.
void checkBuildInterrupt();

/// Throws Error(OutOfMemory) when converting `mesh` into `volume` certainly
/// needs more than the volume's memory limit (meshToSdfLeastMemory, in
/// MeshToSdfMemory.cpp); checks nothing where even a dense volume fits.
void requireVolumeFits(const TriangleMesh& mesh, const DictionaryVolume& volume, const MeshToSdfOptions& options);

struct PreparedMesh
{
  TriList tris;          // non-degenerate triangles only
  std::size_t degenerate = 0;     // skipped zero-area triangles
  double boundaryLength = 0;      // total length of the boundary chain (0 when closed)
  std::size_t boundaryEdges = 0;  // edges of non-zero net multiplicity
  std::size_t orientationSeams = 0; // of those, edges of exactly two faces running them the same way
  /// Edges used by more than two faces (non-manifold). Every exact duplicate
  /// face (the same three welded corners) that is not alone with its copies
  /// has such edges, so a closed mesh (boundaryEdges 0) without them has no
  /// duplicates worth looking for: the duplicate searches (the reoriented
  /// winding sign's orientation pass, the warnings' count) run only then.
  std::size_t crowdedEdges = 0;
  /// The boundary chain as directed segments (a -> b, repeated per unit of
  /// multiplicity): the oriented edges of the triangles that do not cancel.
  std::vector<std::array<V3, 2>> boundary;
  /// Per triangle of tris: its corners' vertex ids, welded by exact position.
  LargeVector<std::array<std::uint32_t, 3>> welded;
  std::size_t vertices = 0; // welded vertices (ids in [0, vertices))
  /// The welded vertices' positions (the input's float bits: tris[t].v[k] is
  /// points[welded[t][k]] exactly): with welded, the compact form of the
  /// records' vertices that the device copy is built from.
  LargeVector<Vec3f> points;
  double lo[3] = { 0, 0, 0 }, hi[3] = { 0, 0, 0 }; // bounds of the kept triangles
  /// Per triangle of tris: its pseudo-normals, once computed (pseudoNormals;
  /// empty before): only the Normal/PseudoNormal signs read them
  /// (featureNormal, far blocks).
  LargeVector<TriNormals> normals;
  bool pseudoNormals = false;
  /// Per triangle of tris: the input mesh's vertex normals at its corners;
  /// empty when the mesh has none (the Normal sign with useVertexNormals).
  LargeVector<CornerNormals> cornerNormals;
  /// Triangle t's corner normals, or null when the mesh has none.
  const CornerNormals* cornersOf(std::size_t t) const { return this->cornerNormals.empty() ? nullptr : &this->cornerNormals[t]; }
};

/// Validates the mesh and builds the triangle records (vertices welded by
/// exact position), the boundary chain and, when `pseudoNormals`, the
/// pseudo-normals (else none, for addPseudoNormals).
PreparedMesh prepareMesh(const TriangleMesh& mesh, bool pseudoNormals = true);
/// The same, into `out` (which must stay where it is: a reader started by
/// recordsReady holds references into it). recordsReady (optional) is called
/// once tris, welded, vertices and the bounds are final, before the edge
/// pass (boundary, edge pseudo-normals): it may start a reader of those
/// fields alone (the mesh BVH reads Tri::v and Tri::n) on another thread; the
/// rest of prepareMesh writes no field such a reader reads.
void prepareMesh(const TriangleMesh& mesh, PreparedMesh& out, bool pseudoNormals,
  const std::function<void()>& recordsReady);
/// What a preparation may hold, in bytes per triangle, each part at its own
/// peak (one rule: requirePreparedMemory adds up the parts a call will build
/// before any is allocated, and the index and the orientation check their
/// own share when they are built). Peaks measured on the 832k-triangle
/// armadillo (sub2, and damaged for the winding part), rounded up; their sum
/// bounds the call's peak from above (docs/MESH_TO_SDF.md, "Memory").
constexpr std::uint64_t PreparedBytesPerTriangle = 200;      // records, welding, edge grouping, boundary (188)
constexpr std::uint64_t PseudoNormalBytesPerTriangle = 300;  // Normal/PseudoNormal: pseudo-normals (180), far-block tree (72)
constexpr std::uint64_t WindingBytesPerTriangle = 200;       // winding: orientation (checked alone too), closure, BVH, dipole tree (72-187)
constexpr std::uint64_t NearestIndexBytesPerTriangle = 800;  // the CPU's NearestIndex while it is built (648)
/// The sum of those parts for `triangles` triangles.
std::uint64_t preparedBytes(std::uint64_t triangles, bool pseudoNormals, bool winding, bool nearestIndex);
/// requireMemory(preparedBytes(...)) for the mesh: called before prepareMesh
/// allocates anything, so a mesh too large for LVDIF_MEMORY_LIMIT is refused
/// at once with what it would need.
void requirePreparedMemory(const TriangleMesh& mesh, bool pseudoNormals, bool winding, bool nearestIndex);
/// Fills the pseudo-normals of a mesh prepared without them, bit for bit as
/// prepareMesh(mesh, true) does; nothing if they are there. Writes only
/// `normals` and `pseudoNormals` (readers of other fields may run meanwhile).
void addPseudoNormals(PreparedMesh& mesh);

struct NearestResult
{
  double dist2 = 0;
  std::int32_t tri = -1;
  Closest closest;
};

/// A voxel's value from its nearest triangle: the sign s times the distance in
/// output units (toOut per world unit), saturated at the band. One expression
/// for the CPU's distance rows and the sharp features' voxels
/// (MeshToSdfSharpFeatures.h), which must store the same floats.
LVDIF_HD float storedValue(float s, double dist2, double toOut, double band)
{
  return s * static_cast<float>(std::min(std::sqrt(dist2) * toOut, band));
}

class BvhSubtreeNodes; // MeshToSdfBvh.cpp
struct LocalBoundsCounts; // MeshToSdfDipoleLocal.h

/// Binary BVH over the triangles (median split on the longest axis of the
/// centroid bounds, leaves of at most 4), built in parallel: a function of
/// the triangles alone (the median by the total order (centroid coordinate,
/// triangle index), a leaf's triangles by index), the same on any thread count.
class Bvh
{
public:
  struct Node
  {
    double lo[3], hi[3];
    std::int32_t left = -1, right = -1; // children, or -1 for a leaf
    std::int32_t first = 0, count = 0;  // leaf range in Order
  };

  /// Nodes of at least this many triangles split with all threads together
  /// (a parallel bucket partition at the median); below, whole subtrees are tasks.
  /// The tree does not depend on it (tests build with a small one).
  static constexpr std::int32_t DefaultParallelSplitMin = std::int32_t(1) << 19;
  explicit Bvh(const TriList& tris, std::int32_t parallelSplitMin = DefaultParallelSplitMin);

  /// Nearest triangle to p among those closer than sqrt(bestDist2): starts
  /// from the given hint (tri index, -1 for none), exact. Ties go to the
  /// lowest index. skip (skipCount entries): triangles left out.
  NearestResult nearest(V3 p, std::int32_t hint, double maxDist2, const std::int32_t* skip = nullptr,
    int skipCount = 0) const;

  /// Whether every triangle vertex x has (x - o) . dir <= `limit`: the
  /// largest value found above it, or `limit` when there is none (nodes
  /// whose box cannot exceed it are skipped; the box bound is summed in the
  /// vertices' order, so it is never below a vertex's computed value).
  double maxAlongAbove(V3 o, V3 dir, double limit) const;

  /// Exact winding number: the sum of all solid angles / 4 pi.
  double windingExact(V3 p) const;

  struct RayHit
  {
    double t;
    std::int32_t tri;
    std::int8_t sign; // +1 when the ray leaves through the front face
  };
  /// Every crossing of the ray o + t dir, t > tmin, with a triangle. Returns
  /// false when a crossing is too close to an edge, a vertex, the ray origin,
  /// or the ray lies in a triangle's plane (the count would be ambiguous).
  bool rayHits(V3 o, V3 dir, double tmin, std::vector<RayHit>& hits) const;

  const LargeVector<Node>& nodes() const { return this->Nodes; }
  const LargeVector<std::int32_t>& order() const { return this->Order; }
  const TriList& tris() const { return this->Tris; }

private:
  struct BuildData
  {
    /// 16 bytes (the splits move these: half the traffic of double keys).
    struct Ref
    {
      float c[3];       // 3x the centroid minus 3x the origin, rounded: only compared
      std::int32_t tri; // triangle index
    };
    LargeVector<Ref> ref;   // permuted by the build; becomes Order
    LargeVector<Ref> spare; // the top splits partition ref into spare and back (large meshes only)
    const BvhSubtreeNodes* subtreeNodes = nullptr; // nodes of a subtree by its triangle count
    struct Subtree
    {
      std::int32_t id, first, count, depth;
      bool inSpare; // its triangles lie in spare
    };
    std::vector<Subtree> subtrees; // below the top splits: built as tasks
    std::vector<std::int32_t> topNodes; // the top splits' nodes, in preorder
    std::int32_t parallelSplitMin = DefaultParallelSplitMin;
  };
  /// The top splits, each with all threads (a bucket partition at the median, the children's bounds on the way);
  /// lists the subtrees below them in d.subtrees.
  void splitTop(BuildData& d, std::int32_t id, std::int32_t first, std::int32_t count, int depth, bool inSpare,
    const double clo[3], const double chi[3]);
  /// A subtree: its nodes, then (a leaf) its entries of Order and its box, (an inner node) its box from its children's.
  void build(BuildData& d, std::int32_t id, std::int32_t first, std::int32_t count, int depth);
  void innerBox(std::int32_t id); // the union of the children's boxes
  const TriList& Tris;
  LargeVector<Node> Nodes;
  LargeVector<std::int32_t> Order;
};

/// The tree's triangles in leaf order as the GPU's kernels read them:
/// leafCopies(b)[i] = the vertices and normal of triangle b.order()[i]
/// (96 bytes each, on the OpenMP threads). The host tree keeps no such
/// copy: the mesh's own tree gets them on the device, gathered from the
/// welded mesh (MeshToSdfCuda.cu, 1.2 GB fewer bytes to upload for 13.3M
/// triangles); a closure's tree and the tests take them from here.
LargeVector<LeafTri> leafCopies(const Bvh& b);

/// The paper's "octree of overlapping chunks" (Sect. 3.1, spec 1.7): a uniform
/// grid of M^3 cells over the triangle bounds; each cell lists the triangles
/// overlapping the cell scaled by `scale` about its centre (Akenine-Moeller
/// separating-axis test). Every cell is processed (the original skipped the
/// last one). The query is exact: see nearest().
class FaithfulGrid
{
public:
  FaithfulGrid(const TriList& tris, const double lo[3], const double hi[3], int m, double scale);
  /// Paper's step: brute force over the list of the cell nearest to p that
  /// has triangles; then, to be exact, every other cell whose own (unscaled)
  /// region is within the current best distance is searched too (the true
  /// closest point lies in some cell, and its triangle overlaps that cell).
  NearestResult nearest(V3 p) const;
  std::size_t listEntries() const { return this->Entries.size(); }

private:
  std::int64_t cellIndex(int i, int j, int k) const { return i + this->M * (j + static_cast<std::int64_t>(this->M) * k); }
  void scanCell(std::int64_t cell, V3 p, NearestResult& best) const;
  const TriList& Tris;
  int M;
  double Lo[3], Step[3];
  std::vector<std::int64_t> Start; // M^3 + 1 offsets into Entries
  std::vector<std::int32_t> Entries;
  std::vector<std::int32_t> NearestFull; // for each cell, a cell with triangles near it (BFS)
};

/// Exact generalized winding number of the mesh by crossings (MeshToSdfWinding.cpp).
class WindingSigner
{
public:
  /// meshBvh (optional): a Bvh over mesh.tris already built (the GPU's mesh
  /// tree); a closed mesh's closure is the mesh itself and takes that tree
  /// instead of building a second, identical one.
  explicit WindingSigner(const PreparedMesh& mesh, std::shared_ptr<const Bvh> meshBvh = nullptr);
  ~WindingSigner();
  /// False when the boundary is empty or a few edges of multiplicity 1 (holes):
  /// then no orientation pass runs for M as given and the closure is M itself
  /// or the cone over dM, as on CUDA (a closed mesh with edges of more than two
  /// faces still gets the pass, for M+ alone: duplicates of closed parts).
  /// True: the orientation pass runs (flippedTriangles() tells what it found).
  static bool mayHaveReversedFaces(const PreparedMesh& mesh);
  /// Flips the sign of the voxels of one row (unsigned distances in out,
  /// world distance = out / toOut) where |w| >= 0.5. Positions x0 + i * h.
  /// fullSums (optional) counts voxels whose refinement summed every
  /// reversed/removed face exactly (or all of M, on an ambiguous oblique ray).
  /// priorLo/priorHi (optional, n entries): bounds of the correction s at
  /// each voxel already known (boundCorrection over a block of voxels; lo >
  /// hi where none), used before any refinement of the row.
  void signRow(V3 rowStart, double h, std::int64_t n, float* out, std::int64_t& evaluations,
    std::int64_t& fallbacks, std::int64_t* fullSums = nullptr, bool reoriented = false,
    const double* priorLo = nullptr, const double* priorHi = nullptr) const;
  /// Whether the sign needs the correction s (reversed, removed or capped faces).
  bool hasCorrection(bool reoriented) const { return this->correction(reoriented) != nullptr; }
  /// s over the ball (q, rho): true with [lo, hi] when it lies inside
  /// (n - 1/2, n + 1/2) for an integer n, which decides every voxel in the
  /// ball whatever its crossing count; false when it does not or cannot be
  /// bounded there.
  /// cut (optional): as DipoleTree::refine (start from it, end with the final one).
  bool boundCorrection(V3 q, double rho, double& lo, double& hi, std::int64_t& leafTris, bool reoriented,
    std::vector<std::int32_t>* cut = nullptr) const;
  /// s at each of the points pts[0, n), all within rho of centre (a block's
  /// voxels, positioned exactly as signRow positions them): rigorous
  /// intervals from one local expansion of the far clusters and the near
  /// faces summed at each point (localBounds, MeshToSdfDipoleLocal.h),
  /// refined until each lies inside (m - 1/2, m + 1/2) or a work budget per
  /// point is spent. Returns how many are so decided; start: a cut to begin
  /// from (the block's own failed ball bound's); counts (optional): what
  /// the expansion took, added to.
  int boundCorrectionAt(V3 centre, double rho, const V3* pts, int n, double* lo, double* hi, bool reoriented,
    const std::vector<std::int32_t>* start = nullptr, LocalBoundsCounts* counts = nullptr) const;
  /// Exact winding number at p by a ray in a fixed oblique direction; the
  /// sum of all solid angles if that ray is ambiguous. reoriented: of M+
  /// (every component consistently oriented, exact duplicates once) instead
  /// of M as given (MeshToSdfOptions::reorientFaces).
  double evaluate(V3 p, bool reoriented = false) const;

  struct Cluster
  {
    V3 centre;
    double radius = 0, length = 0;
  };
  /// A closed chain: triangles [0, meshTris) of `closed` are the mesh (some
  /// possibly reversed), the rest the caps (or the cone) over its boundary.
  struct Closure
  {
    /// The closed chain's triangles: `own`, or the mesh's own list when the
    /// mesh is closed as given (no copy; bvh is then a tree over mesh.tris).
    const TriList& closed() const { return this->shared ? *this->shared : this->own; }
    TriList own;
    const TriList* shared = nullptr;
    std::shared_ptr<const Bvh> bvh;
    TriList cone;
    std::vector<Cluster> clusters; // of boundary edges, for the drift bound
    std::size_t meshTris = 0;
  };
  /// The CPU's construction as the GPU takes it: the closed chain whose
  /// crossings count (M+ or M, closed by local caps) and the correction s
  /// (null when there is none). Unless the closure has a cone (only if the
  /// boundary could not be split into closed walks), the CUDA sign kernel
  /// uses exactly these (MeshToSdfCudaDipole.cuh), so both decide alike.
  /// reoriented: the winding number of M+ (MeshToSdfOptions::reorientFaces),
  /// the same kind of closure and correction, which signRow(reoriented) reads.
  bool gpuTakesCpuClosure(bool reoriented = false) const { return this->closure(reoriented).cone.empty(); }
  const Closure& cpuClosure(bool reoriented = false) const { return this->closure(reoriented); }
  const DipoleTree* cpuCorrection(bool reoriented = false) const { return this->correction(reoriented); }
  // the older CUDA construction, for a closure with a cone: the cone over the
  // boundary of M itself (built on first use when it differs from the CPU's closure)
  const TriList& closedTris() const { return this->coneOverMesh().closed(); }
  const Bvh& closedBvh() const { return *this->coneOverMesh().bvh; }
  const TriList& cone() const { return this->coneOverMesh().cone; }
  const std::vector<Cluster>& clusters() const { return this->coneOverMesh().clusters; }
  std::size_t meshTriangles() const { return this->coneOverMesh().meshTris; }
  /// The closure's tree when the closure is the mesh itself (a closed mesh as
  /// given: the same tree as Bvh(mesh.tris)), else null.
  std::shared_ptr<const Bvh> meshBvh() const { return this->Plus.shared ? this->Plus.bvh : nullptr; }
  /// Faces reversed (F) or removed as duplicates (R) by the orientation pass
  /// (Plus is M+ closed by caps when that is cheaper than caps over dM).
  std::size_t flippedTriangles() const { return this->CorrectedFaces; }
  /// Of those, the faces reversed against their neighbours (|F|), and the
  /// faces cancelled by an exact duplicate of opposite orientation: what the
  /// reversed-faces warning reports (0 when the pass did not run).
  std::size_t reversedFaces() const { return this->ReversedFaces; }
  std::size_t opposedDuplicates() const { return this->OpposedDuplicates; }
  /// Whether the CPU closes M+ (the faces re-oriented); false when it closes
  /// M itself by caps over dM (no reversed faces, or reversed patches whose
  /// rims are shorter than F).
  bool closesReorientedMesh() const { return this->CorrectedFaces != 0 && this->OrientState.empty(); }

private:
  const Closure& coneOverMesh() const;
  bool insideAt(V3 p, std::int64_t& fullSums, bool reoriented) const;
  const PreparedMesh& Mesh;
  /// The correction s (w = K - s) of M as given, or of M+ (reoriented).
  const DipoleTree* correction(bool reoriented) const;
  /// The closure whose crossings count: Plus, or M+ closed by its caps
  /// (reoriented, when Plus closes M itself although the orientation pass
  /// found reversed faces; built on first use).
  const Closure& closure(bool reoriented) const;
  Closure Plus;                          // M+ (F reversed, R removed) closed by local caps S over dM+, or M closed by caps over dM (or a cone)
  bool PlusIsCone = true;                // Plus is M closed by the cone over dM (what CUDA uses)
  std::size_t CorrectedFaces = 0;        // |F| + |R| found by the orientation pass
  std::size_t ReversedFaces = 0;         // |F|
  std::size_t OpposedDuplicates = 0;     // OrientedMesh::opposedDuplicates
  std::unique_ptr<DipoleTree> Flipped;   // F reversed, weight 2, R reversed, weight 1, and the caps S (null if all empty)
  std::unique_ptr<DipoleTree> CapsOnly;  // the caps S alone (reoriented), when F or R is not empty
  std::vector<std::uint8_t> OrientState;            // OrientedMesh::state when Plus closes M itself (caps over dM, or a closed M) but F or R is not empty
  std::vector<std::array<V3, 2>> OrientBoundary;     // the boundary of M+ then
  mutable std::once_flag ReorientedOnce;
  mutable std::unique_ptr<Closure> Reoriented;       // M+ closed by caps (reorientFaces), from OrientState
  mutable std::unique_ptr<DipoleTree> ReorientedCaps; // its caps
  mutable std::once_flag LegacyOnce;
  mutable std::unique_ptr<Closure> Legacy; // M closed by the cone over dM (CUDA), when F or R is not empty
};

/// Akenine-Moeller (2001) triangle/box overlap by the separating axis theorem
/// (13 axes). Conservative: the box is inflated by a relative 1e-9.
bool triangleBoxOverlap(const V3 tri[3], const double centre[3], const double half[3]);

class NearestIndex; // MeshToSdfNearest.h: the CPU nearest-triangle queries
struct MeshParts;     // MeshToSdfSolid.h: the connected parts
struct SolidBoundary; // MeshToSdfSolid.h: whether the mesh bounds a solid
struct SharpFeatures; // MeshToSdfSharpFeatures.h: the Normal sign of a solid by the winding path
struct FarCone;     // MeshToSdfFarBlocks.h: normal cones of the BVH's nodes

} // namespace detail::meshtosdf

namespace detail::meshtosdf_cuda
{
class DeviceMesh; // MeshToSdfCuda.h
}

/// What prepareMeshToSdf builds (immutable once built; the lazily built parts
/// are guarded by Lock).
struct MeshToSdfPrepared::Impl
{
  detail::meshtosdf::PreparedMesh mesh;
  /// The GPU's tree (and the far blocks'), built on first use (under Lock);
  /// for a closed mesh the same object as the winding closure's tree.
  std::shared_ptr<const detail::meshtosdf::Bvh> bvh;
  std::unique_ptr<detail::meshtosdf::NearestIndex> nearest; // the CPU's distance queries, built on first CPU use
  /// this->bvh, built (or taken from the winding closure) if missing; under Lock.
  const detail::meshtosdf::Bvh& meshBvhLocked();
  /// The same, taking Lock: the tree stays alive while the pointer is held.
  std::shared_ptr<const detail::meshtosdf::Bvh> meshBvh();
  /// The CPU's NearestIndex, built on first use (seconds added; under Lock).
  const detail::meshtosdf::NearestIndex& nearestIndex(double& seconds);
  double prepareSeconds = 0;
  /// For the far blocks of the Normal/PseudoNormal signs on the CPU: the
  /// binary BVH (the GPU's tree) and its node cones, built on first use
  /// (seconds added; under Lock).
  const detail::meshtosdf::Bvh& farTree(const std::vector<detail::meshtosdf::FarCone>*& cones, double& seconds);
  /// The winding-number structures, built on first use (seconds added).
  const detail::meshtosdf::WindingSigner& windingSigner(double& seconds);
  /// The records' pseudo-normals, built on first use (seconds added; under
  /// Lock): by every call whose sign reads them (Normal, PseudoNormal).
  void pseudoNormals(double& seconds);
  /// Whether the winding-number structures are built already.
  bool hasWindingSigner();
  /// The bounds (min x, y, z, max x, y, z) of each connected part of the
  /// mesh (faces joined by welded vertices), found on first use (under
  /// PartsLock, not Lock: on CUDA it runs beside the call's GPU session, which
  /// takes Lock; it reads only the welded faces and points, which nothing
  /// changes after preparation): a property of the mesh, not of a call's grid
  /// (warnIfPartsVanish).
  const std::vector<std::array<float, 6>>& partBounds();
  /// Each welded vertex's connected part, found on first use (under PartsLock).
  const detail::meshtosdf::MeshParts& parts();
  /// Whether the mesh bounds a solid (checkSolidBoundary: closed, manifold,
  /// not self-intersecting, winding number 0 or 1), checked on first use:
  /// then the PseudoNormal sign is the winding sign (MeshToSdf.cpp).
  const detail::meshtosdf::SolidBoundary& solidBoundary();
  /// Whether solidBoundary() has been found (then it costs nothing).
  bool solidBoundaryKnown() const { return this->SolidKnown.load(std::memory_order_acquire); }
  /// The sharp features (MeshToSdfSharpFeatures.h) of a mesh whose
  /// solidBoundary() holds, found on first use: for the Normal sign.
  const detail::meshtosdf::SharpFeatures& sharpFeatures();
  /// The mesh (and, when asked, the winding structures) on the GPU, uploaded
  /// on first use and kept until the prepared mesh is destroyed. The winding
  /// part may be added later (once) to a copy uploaded without it: sessions
  /// that do not use it never read it.
  /// windingLater: the winding part will be added soon (its memory is reserved now).
  /// reoriented: the winding part of M+ (reorientFaces) instead of M's.
  const detail::meshtosdf_cuda::DeviceMesh& deviceMesh(
    bool winding, bool normals, double& seconds, bool windingLater = false, bool reoriented = false);
  ~Impl();

private:
  std::mutex Lock;
  std::unique_ptr<detail::meshtosdf::WindingSigner> Winding;
  std::unique_ptr<std::vector<detail::meshtosdf::FarCone>> FarConesOfBvh;
  std::unique_ptr<detail::meshtosdf_cuda::DeviceMesh> Device;
  std::mutex PartsLock;
  std::unique_ptr<std::vector<std::array<float, 6>>> Parts;
  std::unique_ptr<detail::meshtosdf::MeshParts> PartsOfVertices;
  const detail::meshtosdf::MeshParts& partsLocked(); // under PartsLock
  std::once_flag SolidOnce;
  std::unique_ptr<detail::meshtosdf::SolidBoundary> Solid;
  std::atomic<bool> SolidKnown{ false };
  std::once_flag SharpOnce;
  std::unique_ptr<detail::meshtosdf::SharpFeatures> Sharp;
};

} // namespace lvdif
