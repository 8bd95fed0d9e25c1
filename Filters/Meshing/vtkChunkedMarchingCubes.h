/**
 * @class   vtkChunkedMarchingCubes
 * @brief   seamless chunked marching cubes of an SDF image or dictionary volume (paper Sect. 3.3)
 *
 * A thin wrapper over lvdif::ChunkedMarchingCubes. Input, one of:
 * - a vtkSparseDictionaryVolume (vtkDictionaryVolumeReader, vtkMeshToSDF,
 *   vtkSignVoxelFilter, vtkImageToSparseVolume): its Core volume is meshed
 *   directly, in batches of chunks, without a dense copy (colours from its
 *   colour dictionary). In PARTITIONED mode (one piece) the filter keeps the
 *   chunk meshes of its last run (shared with its output): when the input
 *   holds the same Core volume again, edited in place and announced with
 *   vtkSparseDictionaryVolume::VolumeModified(), only the chunks its dirty
 *   storage chunks reach are meshed again (the dirty flags are taken, i.e.
 *   cleared); any change of the filter's settings meshes everything;
 * - vtkImageData on port 0 with a scalar point array (default `sdf`, negative
 *   inside; choose another with SetInputArrayToProcess(0, 0, 0,
 *   vtkDataObject::FIELD_ASSOCIATION_POINTS, name)) and an optional
 *   4-component unsigned char colour array (default `rgba`);
 * - an lvdif::DictionaryVolume given with SetVolume() and nothing connected to
 *   port 0 (the filter then acts as a source): it is meshed directly, chunk by
 *   chunk, without a dense copy (colours from its colour dictionary). The
 *   volume is shared, not copied: call Modified() after editing it. The result
 *   equals meshing its dense image (vtkDictionaryVolumeToImage) with the
 *   same settings. Connecting an input while a volume is set is an error.
 * A volume of fewer than 2 points along some axis (16 x 12 x 1: a slice) has
 * no cells and is refused with one error naming its dimensions, as
 * vtkMarchingCubes refuses it; an empty one (0 points) gives an empty output.
 *
 * Case table (UseVTKCaseTable, default on): VTK's own table
 * (vtkMarchingCubesTriangleCases, read at run time and converted to lvdif's
 * numbering), so the surface is vtkMarchingCubes' / vtkFlyingEdges3D's:
 * the same triangles (as sets of 3 vertices; ours are counter-clockwise seen
 * from outside, VTK's the other way round) up to float rounding of the vertex
 * positions, after merging chunk seams. Off: lvdif's own generated table (same
 * loops and triangle counts, other diagonals inside some 4- to 7-vertex loops).
 *
 * Output (OutputMode):
 * - PARTITIONED: a vtkPartitionedDataSet with one vtkPolyData per non-empty
 *   chunk, each with field data `chunk_id` (vtkIdType: x + cx*(y + cy*z) of the
 *   chunk coordinate, cx, cy chunk counts of the whole extent) and `chunk_ijk`
 *   (int, 3 components). Chunk boundary vertices appear in both chunks with
 *   bit-identical coordinates.
 * - MERGED: one vtkPolyData, chunk boundary vertices merged (one point per cut
 *   grid edge), so a closed surface is watertight as it is.
 * Point arrays: `Normals` (unit, outward: along the SDF gradient) when
 * ComputeNormals, `rgba` (interpolated along the cut edge) when ComputeColors
 * and the input has colours. Cell arrays (ComputeCornerColors): `cell_ijk`
 * (int, 3 components: the structured index of the cell's lowest point) and,
 * with colours, `corner_rgba` (unsigned char, 32 components: the RGBA of the
 * cell's 8 corners, corner c at offset (c&1, (c>>1)&1, (c>>2)&1)) for the
 * tetrahedral colour shader. Triangles are counter-clockwise seen from outside.
 *
 * Chunks are ChunkEdge^3 cells aligned to the whole extent's first point.
 *
 * Pieces: the filter asks its input for the piece's extent (vtkExtentTranslator,
 * block mode, split by cells so neighbouring pieces share a plane of points)
 * plus one ghost level, which makes gradients at piece borders central
 * differences as in a one-piece run. Ownership rule: a cell belongs to the
 * piece whose (ghost-free) piece extent contains its lowest corner AND its
 * upper corner, i.e. lowest corner in [lo, hi-1] of the piece extent. Pieces
 * therefore partition the cells: no triangle is emitted twice, and the vertices
 * on a shared plane are bit-identical (positions are computed from global point
 * indices), so the union of the pieces is seamless.
 *
 * Progress and abort: UpdateProgress / AbortExecute through LVDIFInterrupter.
 */
