// vtkSparseDictionaryVolume: which partitions there are (the band's chunks and
// the grid's corner points), and decoding, holding and handing them out
// (held by default, or released after use; docs/ARCHITECTURE.md).
#include "vtkSparseDictionaryVolumeInternals.h"

#include "LVDIFVolumeBridge.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"
#include "vtkCompositeDataIterator.h"
#include "vtkDataObjectTreeInternals.h" // vtkDataObjectTreeIndex
#include "vtkDataObjectTreeIterator.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include <algorithm>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>

namespace vtkSparseDictionaryVolumeLayout
{
/// The point box of chunk `id`'s partition: its voxels plus the first layer of
/// its upper neighbours (clipped to the volume).
lvdif::VoxelBox partitionBox(const lvdif::DictionaryVolume& v, std::int64_t id)
{
  lvdif::VoxelBox b = v.chunkBox(id);
  for (int a = 0; a < 3; ++a) b.hi[a] = std::min(b.hi[a] + 1, v.dims()[a] - 1);
  return b;
}

/// True when the partition of chunk `id` has cells whose corners can differ:
/// the chunk or one of the upper neighbours its cells reach holds voxels, or
/// two of them are uniform with different distances. A partition of one point
/// layer along an axis is never needed when the volume has more (the volume's
/// last layer: the partition below holds it); an axis on which the whole
/// volume is one point (a 2-D slice, a 1-D line) is flat in every partition,
/// as in a vtkImageData of the volume, whose cells are then pixels or lines.
bool partitionNeeded(const lvdif::DictionaryVolume& v, std::int64_t id)
{
  const lvdif::VoxelBox b = partitionBox(v, id);
  for (int a = 0; a < 3; ++a)
    if (b.hi[a] <= b.lo[a] && v.dims()[a] > 1) return false;
  const lvdif::Index3 c = v.chunkCoord(id);
  const lvdif::Index3& n = v.chunkCounts();
  bool first = true;
  lvdif::SdfKey key = 0;
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx)
      {
        const lvdif::Index3 q{ c[0] + dx, c[1] + dy, c[2] + dz };
        if (q[0] >= n[0] || q[1] >= n[1] || q[2] >= n[2]) continue;
        const std::int64_t qid = v.chunkId(q[0], q[1], q[2]);
        if (!v.isUniform(qid)) return true;
        const lvdif::SdfKey k = v.uniformValue(qid).sdf;
        if (!first && k != key) return true;
        key = k;
        first = false;
      }
  return false;
}

/// A partition's source: a storage chunk (>= 0), or, for the one-point
/// partitions that give the object the box of its grid (corner points),
/// -2 - the linear index of that grid point.
bool isCorner(std::int64_t source)
{
  return source <= -2;
}

lvdif::Index3 cornerPoint(const lvdif::DictionaryVolume& v, std::int64_t source)
{
  const std::int64_t i = -2 - source;
  const lvdif::Index3& d = v.dims();
  return { i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1]) };
}

std::int64_t cornerSource(const lvdif::DictionaryVolume& v, const lvdif::Index3& p)
{
  const lvdif::Index3& d = v.dims();
  return -2 - (p[0] + d[0] * (p[1] + d[1] * p[2]));
}

/// The point box of a partition's source.
lvdif::VoxelBox sourceBox(const lvdif::DictionaryVolume& v, std::int64_t source)
{
  if (!isCorner(source)) return partitionBox(v, source);
  const lvdif::Index3 p = cornerPoint(v, source);
  lvdif::VoxelBox b;
  b.lo = p;
  b.hi = p;
  return b;
}

/// The storage chunk a partition's points come from (a corner point's own chunk).
std::int64_t sourceChunk(const lvdif::DictionaryVolume& v, std::int64_t source)
{
  if (!isCorner(source)) return source;
  const lvdif::Index3 p = cornerPoint(v, source);
  return v.chunkOf(p[0], p[1], p[2]);
}

