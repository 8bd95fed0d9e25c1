/**
 * @class   vtkSparseDictionaryVolume
 * @brief   the sparse dictionary volume as a VTK data object (no dense copy)
 *
 * A vtkPartitionedDataSet that holds an lvdif::DictionaryVolume by shared
 * pointer: the storage chunks, both dictionaries, the uniform (collapsed)
 * chunks and the dirty flags are the Core volume's own, never copied. Our
 * filters (vtkChunkedMarchingCubes, vtkSignVoxelFilter,
 * vtkDictionaryVolumeWriter, vtkSparseVolumeToImage) work on GetVolume().
 *
 * For generic VTK filters and ParaView the partitions are vtkImageData, one
 * per storage chunk whose cells are not all equal: chunk c owns the voxels
 * [lo, hi] and its partition has the points [lo, hi + 1] (clipped to the
 * volume), i.e. it shares one boundary layer of points with its upper
 * neighbours. Every cell with differing corner values then lies in exactly one
 * partition, so vtkContourFilter / vtkCutter / vtkThreshold run per partition
 * and meet without seams (shared points are bit-identical: same global index,
 * same origin and spacing). Point arrays: float `sdf` (decoded, negative
 * inside, voxel units) and, with PartitionColors on, unsigned char `rgba`;
 * field data `chunk_id` and `chunk_ijk` as vtkChunkedMarchingCubes writes
 * them. Uniform regions have no partition (their value is +-band, no surface).
 *
 * Bounds: the grid's box, as a vtkImageData's (and a vtkOverlappingAMR's,
 * whose bounds are its grid's, not its blocks'). VTK's composite consumers
 * (vtkCompositeDataSet::GetBounds, vtkOutlineFilter, ParaView's Outline
 * filter and data information) take the bounds from the leaves, so when the
 * band's partitions do not reach a corner of the grid, a partition of that
 * one grid point (its decoded `sdf`/`rgba`, the field data of its chunk; one
 * vertex cell, VTK's for a one-point image) comes first (the lower corner) or
 * last (the upper corner). Contour and Slice find nothing there (Threshold
 * keeps the vertex when its value passes: it is a point of the grid); they were the narrow band's bounds
 * until session 22. With SetOwnedChunks the corners are those of the owned
 * chunks' points, so the pieces' boxes make the grid's.
 *
 * The partitions are built lazily, on the first request through the
 * composite API (NewIterator, NewTreeIterator, GetNumberOfPartitions,
 * GetPartition, CopyStructure, ShallowCopy of this object), so a pipeline of
 * our own filters never makes them (nor decodes any). What building them does:
 *  - held (the default): every partition is decoded then (DecodePartitions(),
 *    checked against lvdif's memory limit, LVDIF_MEMORY_LIMIT), held by the
 *    object until the volume changes (VolumeModified, SetVolume, Initialize,
 *    ReleaseData) or ReleaseDecodedPartitions(), and set as the tree's leaf
 *    (the superclass's storage), so every VTK path sees the decoded images:
 *    this class's overrides and iterator, and the paths that read the tree
 *    itself (vtkPartitionedDataSet::GetPartition through a base-class pointer,
 *    DeepCopy or ShallowCopy into a plain vtkPartitionedDataSet, a consumer's
 *    own vtkDataObjectTreeIterator, vtkXMLPartitionedDataSetWriter). Any
 *    consumer may keep the pointers it got (vtkCompositeDataSet::GetDataSets
 *    collects every leaf before using them: vtkArrayCalculator, ParaView's
 *    Calculator, Plot Over Line, Ghost Cells Generator; until session 26 these
 *    read freed memory). All or none: when they do not fit the memory limit
 *    together, none is decoded, with one error (the leaves stay empty; this
 *    class's paths hand out images without points), so that no consumer
 *    (a writer, a copy) takes a part of the volume for all of it. The cost:
 *    all partitions decoded (GetHeldPartitionBytes(), the images' own size;
 *    about GetPartitionBytes(), 8 bytes a point with colours): less than a
 *    dense image (only the band's chunks), more than the Core volume.
 *    ParaView's data information visits every partition of every output anyway.
 *    Before anything asked for the partitions, a path that reads the tree
 *    itself sees no partition (call GetNumberOfPartitions() or
 *    DecodePartitions() first).
 *  - released after use (SetReleasePartitionsAfterUse(true), or the
 *    environment variable LVDIF_RELEASE_PARTITIONS=1 for every new object):
 *    the leaves stay empty (16 + 8 bytes a partition; a vtkImageData without
 *    arrays would cost about 8 KiB in VTK 9.2); this object's iterator decodes
 *    the leaf it stands on and releases it at its next step, so ParaView's
 *    data information, the outline and per-partition filters (Contour,
 *    Cutter, Threshold, Clip) hold one decoded partition at a time.
 *    GetPartition(i) and GetDataSet(flat index) decode partition i and hold it
 *    (and set it as its leaf). For such pipelines only: a consumer that keeps
 *    pointers past the step (the filters above, and
 *    vtkXMLPartitionedDataSetWriter, which collects the leaves with GetDataSets)
 *    reads freed memory, and the paths that read the tree itself see empty
 *    leaves (or the partitions asked for by index). Call DecodePartitions()
 *    before such a consumer (it holds them all, within the memory limit).
 * The decoded partitions are shared by the shallow copies of this object
 * (ParaView's post filter copies every output). The iterator visits the empty
 * leaves even when asked to skip empty nodes (they are partitions, only not
 * decoded). After editing the Core volume in place, call VolumeModified()
 * (drops the partitions; the dirty flags stay in the Core volume for
 * vtkChunkedMarchingCubes' incremental update).
 *
 * ShallowCopy shares the Core volume; DeepCopy clones it (lvdif's clone()).
 */
