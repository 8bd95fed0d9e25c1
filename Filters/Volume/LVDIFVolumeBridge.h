/**
 * @file   LVDIFVolumeBridge.h
 * @brief  conversions between lvdif::DictionaryVolume and vtkImageData
 *
 * Image data use the project's array names: a float point array `sdf`
 * (negative inside, voxel units) and an optional 4-component unsigned char
 * array `rgba`. Extents are VTK extents (inclusive point indices) of the
 * volume's whole extent [0, dims-1].
 */
#ifndef LVDIFVolumeBridge_h
#define LVDIFVolumeBridge_h

#include "lvdif/DenseGrid.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdif/TriangleMesh.h"
#include "lvdifFiltersVolumeModule.h"

#include "lvdif/Cuda.h"

#include "vtkSmartPointer.h"

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>

class vtkAlgorithm;
class vtkDataArray;
class vtkDataObject;
class vtkDataSet;
class vtkFloatArray;
class vtkImageData;
class vtkIdTypeArray;
class vtkInformation;
class vtkInformationIntegerKey;
class vtkInformationVector;
class vtkIntArray;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace LVDIFVolumeBridge
{
/// The project's array names (README "Conventions").
constexpr const char* SdfArrayName = "sdf";
constexpr const char* ColorArrayName = "rgba";

/// The filters' Device property (0 auto, 1 CPU, 2 CUDA) as lvdif's Device
/// (DeviceOption checked it first).
LVDIFFILTERSVOLUME_EXPORT lvdif::Device ToDevice(int device);

/// The one rule for an enumeration property (Device, Boundary, Sign Mode, ...):
/// `value` must be one of 0 .. names.size() - 1; anything else is refused with
/// an lvdif::Error naming the property, the allowed values and the value given
/// ("Device must be 0 (auto), 1 (CPU) or 2 (CUDA), not 3"), never clamped
/// (vtkSetClampMacro turned Device 7 into CUDA silently). Returns `value`.
/// The filters check their enumerations with their other settings, at update.
LVDIFFILTERSVOLUME_EXPORT int EnumOption(int value, const std::string& name, std::initializer_list<const char*> names);
/// EnumOption for every filter's Device property (0 auto, 1 CPU, 2 CUDA).
LVDIFFILTERSVOLUME_EXPORT int DeviceOption(int device);

/// "cannot VERB 'PATH': WHAT", the file named once: Core's file errors already
/// name it ("cannot open 'PATH': No such file ..."), and were reported as
/// "cannot read 'PATH': cannot open 'PATH': ...". Every reader and writer's
/// file error goes through here.
LVDIFFILTERSVOLUME_EXPORT std::string FileError(const std::string& verb, const std::string& path, const std::string& what);
/// The one rule for a band setting (every filter's and writer's BandWidth, the
/// CLI's --band): a number of voxels > 0, 0 (or VTK_FLOAT_MAX and more) for no
/// band (infinity); negative or NaN is refused with an lvdif::Error naming
/// `name` (both meant no band, silently). Widths below the dictionary's step are
/// refused by the volume itself.
LVDIFFILTERSVOLUME_EXPORT float BandOption(double bandWidth, const std::string& name = "BandWidth");

/// The one rule for a fitted grid's padding (vtkMeshToSDF's Padding, the CLI's
/// --padding), as BandOption's: a finite number of voxels >= 0; negative, NaN or
/// infinite is refused with an lvdif::Error naming `name` (the filter clamped a
/// negative padding to 0 silently). Returns the padding.
LVDIFFILTERSVOLUME_EXPORT double PaddingOption(double padding, const std::string& name = "Padding");

/// A filter's ChunkEdge and BandWidth settings checked by the one rule before
/// any work (Core's chunk edge rule: a power of two in [4, 256], no clamp; and
/// BandOption); throws lvdif::Error. Returns the band (BandOption's).
LVDIFFILTERSVOLUME_EXPORT float CheckVolumeSettings(
  int chunkEdge, double bandWidth, const std::string& bandName = "BandWidth");

/// FileError's rule: `context` + `what`, unless `what` already holds the first
/// 'quoted' name of `context` (then `what` alone).
LVDIFFILTERSVOLUME_EXPORT std::string WithContext(const std::string& context, const std::string& what);

/// Calls Core: returns true on success; on lvdif::Error reports it with
/// vtkErrorMacro's text on `algorithm` (prefixed by `context` when given, unless
/// the message already holds the context's quoted file name: FileError's rule) and
/// returns false; likewise on std::bad_alloc ("out of memory"). A cancel (AbortExecute through LVDIFInterrupter) returns
/// false without an error, and sets `cancelled` when given.
LVDIFFILTERSVOLUME_EXPORT bool CallCore(vtkAlgorithm* algorithm, const std::function<void()>& work,
  const std::string& context = std::string(), bool* cancelled = nullptr);

/// The message itself of a VTK error or warning event's text (the call data
/// of vtkCommand::ErrorEvent / WarningEvent): without VTK's "ERROR: In file,
/// line N" preamble and "Class (0x...): " prefix, trailing newlines dropped.
LVDIFFILTERSVOLUME_EXPORT std::string MessageText(const char* vtkMessage);

/// A vtkPolyData's polygons (fan-triangulated: exact for convex polygons) and
/// triangle strips (split keeping the strip's orientation) as an lvdif mesh;
/// with withNormals, its 3-component point normals too.
LVDIFFILTERSVOLUME_EXPORT lvdif::TriangleMesh ToTriangleMesh(vtkPolyData* polyData, bool withNormals);

/// An lvdif mesh as vtkPolyData: float points, triangles, `Normals` when it has them.
LVDIFFILTERSVOLUME_EXPORT vtkSmartPointer<vtkPolyData> ToPolyData(const lvdif::TriangleMesh& mesh);

/// VTK's rule for an empty input (vtkContourFilter, vtkCutter: an empty output
/// and success, no error), which every LVDIF filter follows: true for a sparse
/// volume that holds no volume and for a data set without points. A filter
/// below a failed reader or filter gets such an input (ParaView runs it anyway):
/// the failure said why once; each filter below it added an error of its own.
/// False for no input (the executive reports a missing connection).
LVDIFFILTERSVOLUME_EXPORT bool IsEmptyInput(vtkDataObject* input);

/// RequestDataObject of a filter whose output port 0 is a vtkSparseDictionaryVolume.
LVDIFFILTERSVOLUME_EXPORT void EnsureSparseOutput(vtkInformationVector* outputVector);

/// What a sparse volume producer announces in RequestInformation: the volume's
/// whole extent, origin and spacing (read by vtkSparseVolumeToImage and the
/// piece logic of the consumers), and its chunk edge (CHUNK_EDGE).
LVDIFFILTERSVOLUME_EXPORT void SetSparseInformation(vtkInformation* outInfo, const lvdif::VolumeOptions& options);

/// The storage chunks a piece of a sparse volume owns when a generic filter
/// asks for piece `piece` of `pieces` (ParaView's Contour under pvbatch): the
/// chunk boundaries 0..C of each axis are split like a point extent
/// (vtkExtentTranslator, block mode, by cells), and the piece owns the chunks
/// between its boundaries, `owned` as an inclusive box of chunk coordinates.
/// `region` gets the voxels it needs: its chunks plus the one layer of points
/// their partitions share with the next chunks. False for a piece without chunks.
LVDIFFILTERSVOLUME_EXPORT bool PieceChunks(
  int piece, int pieces, const lvdif::VolumeOptions& options, int owned[6], lvdif::VoxelBox& region);

/// A piece's `region` (PieceChunks': its chunks and the one layer of points
/// their partitions share with the next chunks) grown to whole chunks, as the
/// .lvdv reader loads them: whether a uniform chunk has a partition depends on
/// its neighbour chunks as a whole, so a producer that filled only the shared
/// layer of a neighbour (its other voxels left outside) gave partitions the
/// serial run has not (ParaView's Integrate Variables over 2 ranks differed).
LVDIFFILTERSVOLUME_EXPORT void GrowToWholeChunks(lvdif::VoxelBox& region, const lvdif::VolumeOptions& options);

/// The voxels a sparse producer's request needs, by the .lvdv reader's rule:
/// piece p of n > 1: its chunk block (PieceChunks; `owned` set, returns 1, or
/// -1 for a piece without chunks); else an update extent smaller than the
/// whole: those voxels (returns 2); else the whole volume (returns 0).
LVDIFFILTERSVOLUME_EXPORT int RequestedVoxels(
  vtkInformation* outInfo, const lvdif::VolumeOptions& options, int owned[6], lvdif::VoxelBox& region);
/// ParaView (pvpython's UpdatePipeline, the GUI's Apply) runs RequestData even
/// when RequestInformation failed, and the error came twice (the second one
/// often less clear: "cannot open ''"). RequestInformation calls
/// BeginInformation first and returns FailInformation (0) after reporting an
/// error; RequestData returns 0 without a second error when InformationFailed
/// (which empties the output).
/// Both failures also drop the executive's own "Algorithm X returned failure for
/// request: <the request dumped>" that would follow the algorithm's error (one
/// error per failure, in pvpython too; FailReported marks a RequestData that
/// failed after reporting its error and returns 0).
LVDIFFILTERSVOLUME_EXPORT void BeginInformation(vtkInformation* outInfo);
LVDIFFILTERSVOLUME_EXPORT int FailInformation(vtkInformation* outInfo);
LVDIFFILTERSVOLUME_EXPORT bool InformationFailed(vtkInformation* outInfo);
LVDIFFILTERSVOLUME_EXPORT int FailReported(vtkInformation* outInfo);

/// The chunk edge of a sparse producer's volume, announced before the data
/// exists, so that a consumer can ask for whole chunks (vtkSignVoxelFilter's pieces).
LVDIFFILTERSVOLUME_EXPORT vtkInformationIntegerKey* CHUNK_EDGE();

/// Writes the voxels of `extent` (clipped to the volume) into `image`:
/// extent, origin, spacing, `sdf` and, if withColor, `rgba`.
/// With an `interrupter`: progress over the planes and its cancel polled at each
/// plane (Error(Cancelled) after the planes begun; `image` then gets no arrays).
LVDIFFILTERSVOLUME_EXPORT void FillImage(const lvdif::DictionaryVolume& volume, const int extent[6],
  vtkImageData* image, bool withColor, lvdif::Interrupter* interrupter = nullptr);

/// Builds a dictionary volume from an image's float SDF array (any real type
/// is converted) and optional RGBA array (1 to 4 unsigned char components).
/// `options` supplies chunk edge, band width and dictionary; dims, origin and
/// spacing come from the image. Throws lvdif::Error on bad input, and on an
/// image whose direction matrix is not the identity (the volume is axis-aligned).
/// With an `interrupter`: progress over the chunks and its cancel polled at each
/// chunk (Error(Cancelled) after the chunks begun).
LVDIFFILTERSVOLUME_EXPORT std::unique_ptr<lvdif::DictionaryVolume> VolumeFromImage(vtkImageData* image,
  vtkDataArray* sdf, vtkDataArray* rgba, lvdif::VolumeOptions options, lvdif::Interrupter* interrupter = nullptr);

/// A piece's volume: `options` gives the whole grid (dims, origin, spacing as
/// well), whose point (0, 0, 0) is the image's point `wholeLo` (the whole
/// extent's first point); only the chunks holding voxels of `region` are
/// written, from the image (its extent must cover the region), the others stay
/// uniform outside. The chunk grid is then the whole grid's, as the readers'
/// pieces (vtkImageToSparseVolume under pvbatch). Throws as VolumeFromImage.
LVDIFFILTERSVOLUME_EXPORT std::unique_ptr<lvdif::DictionaryVolume> VolumeFromImageRegion(vtkImageData* image,
  vtkDataArray* sdf, vtkDataArray* rgba, lvdif::VolumeOptions options, const int wholeLo[3],
  const lvdif::VoxelBox& region, lvdif::Interrupter* interrupter = nullptr);

/// The voxels of `extent` (inclusive point indices, inside the volume) as a
/// volume of their own: the same chunk edge, band, dictionaries and keys
/// (no re-encoding), origin moved to the extent's first point.
LVDIFFILTERSVOLUME_EXPORT std::unique_ptr<lvdif::DictionaryVolume> CropVolume(
  const lvdif::DictionaryVolume& volume, const int extent[6]);

/// What an image source of this volume announces in RequestInformation: whole
/// extent, origin, spacing, CAN_PRODUCE_SUB_EXTENT and a float `sdf` scalar.
LVDIFFILTERSVOLUME_EXPORT void SetImageInformation(vtkInformation* outInfo, const lvdif::VolumeOptions& options);


/// What a filter or reader says (vtkWarningMacro) before it allocates a dense
/// image of `bytes` for `extent`: the size, the memory limit and what to do;
/// "" for images under 1 GiB and under half the limit. Above the limit the
/// allocation itself is refused (lvdif::requireMemory).
LVDIFFILTERSVOLUME_EXPORT std::string DenseImageWarning(
  std::uint64_t bytes, const int extent[6], std::uint64_t limit, const char* advice);

/// Throws lvdif::Error (InvalidArgument, naming the matrix) when the image's
/// direction matrix is not the identity: the one check of every image input
/// (VolumeFromImage, vtkChunkedMarchingCubes), whose volumes and meshes are axis-aligned.
LVDIFFILTERSVOLUME_EXPORT void RequireAxisAligned(vtkImageData* image);

/// Geometry of an image's point grid (dims from its extent; origin moved to the extent's first point).
LVDIFFILTERSVOLUME_EXPORT lvdif::GridGeometry Geometry(vtkImageData* image);

/// A view of a float array's storage when it is a contiguous single-component
/// vtkFloatArray covering the image's points; data is nullptr otherwise.
LVDIFFILTERSVOLUME_EXPORT lvdif::FloatGridView FloatView(vtkImageData* image, vtkDataArray* array);

/// The SDF array a filter processes: `selected` (its GetInputArrayToProcess)
/// when found; when the selection names no array (`selection` is the
/// filter's GetInputArrayInformation: ParaView sends an empty name for a
/// filter chained to one not yet updated), the point array `sdf`, else the
/// active point scalars; nullptr when a named array is missing.
LVDIFFILTERSVOLUME_EXPORT vtkDataArray* SdfArray(vtkInformation* selection, vtkDataSet* input, vtkDataArray* selected);

/// Computes the ranges of an array written through its raw pointer (1 to 4
/// components: each component's and the magnitude's) and stores them as the
/// array's cached ranges and finite ranges (what GetRange/GetFiniteRange return
/// until the next Modified()). ParaView asks every new output, and every
/// partition of the sparse volume, for them: VTK's generic pass takes about
/// 1 s for 10^8 values, and a thread pool per call under the STDThread backend
/// (~12 calls per partition). Nothing is cached when a value is not finite
/// (VTK then computes as usual).
LVDIFFILTERSVOLUME_EXPORT void StoreRange(vtkFloatArray* array);
LVDIFFILTERSVOLUME_EXPORT void StoreRange(vtkUnsignedCharArray* array);
LVDIFFILTERSVOLUME_EXPORT void StoreRange(vtkIntArray* array);
LVDIFFILTERSVOLUME_EXPORT void StoreRange(vtkIdTypeArray* array);
}

#endif
