// Mesh to signed distance field (paper Sect. 3.1, Algorithm 1), exact and
// with signs that survive broken meshes.
//
// Distance: the exact Euclidean distance from each voxel position to the
// nearest (non-degenerate) triangle, computed in double precision and stored
// as float (so exact within float rounding). The closest point uses
// Ericson's Voronoi-region routine (Real-Time Collision Detection, 5.1.5).
// Acceleration (all three give the same distance bit for bit):
//   Bvh        - branch-and-bound nearest triangle on a BVH, warm-started with
//                the previous voxel's triangle along each scan line (default);
//   Faithful   - the paper's uniform grid of M^3 cells whose triangle lists
//                come from the cells scaled by 2 (Akenine-Moeller SAT), with
//                every cell built and an exact expansion to all cells within
//                the current best distance (see FaithfulGrid in src/);
//   BruteForce - every triangle for every voxel (tests, tiny meshes).
// Sign (negative inside, the project's convention):
//   Normal        - Algorithm 1: the sign of (p - c) . n of the closest
//                   triangle, n its face normal (or, with useVertexNormals and
//                   normals in the mesh, the vertex normals interpolated at c);
//   PseudoNormal  - the angle-weighted pseudo-normal of the closest feature
//                   (Baerentzen & Aanaes 2005): right on closed, consistently
//                   oriented meshes; on a mesh proven to bound a solid it is
//                   the winding sign, and is computed so (solidsByWinding);
//   WindingNumber - inside iff |w| >= 0.5 for the generalized winding number
//                   w (Jacobson, Kavan, Sorkine-Hornung 2013), computed
//                   exactly (up to double rounding) by signed ray crossings
//                   along each scan line of the mesh closed by a cone over its
//                   boundary, minus the cone's solid angle; for open meshes w
//                   is carried along the line with a Biot-Savart bound of its
//                   variation. Details: src/MeshToSdfWinding.cpp.
// Units: distances in voxels (world distance / the smallest spacing), or world
// units with DistanceUnit::World. Band: |d| saturates at bandWidth.
#pragma once