#ifndef vtkSparseDictionaryVolume_h
#define vtkSparseDictionaryVolume_h

#include "lvdifFiltersVolumeModule.h"
#include "vtkPartitionedDataSet.h"
#include "vtkVersionMacros.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace lvdif
{
class DictionaryVolume;
}
class vtkImageData;

class LVDIFFILTERSVOLUME_EXPORT vtkSparseDictionaryVolume : public vtkPartitionedDataSet
{
public:
  static vtkSparseDictionaryVolume* New();
  vtkTypeMacro(vtkSparseDictionaryVolume, vtkPartitionedDataSet);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /// Shares the Core volume (no copy) and drops any built partitions.
  void SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume);
  const std::shared_ptr<lvdif::DictionaryVolume>& GetVolume() const { return this->Volume; }
#endif
  /// True when a Core volume is held.
  bool HasVolume() const { return this->Volume != nullptr; }

  ///@{
  /// Facts about the held volume, for Python and ParaView (0 without a volume).
  void GetDimensions(int dims[3]) const;
  int GetChunkEdge() const;
  double GetBandWidth() const;
  vtkIdType GetNumberOfChunks() const;
  /// Chunks that hold voxels (the others are uniform: one value each).
  vtkIdType GetNumberOfExpandedChunks() const;
  /// Bytes the Core volume holds (chunk table, expanded chunks, dictionaries).
  double GetVolumeMemoryBytes() const;
  /// Bytes a dense float `sdf` + `rgba` image of the whole volume would need.
  double GetDenseImageBytes() const;
  /// Bytes all partitions would need decoded at once (from the chunk states, nothing built).
  double GetPartitionBytes() const;
  ///@}

  /// Chunks written since the Core volume's dirty flags were last taken.
  vtkIdType GetNumberOfDirtyChunks() const;

  ///@{
  /// Give the partitions an `rgba` array too (default on).
  void SetPartitionColors(bool on);
  bool GetPartitionColors() const { return this->PartitionColors; }
  ///@}

  ///@{
  /// The storage chunks this object's partitions come from, as an inclusive
  /// box of chunk coordinates (cx0, cx1, cy0, cy1, cz0, cz1); default: all.
  /// A distributed reader sets its piece's chunks here (its Core volume then
  /// holds those chunks plus the one layer of points their partitions share).
  void SetOwnedChunks(const int box[6]);
  void GetOwnedChunks(int box[6]) const;
  ///@}

  ///@{
  /// Release each decoded partition at the iterator's next step (see the class
  /// comment: for pipelines of per-partition filters only). Default: off, or on
  /// when the environment variable LVDIF_RELEASE_PARTITIONS is 1 at construction.
  void SetReleasePartitionsAfterUse(bool on);
  bool GetReleasePartitionsAfterUse() const { return this->ReleasePartitionsAfterUse; }
  vtkBooleanMacro(ReleasePartitionsAfterUse, bool);
  ///@}
  /// Releases the held decoded partitions now (they are decoded again on demand;
  /// pointers handed out before are no longer valid).
  void ReleaseDecodedPartitions();
  /// Bytes of the decoded partitions held now (shared with this object's shallow
  /// copies): the images' own size (vtkImageData::GetActualMemorySize), the
  /// measure the memory limit is checked on.
  double GetHeldPartitionBytes() const;

  /// Builds the partitions now if they are not built (idempotent); when they
  /// are held (not released after use), also decodes them all: DecodePartitions().
  /// False when that was refused (see DecodePartitions).
  bool UpdatePartitions();
  /// Decodes every partition, holds them and sets them as the tree's leaves,
  /// so that every VTK path sees them (vtkPartitionedDataSet::GetPartition
  /// through a base-class pointer, DeepCopy into a plain vtkPartitionedDataSet,
  /// a consumer's own vtkDataObjectTreeIterator, vtkXMLPartitionedDataSetWriter).
  /// All or none: refused with one error when they do not fit the memory limit
  /// together (LVDIF_MEMORY_LIMIT; checked on their point arrays before
  /// allocating, then on the images' own size), or when one cannot be decoded;
  /// then none of the partitions not held is decoded (not tried again until
  /// ReleaseDecodedPartitions() or the volume changes) and false is returned.
  /// Idempotent (cheap once done). Held mode does it when the partitions are built.
  bool DecodePartitions();
  bool GetPartitionsBuilt() const { return this->PartitionsBuilt; }
  /// Call after editing the Core volume in place: drops the partitions and Modified().
  void VolumeModified();