/// The partitions' sources: the needed chunks, in chunk order; owned: null for
/// every chunk, else an inclusive box of chunk coordinates. When the chunks'
/// partitions do not reach a corner of the grid (of the owned chunks' points),
/// a partition of that one grid point comes first (lower corner) or last
/// (upper corner), so that the bounds of the object, which VTK's composite
/// consumers (vtkOutlineFilter, vtkCompositeDataSet::GetBounds, ParaView's
/// data information) take from its leaves, are the grid's box, as an image's
/// are, not the narrow band's. A corner point's chunk is never a partition.
std::vector<std::int64_t> neededPartitions(const lvdif::DictionaryVolume& v, const int* owned)
{
  std::vector<std::int64_t> ids;
  const lvdif::Index3& n = v.chunkCounts();
  lvdif::Index3 c0{ 0, 0, 0 }, c1{ n[0] - 1, n[1] - 1, n[2] - 1 };
  if (owned)
  {
    for (int a = 0; a < 3; ++a)
    {
      c0[a] = std::max<std::int64_t>(owned[2 * a], 0);
      c1[a] = std::min<std::int64_t>(owned[2 * a + 1], n[a] - 1);
    }
  }
  if (c1[0] < c0[0] || c1[1] < c0[1] || c1[2] < c0[2]) return ids;
  lvdif::VoxelBox reached;
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
  {
    if (owned)
    {
      const lvdif::Index3 c = v.chunkCoord(id);
      if (c[0] < owned[0] || c[0] > owned[1] || c[1] < owned[2] || c[1] > owned[3] || c[2] < owned[4] ||
        c[2] > owned[5])
        continue;
    }
    if (partitionNeeded(v, id))
    {
      ids.push_back(id);
      reached = reached.unite(partitionBox(v, id));
    }
  }
  const lvdif::Index3 lo = v.chunkBox(v.chunkId(c0[0], c0[1], c0[2])).lo;
  const lvdif::Index3 hi = partitionBox(v, v.chunkId(c1[0], c1[1], c1[2])).hi;
  if (reached.empty() || reached.lo != lo) ids.insert(ids.begin(), cornerSource(v, lo));
  if ((reached.empty() || reached.hi != hi) && hi != lo) ids.push_back(cornerSource(v, hi));
  return ids;
}

std::uint64_t partitionBytes(const lvdif::DictionaryVolume& v, const std::vector<std::int64_t>& ids, bool colors)
{
  std::uint64_t points = 0;
  for (std::int64_t id : ids) points += static_cast<std::uint64_t>(sourceBox(v, id).voxelCount());
  return points * (colors ? 8u : 4u);
}
} // namespace vtkSparseDictionaryVolumeLayout

using namespace vtkSparseDictionaryVolumeLayout;