#ifndef vtkChunkedMarchingCubes_h
#define vtkChunkedMarchingCubes_h

#include "lvdifFiltersMeshingModule.h"
#include "vtkDataObjectAlgorithm.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include <memory>
#include <vector>

class vtkPartitionedDataSet;
namespace lvdif
{
class DictionaryVolume;
struct ChunkMesh;
struct MarchingCubesOptions;
}
namespace LVDIFChunkedMarchingCubesOutput
{
struct Context;
}

class LVDIFFILTERSMESHING_EXPORT vtkChunkedMarchingCubes : public vtkDataObjectAlgorithm
{
public:
  static vtkChunkedMarchingCubes* New();
  vtkTypeMacro(vtkChunkedMarchingCubes, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum OutputModes
  {
    PARTITIONED = 0,
    MERGED = 1
  };
  enum Devices
  {
    DEVICE_AUTO = 0,
    DEVICE_CPU = 1,
    DEVICE_CUDA = 2
  };

  ///@{
  /// PARTITIONED (default): one vtkPolyData per chunk; MERGED: one vtkPolyData;
  /// anything else is an error at update (no clamp).
  vtkSetMacro(OutputMode, int);
  vtkGetMacro(OutputMode, int);
  void SetOutputModeToPartitioned() { this->SetOutputMode(PARTITIONED); }
  void SetOutputModeToMerged() { this->SetOutputMode(MERGED); }
  ///@}

  ///@{
  /// The iso value (default 0: the SDF's zero set).
  vtkSetMacro(IsoValue, double);
  vtkGetMacro(IsoValue, double);
  ///@}

  ///@{
  /// Cells per chunk edge, 16..256 (default 64); out of range: an error at
  /// update (no clamp).
  vtkSetMacro(ChunkEdge, int);
  vtkGetMacro(ChunkEdge, int);
  ///@}

  ///@{
  /// Per-vertex `Normals` from the SDF gradient (default on).
  vtkSetMacro(ComputeNormals, vtkTypeBool);
  vtkGetMacro(ComputeNormals, vtkTypeBool);
  vtkBooleanMacro(ComputeNormals, vtkTypeBool);
  ///@}

  ///@{
  /// Per-vertex `rgba` when the input has the colour array (default on).
  vtkSetMacro(ComputeColors, vtkTypeBool);
  vtkGetMacro(ComputeColors, vtkTypeBool);
  vtkBooleanMacro(ComputeColors, vtkTypeBool);
  ///@}

  ///@{
  /// Per-triangle `cell_ijk` and (with colours) `corner_rgba` (default on).
  vtkSetMacro(ComputeCornerColors, vtkTypeBool);
  vtkGetMacro(ComputeCornerColors, vtkTypeBool);
  vtkBooleanMacro(ComputeCornerColors, vtkTypeBool);
  ///@}

  ///@{
  /// Name of the input's colour point array (default `rgba`).
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  ///@}

  ///@{
  /// DEVICE_AUTO (default), DEVICE_CPU or DEVICE_CUDA (falls back to the CPU
  /// without a GPU). On the GPU the image is uploaded at every execution, then
  /// meshed in batches of chunks; the result equals the CPU's (same vertices
  /// bit for bit, same triangles; points numbered in another order). Anything
  /// else is an error at update (LVDIFVolumeBridge::DeviceOption; no clamp).
  vtkSetMacro(Device, int);
  vtkGetMacro(Device, int);
  ///@}

  ///@{
  /// On (default): VTK's marching cubes case table (the surface of
  /// vtkMarchingCubes / vtkFlyingEdges3D); off: lvdif's own table.
  vtkSetMacro(UseVTKCaseTable, vtkTypeBool);
  vtkGetMacro(UseVTKCaseTable, vtkTypeBool);
  vtkBooleanMacro(UseVTKCaseTable, vtkTypeBool);
  ///@}

  /// Chunks meshed by the last run when it was incremental (sparse input,
  /// PARTITIONED, the same Core volume as the run before, settings unchanged);
  /// -1 when the last run meshed everything.
  vtkIdType GetLastChunksMeshed() const { return this->LastChunksMeshed; }

#ifndef __VTK_WRAP__
  ///@{
  /// A dictionary volume to mesh directly (used when nothing is connected to
  /// port 0); null (default) to mesh the input image. Call Modified() after
  /// editing the volume.
  void SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume);
  std::shared_ptr<lvdif::DictionaryVolume> GetVolume() const { return this->Volume; }
  ///@}
#endif

protected:
  vtkChunkedMarchingCubes();
  ~vtkChunkedMarchingCubes() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData: Extract, and a failure (always after its one error) marked
  /// reported (LVDIFVolumeBridge::FailReported: no executive dump after it).
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int Extract(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  /// The options common to both sources (no region, offset or colours yet).
  lvdif::MarchingCubesOptions CoreOptions() const;
  /// Meshes the cells piece `piece` of `pieces` owns of `volume` into output.
  int MeshVolume(const lvdif::DictionaryVolume& volume, int piece, int pieces, vtkDataObject* output);
  /// Fills output (vtkPolyData: merged; vtkPartitionedDataSet: one per chunk).
  int Emit(const std::vector<lvdif::ChunkMesh>& meshes, const LVDIFChunkedMarchingCubesOutput::Context& ctx,
    const int whole[6], vtkDataObject* output);

  /// Sparse input, PARTITIONED, one piece: remeshes only the chunks the
  /// volume's dirty storage chunks reach when the volume and settings are
  /// those of the last run, else everything.
  int MeshVolumeIncrementally(const std::shared_ptr<lvdif::DictionaryVolume>& volume, vtkPartitionedDataSet* output);
  /// Appends one vtkPolyData partition per chunk mesh (with `chunk_id`, `chunk_ijk`).
  void AddPartitions(const std::vector<lvdif::ChunkMesh>& meshes, const LVDIFChunkedMarchingCubesOutput::Context& ctx,
    const int whole[6], vtkPartitionedDataSet* partitioned);

  int OutputMode = PARTITIONED;
  double IsoValue = 0.0;
  int ChunkEdge = 64;
  vtkTypeBool ComputeNormals = 1;
  vtkTypeBool ComputeColors = 1;
  vtkTypeBool ComputeCornerColors = 1;
  char* ColorArrayName = nullptr;
  int Device = DEVICE_AUTO;
  vtkTypeBool UseVTKCaseTable = 1;
  std::shared_ptr<lvdif::DictionaryVolume> Volume;
  vtkSmartPointer<vtkPartitionedDataSet> Cache;
  std::weak_ptr<lvdif::DictionaryVolume> CachedVolume;
  vtkTimeStamp CacheTime;
  vtkIdType LastChunksMeshed = -1;

private:
  vtkChunkedMarchingCubes(const vtkChunkedMarchingCubes&) = delete;
  void operator=(const vtkChunkedMarchingCubes&) = delete;
};

#endif