#include "lvdif/Cuda.h"
#include "lvdif/DenseGrid.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdif/SignVoxelFilter.h"
#include "lvdif/TriangleMesh.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace lvdif
{

enum class SignMode
{
  Normal,
  PseudoNormal,
  WindingNumber,
  Unsigned // no sign (distance only)
};

enum class MeshToSdfAccel
{
  Bvh,
  Faithful,
  BruteForce
};

enum class DistanceUnit
{
  Voxel,
  World
};

struct MeshToSdfOptions
{
  SignMode sign = SignMode::WindingNumber;
  MeshToSdfAccel accel = MeshToSdfAccel::Bvh;
  int faithfulCellsPerAxis = 16; // M (the paper's scenes: 16)
  double faithfulScale = 2.0;    // overlap scale of the cells (paper: 2)
  bool useVertexNormals = false; // Normal mode: interpolate the mesh's vertex normals
  float bandWidth = std::numeric_limits<float>::infinity(); // |d| saturates here (output units)
  DistanceUnit unit = DistanceUnit::Voxel;
  /// WindingNumber only: the winding number of the mesh with every connected
  /// component consistently re-oriented (breadth-first over edges shared by
  /// two faces, the majority orientation kept) and exact duplicate faces
  /// counted once, instead of the mesh as given. For meshes whose face
  /// orientation cannot be trusted: with many reversed faces the exact winding
  /// number of the mesh as given drops below 1/2 inside (30 % reversed: ~0.4),
  /// the re-oriented one does not. Also faster on such meshes (its closure
  /// needs few or no correction faces). On CUDA too, the same field bit for
  /// bit, unless M+ cannot be closed by local caps (then the CPU). Without it,
  /// a call that meets reversed faces or duplicates that cancel adds a warning
  /// (MeshToSdfStats::warnings) naming this option.
  bool reorientFaces = false;
  /// Auto: CUDA when available (every sign mode and every mesh, damaged ones
  /// included, reorientFaces too), else the CPU; Cuda/Cpu are obeyed. The sign
  /// voxel filters follow it unless svf.device says otherwise.
  Device device = Device::Auto;
  /// Sign voxel filters (SvfBits) run on the result afterwards, with svf's
  /// parameters (meant for SignMode::Normal, as in the paper; 0 = none). On a
  /// sub-extent they see only that extent; on a dictionary volume they run
  /// through signVoxelFilter(DictionaryVolume&), which decodes it densely.
  unsigned svfFilters = 0;
  SignVoxelFilterParams svf;
  /// CUDA: bytes of the device slab buffer (z layers per slab follow from it;
  /// into a dictionary volume at least one layer of chunks per slab).
  std::uint64_t cudaSlabBytes = 256ull << 20;
  /// Into a dictionary volume only: the storage chunks to compute, an
  /// inclusive box of chunk coordinates (a pvbatch rank's chunk block);
  /// every other chunk is left as it is. Empty (the default): every chunk.
  /// The chunks get exactly the values of a whole-volume run. Not with
  /// svfFilters (the sign filters need the whole volume).
  VoxelBox chunkRegion;
  /// Into a dictionary volume on the CPU, and for a chunkRegion on either device: bytes of the float buffer the voxels are
  /// computed into before they are encoded (whole x rows of as many rows of
  /// chunks as fit, at least one): bounded, never a whole chunk layer.
  std::uint64_t cpuBandBytes = 32ull << 20;
  /// CUDA into a dictionary volume: also copy the float slabs back and check
  /// every GPU-encoded key against the host's encode (tests; costs the copy).
  bool cudaVerifyKeys = false;
  /// CUDA into a dictionary volume: the keys of the non-uniform chunks come
  /// back in pieces of about this many bytes (at least one chunk each) through
  /// pinned host memory kept for the process; the host stores piece k while
  /// piece k + 1 is copied and the GPU computes the next group of chunks.
  std::uint64_t cudaKeyPieceBytes = 8ull << 20;
  /// With a finite band: blocks of voxels that are provably past the band
  /// are filled without per-voxel queries; the result is the same, voxel for
  /// voxel (docs/MESH_TO_SDF.md, "Far blocks"). Normal and PseudoNormal also
  /// need every nearby triangle's plane to put the block on one side (its
  /// sign); WindingNumber and Unsigned (CPU) need the distance alone, their
  /// sign pass comes after. false: every voxel queried (tests and benchmarks
  /// compare the two).
  bool farBlocks = true;
  /// PseudoNormal and Normal: a mesh that bounds a solid (closed, a
  /// 2-manifold consistently oriented, not self-intersecting, winding number
  /// 0 or 1 everywhere; checked once per prepared mesh, conservatively) takes
  /// the winding-number path, which needs exact distances only in the band.
  /// Its sign is the pseudo-normal sign there (Baerentzen & Aanaes 2005); the
  /// normal sign differs from it only in the regions of sharp edges and
  /// vertices, whose voxels are then recomputed exactly (Normal without
  /// vertex normals, the BVH accelerator, the sharp features inside the
  /// grid). The same floats either way (MeshToSdfStats::signByWinding;
  /// docs/MESH_TO_SDF.md, "Pseudo-normal signs of solids", "Normal signs of
  /// solids"). false: their own paths always (tests compare).
  bool solidsByWinding = true;
  /// Print the host phases' times (preparation, search structures, upload) to
  /// stderr as they finish: for benchmarks (bench_mesh_to_sdf --trace).
  bool tracePhases = false;
};

struct MeshToSdfStats
{
  std::size_t triangles = 0;         // used (non-degenerate)
  std::size_t degenerateSkipped = 0; // zero-area triangles skipped
  std::size_t boundaryEdges = 0;     // edges whose oriented uses do not cancel (net multiplicity != 0): holes' rims,
                                     // and the rims of reversed or duplicated faces (the warnings name those); 0: closed
  Device device = Device::Cpu;
  double buildSeconds = 0, distanceSeconds = 0, signSeconds = 0, writeSeconds = 0;
  std::int64_t windingEvaluations = 0; // voxels whose winding number was evaluated (not carried)
  std::int64_t windingExact = 0;       // of those, on rows whose +x ray was ambiguous
  std::int64_t windingFullSums = 0;    // CPU: voxels whose sign needed every reversed/duplicate face summed exactly (docs/MESH_TO_SDF.md)
  std::uint64_t devicePeakBytes = 0;   // CUDA: device memory used
  std::int64_t keysVerified = 0;       // cudaVerifyKeys: voxels whose GPU key was checked
  std::int64_t keyMismatches = 0;      // cudaVerifyKeys: GPU keys != host encode (must be 0)
  std::int64_t farVoxels = 0;          // voxels filled by far blocks (MeshToSdfOptions::farBlocks)
  bool signByWinding = false;          // PseudoNormal/Normal on a solid's boundary: signs by the winding path (solidsByWinding)
  std::int64_t sharpVoxels = 0;        // Normal by the winding path: voxels recomputed in the sharp features' regions
  std::int64_t svfFlips = 0;           // signs changed by the sign voxel filters
  double svfSeconds = 0;
  /// When the result cannot be what the user expects, one sentence each
  /// naming the cause and the option that helps (the CLI prints them, the VTK
  /// filter emits them as warnings): a signed field over the whole grid with
  /// no voxel deeper than 1 voxel inside (an open mesh that encloses no
  /// volume, or voxels larger than the mesh's parts; meshing such a field
  /// gives no surface, or slivers), and a winding sign over faces reversed
  /// against their neighbours or cancelled by opposite duplicates without
  /// reorientFaces (extra surfaces inside the solid, a slower field), and
  /// the normal and pseudo-normal signs on closed parts whose faces point
  /// inwards (inside out there).
  std::vector<std::string> warnings;
};

/// A mesh prepared once for mesh to SDF and reusable across calls (other
/// grids, extents, options, devices): validated, pseudo-normals, boundary
/// cone, BVHs; the winding-number structures and the GPU upload are made on
/// first use and kept. It owns copies of everything it needs, so it never
/// returns stale results: editing or destroying the TriangleMesh afterwards
/// does not change it (prepare again for a changed mesh). Copies share the
/// same prepared data; concurrent calls with one prepared mesh are safe.
class MeshToSdfPrepared
{
public:
  struct Impl; // MeshToSdfInternal.h
  explicit MeshToSdfPrepared(std::shared_ptr<Impl> impl)
    : Pimpl(std::move(impl))
  {
  }
  std::size_t triangles() const;         // used (non-degenerate)
  std::size_t degenerateSkipped() const; // zero-area triangles skipped
  std::size_t boundaryEdges() const;     // as MeshToSdfStats::boundaryEdges; 0: closed
  double prepareSeconds() const;         // host time spent by prepareMeshToSdf
  Impl& impl() const { return *this->Pimpl; }

private:
  std::shared_ptr<Impl> Pimpl;
};

/// Prepares the mesh (OpenMP). With sign == WindingNumber the winding
/// structures are built now, otherwise on first use. Throws Error on bad
/// input (empty mesh, NaN, no triangle of non-zero area).
MeshToSdfPrepared prepareMeshToSdf(const TriangleMesh& mesh, SignMode sign = SignMode::WindingNumber);

/// Isotropic voxels fitted to the mesh bounds: the longest axis gets maxDim
/// voxels, every axis has paddingVoxels voxels of margin on both sides and
/// as many voxels as it needs (dims need not be equal or powers of two).
GridGeometry fitGridToMesh(const TriangleMesh& mesh, std::int64_t maxDim, double paddingVoxels);

/// Computes the voxels of `extent` (indices in the whole grid `grid`) into
/// out, laid out over the extent (x fastest). Throws Error on bad input
/// (empty mesh, NaN, zero-size grid, absurd sizes), Cancelled when interrupted.
MeshToSdfStats meshToSdf(const TriangleMesh& mesh, const GridGeometry& grid, const VoxelBox& extent, float* out,
  const MeshToSdfOptions& options, Interrupter& interrupter = nullInterrupter());

/// The whole grid of a dense view.
MeshToSdfStats meshToSdf(const TriangleMesh& mesh, const FloatGridView& out, const MeshToSdfOptions& options,
  Interrupter& interrupter = nullInterrupter());

/// Straight into a dictionary volume (its origin, spacing and dims), one
/// slab of chunks at a time: chunks saturated at the volume's band become
/// uniform, no full float array is ever allocated. The volume's band width
/// applies (options.bandWidth is ignored); units are voxels.
MeshToSdfStats meshToSdf(const TriangleMesh& mesh, DictionaryVolume& volume, const MeshToSdfOptions& options,
  Interrupter& interrupter = nullInterrupter());

/// Bytes the volume certainly needs after meshToSdf(mesh, volume, options):
/// its chunk table and the chunks (of options.chunkRegion, if given) that the
/// mesh's surface passes through or that hold a voxel within band - 1 of it,
/// which hold voxels below the band (a lower bound: never more than the
/// conversion takes). meshToSdf(mesh, volume, ...)
/// refuses a volume whose bound exceeds its memory limit before any work,
/// naming the limit (LVDIF_MEMORY_LIMIT) and the options of fewer voxels.
std::uint64_t meshToSdfLeastMemory(const TriangleMesh& mesh, const DictionaryVolume& volume,
  const MeshToSdfOptions& options);

/// The same three calls on a prepared mesh: no preparation, and on CUDA no
/// upload after the first call (buildSeconds then holds only what was still
/// missing, e.g. the first upload).
MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const VoxelBox& extent, float* out,
  const MeshToSdfOptions& options, Interrupter& interrupter = nullInterrupter());
MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, const FloatGridView& out, const MeshToSdfOptions& options,
  Interrupter& interrupter = nullInterrupter());
MeshToSdfStats meshToSdf(const MeshToSdfPrepared& mesh, DictionaryVolume& volume, const MeshToSdfOptions& options,
  Interrupter& interrupter = nullInterrupter());

const char* toString(SignMode mode);
const char* toString(MeshToSdfAccel accel);

/// The one parser of the sign modes' command-line names (`lvdif mesh-to-sdf
/// --sign`, `lvdif-editor --mesh-sign`): normal, pseudo, winding. Any other
/// name is Error(InvalidArgument) "<option> must be normal, pseudo or winding,
/// not '<name>'".
SignMode signModeFromName(const std::string& name, const std::string& option);
/// The command-line name of a mode (what signModeFromName reads back);
/// toString's for Unsigned, which has none.
const char* signModeName(SignMode mode);

} // namespace lvdif