namespace
{
/// The field data `chunk_id` and `chunk_ijk` of chunk `id`'s partition.
void addChunkFields(const lvdif::DictionaryVolume& v, std::int64_t id, vtkImageData* image)
{
  const lvdif::Index3 c = v.chunkCoord(id);
  vtkNew<vtkIdTypeArray> chunkId;
  chunkId->SetName("chunk_id");
  chunkId->InsertNextValue(static_cast<vtkIdType>(id));
  vtkNew<vtkIntArray> ijk;
  ijk->SetName("chunk_ijk");
  ijk->SetNumberOfComponents(3);
  ijk->InsertNextTuple3(c[0], c[1], c[2]);
  image->GetFieldData()->AddArray(chunkId);
  image->GetFieldData()->AddArray(ijk);
}

/// Chunk `id`'s partition with its decoded point arrays and field data, made
/// by the bridge's one FillImage (which checks the memory guard).
vtkSmartPointer<vtkImageData> fillPartition(const lvdif::DictionaryVolume& v, std::int64_t source, bool colors)
{
  const lvdif::VoxelBox b = sourceBox(v, source);
  const int ext[6] = { static_cast<int>(b.lo[0]), static_cast<int>(b.hi[0]), static_cast<int>(b.lo[1]),
    static_cast<int>(b.hi[1]), static_cast<int>(b.lo[2]), static_cast<int>(b.hi[2]) };
  auto image = vtkSmartPointer<vtkImageData>::New();
  LVDIFVolumeBridge::FillImage(v, ext, image, colors);
  addChunkFields(v, sourceChunk(v, source), image);
  // their ranges too, as FillImage's: else ParaView's data information runs
  // VTK's range passes on them for every partition
  vtkFieldData* fields = image->GetFieldData();
  LVDIFVolumeBridge::StoreRange(vtkIdTypeArray::SafeDownCast(fields->GetArray("chunk_id")));
  LVDIFVolumeBridge::StoreRange(vtkIntArray::SafeDownCast(fields->GetArray("chunk_ijk")));
  return image;
}

/// The iterator of the sparse volume: an empty leaf of a volume is handed out
/// decoded, held by the object (the default) or, when the object releases its
/// partitions after use, by the iterator only while it stands on it (the next
/// step releases it unless the consumer kept a reference). The empty leaves are
/// visited even when the consumer asks to skip empty nodes: they are
/// partitions, only not built.
class vtkSparseDictionaryVolumeIterator : public vtkDataObjectTreeIterator
{
public:
  static vtkSparseDictionaryVolumeIterator* New();
  vtkTypeMacro(vtkSparseDictionaryVolumeIterator, vtkDataObjectTreeIterator);

  void SetSkipEmptyNodes(vtkTypeBool skip) override
  {
    this->WantSkip = skip != 0;
    this->ApplySkip();
  }

  void GoToFirstItem() override
  {
    this->ApplySkip();
    this->Index = 0;
    this->Current = nullptr;
    this->Superclass::GoToFirstItem();
  }

  vtkDataObject* GetCurrentDataObject() override
  {
    return this->Decoded(this->Superclass::GetCurrentDataObject(),
      vtkSparseDictionaryVolume::SafeDownCast(this->GetDataSet()), this->CurrentLeafFlatIndex());
  }

  /// The flat index of the leaf the iterator stands on, in either direction:
  /// VTK refuses GetCurrentFlatIndex in reverse order (an error each call), and
  /// vtkCompositeDataProbeFilter (ParaView's Probe, Plot Over Line) walks the
  /// leaves in reverse. A volume's tree is one level, so the leaf's flat
  /// index is its partition index + 1. 0 when not on a leaf of a volume.
  unsigned int CurrentLeafFlatIndex()
  {
    if (!this->GetReverse()) return this->GetCurrentFlatIndex();
    auto* owner = vtkSparseDictionaryVolume::SafeDownCast(this->GetDataSet());
    if (!owner || !owner->HasVolume() || this->IsDoneWithTraversal()) return 0;
    const vtkDataObjectTreeIndex index = this->GetCurrentIndex();
    return index.size() == 1 ? index[0] + 1 : 0;
  }

