#include "vtkSparseDictionaryVolume.h"

#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolumeInternals.h"

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

vtkStandardNewMacro(vtkSparseDictionaryVolume);

using namespace vtkSparseDictionaryVolumeLayout;


namespace
{
/// LVDIF_RELEASE_PARTITIONS=1 (or on/yes/true): new objects release their partitions after use.
bool releaseAfterUseByDefault()
{
  const char* v = std::getenv("LVDIF_RELEASE_PARTITIONS");
  if (!v) return false;
  const std::string s(v);
  return s == "1" || s == "on" || s == "ON" || s == "yes" || s == "true" || s == "TRUE";
}
}

vtkSparseDictionaryVolume::vtkSparseDictionaryVolume()
  : ReleasePartitionsAfterUse(releaseAfterUseByDefault())
  , Held(std::make_shared<HeldPartitions>())
{
}

vtkSparseDictionaryVolume::~vtkSparseDictionaryVolume() = default;

void vtkSparseDictionaryVolume::SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  this->Superclass::Initialize();
  this->Volume = std::move(volume);
  this->PartitionsBuilt = false;
  this->PartitionChunks.clear();
  this->OwnsAll = true;
  this->Held = std::make_shared<HeldPartitions>();
  this->Modified();
}

void vtkSparseDictionaryVolume::SetOwnedChunks(const int box[6])
{
  this->OwnsAll = false;
  std::copy(box, box + 6, this->Owned);
  this->VolumeModified();
}

void vtkSparseDictionaryVolume::GetOwnedChunks(int box[6]) const
{
  if (!this->OwnsAll)
  {
    std::copy(this->Owned, this->Owned + 6, box);
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = 0;
    box[2 * a + 1] = this->Volume ? static_cast<int>(this->Volume->chunkCounts()[a] - 1) : -1;
  }
}

void vtkSparseDictionaryVolume::VolumeModified()
{
  this->Superclass::SetNumberOfPartitions(0);
  this->PartitionsBuilt = false;
  this->PartitionChunks.clear();
  // a new set: the shallow copies keep the old one (and the pointers they handed out)
  this->Held = std::make_shared<HeldPartitions>();
  this->Modified();
}

void vtkSparseDictionaryVolume::SetReleasePartitionsAfterUse(bool on)
{
  if (on == this->ReleasePartitionsAfterUse) return;
  this->ReleasePartitionsAfterUse = on;
  this->Modified();
}

void vtkSparseDictionaryVolume::ReleaseDecodedPartitions()
{
  HeldPartitions& held = *this->Held;
  std::lock_guard<std::mutex> lock(held.Lock);
  // this object's leaves that are held partitions go too (a shallow copy keeps
  // the ones set as its own leaves until it changes)
  auto& children = this->Internals->Children;
  for (std::size_t i = 0; i < children.size() && i < this->PartitionChunks.size(); ++i)
  {
    auto found = held.Images.find(this->PartitionChunks[i]);
    if (found != held.Images.end() && children[i].DataObject == found->second) children[i].DataObject = nullptr;
  }
  held.Images.clear();
  held.Bytes = 0;
  held.AllHeld = false;
  held.AllRefused = false;
  held.LimitReported = false;
  held.DecodeReported = false;
  this->LeavesSet = false;
}

double vtkSparseDictionaryVolume::GetHeldPartitionBytes() const
{
  std::lock_guard<std::mutex> lock(this->Held->Lock);
  return static_cast<double>(this->Held->Bytes);
}

void vtkSparseDictionaryVolume::SetPartitionColors(bool on)
{
  if (on == this->PartitionColors) return;
  this->PartitionColors = on;
  this->VolumeModified();
}

void vtkSparseDictionaryVolume::GetDimensions(int dims[3]) const
{
  for (int a = 0; a < 3; ++a) dims[a] = this->Volume ? static_cast<int>(this->Volume->dims()[a]) : 0;
}

int vtkSparseDictionaryVolume::GetChunkEdge() const
{
  return this->Volume ? this->Volume->chunkEdge() : 0;
}