#ifndef __VTK_WRAP__
  /// The storage chunk of partition `idx`, or -1 (no volume, not built, out of
  /// range); for a corner point's partition -2 - the point's linear index.
  std::int64_t GetPartitionChunk(unsigned int idx) const;
  /// Partition `idx` decoded and held, and set as its leaf if that is empty
  /// (see the class comment); null when it is not a partition of a volume; an
  /// image without points when it could not be decoded: alone over the memory
  /// limit or not decodable (one error for the set, saying which and why), or
  /// not fitting with the partitions held (one error for the set).
  vtkImageData* GetHeldPartition(unsigned int idx);
  /// As above; decode false: only a partition held already (else the image without points).
  vtkImageData* GetHeldPartition(unsigned int idx, bool decode);
#endif

  ///@{
  /// The composite API builds the partitions first (see the class comment).
  unsigned int GetNumberOfPartitions();
  vtkDataSet* GetPartition(unsigned int idx);
  VTK_NEWINSTANCE vtkCompositeDataIterator* NewIterator() override;
  VTK_NEWINSTANCE vtkDataObjectTreeIterator* NewTreeIterator() override;
  void CopyStructure(vtkCompositeDataSet* input) override;
  ///@}

  ///@{
  /// The leaf at an iterator's position: decoded (and held by the iterator)
  /// when the iterator is this object's; by flat index: GetPartition's.
  using Superclass::GetDataSet;
  vtkDataObject* GetDataSet(vtkCompositeDataIterator* iter) override;