  /// `leaf` (at `flatIndex`), decoded when it is an empty leaf of `owner`'s
  /// volume (held by the owner, or by this iterator until the next leaf), else `leaf`.
  vtkDataObject* Decoded(vtkDataObject* leaf, vtkSparseDictionaryVolume* owner, unsigned int flatIndex)
  {
    if (leaf || !owner || !owner->HasVolume() || flatIndex < 1) return leaf;
    if (!owner->GetReleasePartitionsAfterUse())
    {
      // held: NewTreeIterator decoded them all (or none, with one error)
      vtkImageData* held = owner->GetHeldPartition(flatIndex - 1, /*decode=*/false);
      return held ? held : leaf;
    }
    const std::int64_t id = owner->GetPartitionChunk(flatIndex - 1);
    if (id == -1) return leaf;
    if (this->Index != flatIndex)
    {
      this->Index = flatIndex;
      this->Current = nullptr;
      try
      {
        this->Current = fillPartition(*owner->GetVolume(), id, owner->GetPartitionColors());
      }
      catch (const lvdif::Error& e)
      {
        vtkErrorWithObjectMacro(owner, << e.what());
        this->Current = vtkSmartPointer<vtkImageData>::New(); // no points, but not a null leaf (see Undecoded)
      }
    }
    return this->Current;
  }

protected:
  vtkSparseDictionaryVolumeIterator() = default;
  ~vtkSparseDictionaryVolumeIterator() override = default;

private:
  /// A volume's empty leaves are its partitions: never skipped (other objects
  /// of this class, e.g. a generic filter's output, keep the consumer's choice).
  void ApplySkip()
  {
    auto* owner = vtkSparseDictionaryVolume::SafeDownCast(this->GetDataSet());
    this->SkipEmptyNodes = this->WantSkip && !(owner && owner->HasVolume());
  }

  bool WantSkip = true;
  unsigned int Index = 0; // flat index of Current (0: none)
  vtkSmartPointer<vtkImageData> Current;
  vtkSparseDictionaryVolumeIterator(const vtkSparseDictionaryVolumeIterator&) = delete;
  void operator=(const vtkSparseDictionaryVolumeIterator&) = delete;
};
vtkStandardNewMacro(vtkSparseDictionaryVolumeIterator);
}

bool vtkSparseDictionaryVolume::BuildPartitions()
{
  if (this->PartitionsBuilt || !this->Volume) return true;
  // the leaves start empty (16 bytes each): a vtkImageData without arrays would cost about 8 KiB
  this->PartitionChunks = neededPartitions(*this->Volume, this->OwnsAll ? nullptr : this->Owned);
  this->Superclass::SetNumberOfPartitions(0);
  this->Superclass::SetNumberOfPartitions(static_cast<unsigned int>(this->PartitionChunks.size()));
  this->PartitionsBuilt = true;
  this->LeavesSet = false;
  return true;
}

bool vtkSparseDictionaryVolume::UpdatePartitions()
{
  if (!this->Volume) return true;
  this->BuildPartitions();
  // held: the partitions are the tree's leaves, decoded, for every VTK path
  // (released after use: empty leaves, decoded by this object's iterator)
  return this->ReleasePartitionsAfterUse ? true : this->DecodePartitions();
}

std::int64_t vtkSparseDictionaryVolume::GetPartitionChunk(unsigned int idx) const
{
  return this->Volume && this->PartitionsBuilt && idx < this->PartitionChunks.size() ? this->PartitionChunks[idx] : -1;
}

unsigned int vtkSparseDictionaryVolume::GetNumberOfPartitions()
{
  this->UpdatePartitions();
  return this->Superclass::GetNumberOfPartitions();
}

vtkDataSet* vtkSparseDictionaryVolume::GetPartition(unsigned int idx)
{
  this->UpdatePartitions();
  vtkDataSet* leaf = this->Superclass::GetPartition(idx);
  if (leaf || this->GetPartitionChunk(idx) == -1) return leaf;
  // asked by index: held, whatever the mode (the caller gets a pointer it does not own)
  return this->GetHeldPartition(idx, /*decode=*/true);
}

vtkImageData* vtkSparseDictionaryVolume::GetHeldPartition(unsigned int idx)
{
  this->UpdatePartitions();
  return this->GetHeldPartition(idx, /*decode=*/true);
}

void vtkSparseDictionaryVolume::SetDecodedLeaf(unsigned int idx, vtkImageData* image)
{
  // not Modified(): the data are the volume's, unchanged (a pipeline would run again)
  auto& children = this->Internals->Children;
  if (idx < children.size() && !children[idx].DataObject) children[idx].DataObject = image;
}