double vtkSparseDictionaryVolume::GetBandWidth() const
{
  return this->Volume ? this->Volume->bandWidth() : 0.0;
}

vtkIdType vtkSparseDictionaryVolume::GetNumberOfChunks() const
{
  return this->Volume ? static_cast<vtkIdType>(this->Volume->chunkCount()) : 0;
}

vtkIdType vtkSparseDictionaryVolume::GetNumberOfExpandedChunks() const
{
  return this->Volume ? static_cast<vtkIdType>(this->Volume->expandedChunkCount()) : 0;
}

vtkIdType vtkSparseDictionaryVolume::GetNumberOfDirtyChunks() const
{
  if (!this->Volume) return 0;
  vtkIdType n = 0;
  for (std::int64_t id = 0; id < this->Volume->chunkCount(); ++id) n += this->Volume->isDirty(id) ? 1 : 0;
  return n;
}

double vtkSparseDictionaryVolume::GetVolumeMemoryBytes() const
{
  return this->Volume ? static_cast<double>(this->Volume->memoryBytes()) : 0.0;
}

double vtkSparseDictionaryVolume::GetDenseImageBytes() const
{
  return this->Volume ? 8.0 * static_cast<double>(this->Volume->voxelCount()) : 0.0;
}

double vtkSparseDictionaryVolume::GetPartitionBytes() const
{
  if (!this->Volume) return 0.0;
  return static_cast<double>(partitionBytes(*this->Volume, neededPartitions(*this->Volume, this->OwnsAll ? nullptr : this->Owned), this->PartitionColors));
}


vtkIdType vtkSparseDictionaryVolume::GetNumberOfPoints()
{
  if (!this->Volume) return this->Superclass::GetNumberOfPoints();
  // from the partitions' extents: nothing decoded
  vtkIdType n = 0;
  for (std::int64_t id : neededPartitions(*this->Volume, this->OwnsAll ? nullptr : this->Owned))
    n += static_cast<vtkIdType>(sourceBox(*this->Volume, id).voxelCount());
  return n;
}

vtkIdType vtkSparseDictionaryVolume::GetNumberOfCells()
{
  if (!this->Volume) return this->Superclass::GetNumberOfCells();
  vtkIdType n = 0;
  for (std::int64_t id : neededPartitions(*this->Volume, this->OwnsAll ? nullptr : this->Owned))
  {
    // VTK's rule for an image: the product of (points - 1) over the axes of
    // more than one point (pixels of a flat volume's partitions, lines of a
    // 1-D one), and a one-point image (a corner point) is one vertex cell
    const lvdif::VoxelBox b = sourceBox(*this->Volume, id);
    vtkIdType cells = 1;
    for (int a = 0; a < 3; ++a)
      if (b.hi[a] > b.lo[a]) cells *= static_cast<vtkIdType>(b.hi[a] - b.lo[a]);
    n += cells;
  }
  return n;
}

vtkIdType vtkSparseDictionaryVolume::GetNumberOfElements(int type)
{
  if (this->Volume && type == vtkDataObject::POINT) return this->GetNumberOfPoints();
  if (this->Volume && type == vtkDataObject::CELL) return this->GetNumberOfCells();
  return this->Superclass::GetNumberOfElements(type);
}

void vtkSparseDictionaryVolume::CopyStructure(vtkCompositeDataSet* input)
{
  auto* s = vtkSparseDictionaryVolume::SafeDownCast(input);
  if (s)
  {
    s->UpdatePartitions();
  }
  this->Superclass::CopyStructure(input);
  // ParaView's post filter copies every output as CopyStructure + a shallow
  // copy of each leaf: the copy is still a view of the same Core volume. A
  // generic filter's output made the same way gets other leaves (SetDataSet
  // below drops the volume then).
  if (s)
  {
    this->CopyViewFrom(*s);
    return;
  }
  this->DropView();
}

void vtkSparseDictionaryVolume::DropView()
{
  this->Volume.reset();
  this->PartitionsBuilt = false;
  this->PartitionChunks.clear();
  this->OwnsAll = true;
  this->Held = std::make_shared<HeldPartitions>();
  this->LeavesSet = false;
}