#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 2)
  vtkDataObject* GetDataSet(unsigned int flatIndex) override;
#endif
  ///@}

  ///@{
  /// Points and cells of the partitions, from their extents (nothing decoded).
  vtkIdType GetNumberOfPoints() override;
  vtkIdType GetNumberOfCells() override;
  /// POINT and CELL from the partitions' extents (as the two above); other
  /// types as the superclass. ParaView's data information asks for them, and
  /// the superclass's loop would decode every partition once more.
  vtkIdType GetNumberOfElements(int type) override;
  ///@}

  /// Setting a leaf that is not a vtkImageData (a generic filter's result over
  /// the partitions, e.g. vtkContourFilter's, whose composite output the
  /// executive makes with NewInstance + CopyStructure) drops the Core volume:
  /// such an object is a plain partitioned dataset (HasVolume() false). An
  /// image leaf is kept as set (vtkArrayCalculator fills it afterwards), except
  /// when partitions are released after use and it is a shallow copy of a
  /// decoded partition with only its arrays (ParaView's copy of an output):
  /// that leaf stays empty and is decoded on demand.
  void SetDataSet(vtkCompositeDataIterator* iter, vtkDataObject* dataObj) override;

  void Initialize() override;
  void ShallowCopy(vtkDataObject* src) override;
#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 2)
  /// VTK 9.2 (ParaView 5.11): ParaView's post filter copies every output with it.
  void CompositeShallowCopy(vtkCompositeDataSet* src) override;
#endif
  void DeepCopy(vtkDataObject* src) override;
  /// Kibibytes: the Core volume plus the partitions as held (none unless decoded by GetPartition).
  unsigned long GetActualMemorySize() override;

  ///@{
  /// Retrieve an instance of this class from an information object / vector.
  static vtkSparseDictionaryVolume* GetData(vtkInformation* info);
  static vtkSparseDictionaryVolume* GetData(vtkInformationVector* v, int i = 0);
  ///@}

protected:
  vtkSparseDictionaryVolume();
  ~vtkSparseDictionaryVolume() override;

#ifndef __VTK_WRAP__
  /// The one shallow copy (ShallowCopy, CompositeShallowCopy): shares the Core
  /// volume; the leaves are copied by superCopy only when the source built them.
  void ShareFrom(vtkDataObject* src, const std::function<void(vtkDataObject*)>& superCopy);
#endif

  std::shared_ptr<lvdif::DictionaryVolume> Volume;
  bool PartitionColors = true;
  bool PartitionsBuilt = false;
  bool OwnsAll = true;
  int Owned[6] = { 0, -1, 0, -1, 0, -1 };
  bool ReleasePartitionsAfterUse = false;
#ifndef __VTK_WRAP__
  /// The decoded partitions held, by source; shared by the shallow copies.
  struct HeldPartitions;
  std::shared_ptr<HeldPartitions> Held;
  /// Builds the partitions as empty leaves (idempotent).
  bool BuildPartitions();
  /// Sets a decoded partition as leaf `idx` when the leaf is empty (no Modified()).
  void SetDecodedLeaf(unsigned int idx, vtkImageData* image);
  /// Decodes partition `idx` into `held` (whose lock the caller holds); null, reported, when it cannot.
  vtkImageData* DecodeHeld(unsigned int idx, HeldPartitions& held);
  /// Copies the view's state (volume, partitions, colours, owned chunks, held partitions) from `s`.
  void CopyViewFrom(const vtkSparseDictionaryVolume& s);
  /// No volume, no partitions, all chunks owned, a new (empty) set of held partitions.
  void DropView();
#endif
  /// The storage chunk of each partition (built with them).
  std::vector<std::int64_t> PartitionChunks;
  /// Every held partition is set as this object's leaf (DecodePartitions' fast path).
  bool LeavesSet = false;

private:
  vtkSparseDictionaryVolume(const vtkSparseDictionaryVolume&) = delete;
  void operator=(const vtkSparseDictionaryVolume&) = delete;
};

#endif