vtkImageData* vtkSparseDictionaryVolume::GetHeldPartition(unsigned int idx, bool decode)
{
  const std::int64_t source = this->GetPartitionChunk(idx);
  if (source == -1) return nullptr;
  HeldPartitions& held = *this->Held;
  std::lock_guard<std::mutex> lock(held.Lock);
  auto found = held.Images.find(source);
  vtkImageData* image = found != held.Images.end() ? found->second.Get() : nullptr;
  if (!image && decode) image = this->DecodeHeld(idx, held);
  if (!image) return held.Undecoded;
  this->SetDecodedLeaf(idx, image);
  return image;
}

namespace
{
std::uint64_t imageBytes(vtkImageData* image)
{
  return 1024u * static_cast<std::uint64_t>(image->GetActualMemorySize());
}

std::string partitionName(const lvdif::DictionaryVolume& v, unsigned int idx, std::int64_t source)
{
  return "partition " + std::to_string(idx) + " of the sparse volume (" +
    (isCorner(source) ? std::string("a corner point") : "chunk " + std::to_string(source)) + ", " +
    std::to_string(sourceBox(v, source).voxelCount()) + " points)";
}

const char* const ReleaseHint = " Per-partition filters (Contour, Slice, Clip, Threshold) can decode one partition "
                                "at a time: LVDIF_RELEASE_PARTITIONS=1.";
}

vtkImageData* vtkSparseDictionaryVolume::DecodeHeld(unsigned int idx, HeldPartitions& held)
{
  const std::int64_t source = this->PartitionChunks[idx];
  const std::string name = partitionName(*this->Volume, idx, source);
  const std::uint64_t limit = lvdif::memoryLimitBytes();
  const std::uint64_t least = partitionBytes(*this->Volume, { source }, this->PartitionColors);
  vtkSmartPointer<vtkImageData> image;
  try
  {
    // alone over the limit: refused before allocating (its point arrays at least)
    lvdif::requireMemory(least, "decoding " + name + " on its own", limit);
    image = fillPartition(*this->Volume, source, this->PartitionColors);
    lvdif::requireMemory(imageBytes(image), "decoding " + name + " on its own", limit);
  }
  catch (const lvdif::Error& e)
  {
    if (!held.DecodeReported)
    {
      vtkErrorMacro(<< e.what() << ": it is not decoded (an image without points stands for it).");
    }
    held.DecodeReported = true;
    return nullptr;
  }
  const std::uint64_t bytes = imageBytes(image);
  if (held.Bytes + bytes > limit)
  {
    if (!held.LimitReported)
    {
      vtkErrorMacro(<< "holding the sparse volume's decoded partitions: " << name << " needs "
                    << lvdif::formatBytes(bytes) << " with the " << lvdif::formatBytes(held.Bytes) << " held ("
                    << held.Images.size() << " of " << this->PartitionChunks.size()
                    << " partitions), more than the limit of " << lvdif::formatBytes(limit)
                    << " (set LVDIF_MEMORY_LIMIT to change it): a partition that does not fit with the ones held "
                       "is not decoded (an image without points stands for it)."
                    << ReleaseHint);
    }
    held.LimitReported = true;
    return nullptr;
  }
  held.Images.emplace(source, image);
  held.Bytes += bytes;
  return image;
}