void vtkSparseDictionaryVolume::CopyViewFrom(const vtkSparseDictionaryVolume& s)
{
  this->Volume = s.Volume;
  this->PartitionColors = s.PartitionColors;
  this->PartitionsBuilt = s.PartitionsBuilt;
  this->PartitionChunks = s.PartitionsBuilt ? s.PartitionChunks : std::vector<std::int64_t>();
  this->OwnsAll = s.OwnsAll;
  std::copy(s.Owned, s.Owned + 6, this->Owned);
  this->ReleasePartitionsAfterUse = s.ReleasePartitionsAfterUse;
  this->Held = s.Held;
  this->LeavesSet = false; // its leaves are set from the held ones when asked (UpdatePartitions)
}

void vtkSparseDictionaryVolume::SetDataSet(vtkCompositeDataIterator* iter, vtkDataObject* dataObj)
{
  auto* image = vtkImageData::SafeDownCast(dataObj);
  if (this->Volume && dataObj && !image)
  {
    this->Volume.reset(); // a filter's result over the partitions, not a view of the volume
  }
  if (this->Volume && this->ReleasePartitionsAfterUse && image && image->GetFieldData()->GetArray("chunk_id"))
  {
    // ParaView copies an output leaf by leaf (CopyStructure, then a shallow
    // copy of each leaf our iterator decoded): when partitions are released
    // after use, a leaf that holds only our own arrays stays empty, so the copy
    // decodes on demand as the original does. Not when they are held: a filter
    // that fills its output leaf after setting it (vtkArrayCalculator sets the
    // copy, drops its own reference, then adds the result array) needs the leaf
    // kept, and a shallow copy of a held partition shares its arrays.
    vtkPointData* pd = image->GetPointData();
    bool ours = true;
    for (int a = 0; a < pd->GetNumberOfArrays() && ours; ++a)
    {
      const char* name = pd->GetArrayName(a);
      ours = name && (std::string(name) == "sdf" || std::string(name) == "rgba");
    }
    if (ours && pd->GetNumberOfArrays() > 0)
    {
      auto* id = vtkIdTypeArray::SafeDownCast(image->GetFieldData()->GetArray("chunk_id"));
      int ext[6];
      image->GetExtent(ext);
      const std::int64_t source = this->GetPartitionChunk(iter->GetCurrentFlatIndex() - 1);
      const lvdif::VoxelBox b = source != -1 ? sourceBox(*this->Volume, source) : lvdif::VoxelBox{};
      if (!b.empty() && id && id->GetNumberOfTuples() == 1 && id->GetValue(0) == sourceChunk(*this->Volume, source) &&
        b.lo[0] == ext[0] && b.hi[0] == ext[1] && b.lo[1] == ext[2] && b.hi[1] == ext[3] &&
        b.lo[2] == ext[4] && b.hi[2] == ext[5])
      {
        this->Superclass::SetDataSet(iter, nullptr);
        return;
      }
    }
  }
  this->Superclass::SetDataSet(iter, dataObj);
}

void vtkSparseDictionaryVolume::Initialize()
{
  this->Superclass::Initialize();
  this->DropView();
}

void vtkSparseDictionaryVolume::ShallowCopy(vtkDataObject* src)
{
  this->ShareFrom(src, [this](vtkDataObject* s) { this->Superclass::ShallowCopy(s); });
}

#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 2)
void vtkSparseDictionaryVolume::CompositeShallowCopy(vtkCompositeDataSet* src)
{
  this->ShareFrom(src, [this](vtkDataObject* s) { this->Superclass::CompositeShallowCopy(vtkCompositeDataSet::SafeDownCast(s)); });
}
#endif

void vtkSparseDictionaryVolume::ShareFrom(vtkDataObject* src, const std::function<void(vtkDataObject*)>& superCopy)
{
  if (src == this) return;
  auto* s = vtkSparseDictionaryVolume::SafeDownCast(src);
  if (s && !s->PartitionsBuilt)
  {
    // share the volume without building the source's partitions
    this->Superclass::SetNumberOfPartitions(0);
    this->vtkDataObject::ShallowCopy(src);
  }
  else
  {
    superCopy(src);
  }
  if (s)
  {
    this->CopyViewFrom(*s);
  }
  else
  {
    this->DropView();
  }
  this->Modified();
}