bool vtkSparseDictionaryVolume::DecodePartitions()
{
  if (!this->Volume) return true;
  this->BuildPartitions();
  HeldPartitions& held = *this->Held;
  std::lock_guard<std::mutex> lock(held.Lock);
  if (held.AllHeld && this->LeavesSet) return true;
  const lvdif::DictionaryVolume& v = *this->Volume;
  const unsigned int n = static_cast<unsigned int>(this->PartitionChunks.size());
  std::vector<unsigned int> missing;
  std::uint64_t least = 0; // the missing partitions' point arrays: a lower bound of their size
  for (unsigned int i = 0; i < n; ++i)
  {
    auto found = held.Images.find(this->PartitionChunks[i]);
    if (found != held.Images.end())
    {
      this->SetDecodedLeaf(i, found->second);
      continue;
    }
    missing.push_back(i);
    least += partitionBytes(v, { this->PartitionChunks[i] }, this->PartitionColors);
  }
  if (missing.empty())
  {
    held.AllHeld = true;
    this->LeavesSet = true;
    return true;
  }
  if (held.AllRefused) return false;
  // all or none: a consumer (a writer, a copy, a filter that keeps the leaves)
  // never gets a part of the volume as if it were all of it
  const std::uint64_t limit = lvdif::memoryLimitBytes();
  const std::string what = "decoding the sparse volume's " + std::to_string(n) + " partitions to hold them (" +
    std::to_string(n - missing.size()) + " held, " + lvdif::formatBytes(held.Bytes) + ")";
  std::vector<std::int64_t> added;
  std::uint64_t addedBytes = 0;
  bool decodeError = false;
  try
  {
    lvdif::requireMemory(held.Bytes + least, what, limit);
    for (unsigned int i : missing)
    {
      const std::int64_t source = this->PartitionChunks[i];
      least -= partitionBytes(v, { source }, this->PartitionColors);
      vtkSmartPointer<vtkImageData> image;
      try
      {
        image = fillPartition(v, source, this->PartitionColors);
      }
      catch (const lvdif::Error& e)
      {
        decodeError = true;
        throw lvdif::Error(e.code(), partitionName(v, i, source) + " could not be decoded: " + e.what());
      }
      addedBytes += imageBytes(image);
      lvdif::requireMemory(held.Bytes + addedBytes + least, what, limit);
      held.Images.emplace(source, image);
      added.push_back(source);
    }
  }
  catch (const lvdif::Error& e)
  {
    for (std::int64_t source : added) held.Images.erase(source);
    held.AllRefused = true;
    bool& reported = decodeError ? held.DecodeReported : held.LimitReported;
    if (!reported)
    {
      vtkErrorMacro(<< e.what() << ": none of the partitions not held is decoded (images without points stand "
                                   "for them; a writer would write none of them)."
                    << (decodeError ? "" : ReleaseHint));
    }
    reported = true;
    return false;
  }
  held.Bytes += addedBytes;
  for (unsigned int i : missing) this->SetDecodedLeaf(i, held.Images[this->PartitionChunks[i]]);
  held.AllHeld = true;
  this->LeavesSet = true;
  return true;
}

vtkCompositeDataIterator* vtkSparseDictionaryVolume::NewIterator()
{
  return this->NewTreeIterator();
}

vtkDataObjectTreeIterator* vtkSparseDictionaryVolume::NewTreeIterator()
{
  this->UpdatePartitions();
  vtkDataObjectTreeIterator* iter = vtkSparseDictionaryVolumeIterator::New();
  iter->SetDataSet(this);
  return iter;
}

vtkDataObject* vtkSparseDictionaryVolume::GetDataSet(vtkCompositeDataIterator* iter)
{
  // vtk::Range (ParaView's data information) reads the leaves this way, not
  // through GetCurrentDataObject: decode through the iterator
  vtkDataObject* leaf = this->Superclass::GetDataSet(iter);
  auto* ours = vtkSparseDictionaryVolumeIterator::SafeDownCast(iter);
  return ours ? ours->Decoded(leaf, this, ours->CurrentLeafFlatIndex()) : leaf;
}

#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 2)
vtkDataObject* vtkSparseDictionaryVolume::GetDataSet(unsigned int flatIndex)
{
  // the superclass would walk an iterator of its own to the leaf
  this->UpdatePartitions();
  if (this->Volume && flatIndex >= 1 && flatIndex <= this->Superclass::GetNumberOfPartitions())
  {
    return this->GetPartition(flatIndex - 1);
  }
  return this->Superclass::GetDataSet(flatIndex);
}
#endif