void vtkSparseDictionaryVolume::DeepCopy(vtkDataObject* src)
{
  if (src == this) return;
  auto* s = vtkSparseDictionaryVolume::SafeDownCast(src);
  if (!s)
  {
    this->Superclass::DeepCopy(src);
    this->DropView();
    return;
  }
  this->Superclass::SetNumberOfPartitions(0);
  this->vtkDataObject::DeepCopy(src);
  this->Volume = s->Volume ? std::shared_ptr<lvdif::DictionaryVolume>(s->Volume->clone()) : nullptr;
  this->PartitionColors = s->PartitionColors;
  this->PartitionsBuilt = false;
  this->PartitionChunks.clear();
  this->OwnsAll = s->OwnsAll;
  std::copy(s->Owned, s->Owned + 6, this->Owned);
  this->ReleasePartitionsAfterUse = s->ReleasePartitionsAfterUse;
  this->Held = std::make_shared<HeldPartitions>(); // a copy decodes its own
  this->Modified();
}

unsigned long vtkSparseDictionaryVolume::GetActualMemorySize()
{
  unsigned long kib = this->Volume ? static_cast<unsigned long>(this->Volume->memoryBytes() / 1024) : 0;
  if (!this->Volume)
  {
    return kib + this->Superclass::GetActualMemorySize();
  }
  if (this->PartitionsBuilt)
  {
    // the leaves as set and the decoded partitions held, not through this object's decoding iterator
    kib += this->vtkDataObject::GetActualMemorySize();
    kib += static_cast<unsigned long>(this->GetHeldPartitionBytes() / 1024);
    kib += static_cast<unsigned long>(this->PartitionChunks.capacity() * sizeof(std::int64_t) / 1024);
    // the leaves that are not held partitions (those are counted above), not
    // through this object's decoding iterator
    HeldPartitions& held = *this->Held;
    std::lock_guard<std::mutex> lock(held.Lock);
    const auto& children = this->Internals->Children;
    for (std::size_t i = 0; i < children.size(); ++i)
    {
      vtkDataObject* leaf = children[i].DataObject;
      if (!leaf) continue;
      auto found = i < this->PartitionChunks.size() ? held.Images.find(this->PartitionChunks[i]) : held.Images.end();
      if (found != held.Images.end() && found->second == leaf) continue;
      kib += leaf->GetActualMemorySize();
    }
  }
  return kib;
}

vtkSparseDictionaryVolume* vtkSparseDictionaryVolume::GetData(vtkInformation* info)
{
  return info ? vtkSparseDictionaryVolume::SafeDownCast(info->Get(vtkDataObject::DATA_OBJECT())) : nullptr;
}

vtkSparseDictionaryVolume* vtkSparseDictionaryVolume::GetData(vtkInformationVector* v, int i)
{
  return vtkSparseDictionaryVolume::GetData(v->GetInformationObject(i));
}

void vtkSparseDictionaryVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  // not the superclass's: it would build the partitions to print them
  this->vtkDataObject::PrintSelf(os, indent);
  os << indent << "Volume: ";
  if (this->Volume)
  {
    const auto& d = this->Volume->dims();
    os << d[0] << " x " << d[1] << " x " << d[2] << ", chunk edge " << this->Volume->chunkEdge() << ", "
       << this->Volume->expandedChunkCount() << " of " << this->Volume->chunkCount() << " chunks expanded, "
       << lvdif::formatBytes(this->Volume->memoryBytes()) << "\n";
  }
  else
  {
    os << "(none)\n";
  }
  os << indent << "PartitionColors: " << this->PartitionColors << "\n";
  os << indent << "PartitionsBuilt: " << this->PartitionsBuilt << "\n";
  os << indent << "ReleasePartitionsAfterUse: " << this->ReleasePartitionsAfterUse << "\n";
  os << indent << "HeldPartitionBytes: " << this->GetHeldPartitionBytes() << "\n";
}
