#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include "vtkCompositeDataIterator.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkSparseDictionaryVolume);

namespace
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
/// two of them are uniform with different distances. A partition without a
/// cell along an axis (the volume's last layer) is never needed.
bool partitionNeeded(const lvdif::DictionaryVolume& v, std::int64_t id)
{
  const lvdif::VoxelBox b = partitionBox(v, id);
  for (int a = 0; a < 3; ++a)
    if (b.hi[a] <= b.lo[a]) return false;
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

/// owned: null for every chunk, else an inclusive box of chunk coordinates.
std::vector<std::int64_t> neededPartitions(const lvdif::DictionaryVolume& v, const int* owned)
{
  std::vector<std::int64_t> ids;
  for (std::int64_t id = 0; id < v.chunkCount(); ++id)
  {
    if (owned)
    {
      const lvdif::Index3 c = v.chunkCoord(id);
      if (c[0] < owned[0] || c[0] > owned[1] || c[1] < owned[2] || c[1] > owned[3] || c[2] < owned[4] ||
        c[2] > owned[5])
        continue;
    }
    if (partitionNeeded(v, id)) ids.push_back(id);
  }
  return ids;
}

std::uint64_t partitionBytes(const lvdif::DictionaryVolume& v, const std::vector<std::int64_t>& ids, bool colors)
{
  std::uint64_t points = 0;
  for (std::int64_t id : ids) points += static_cast<std::uint64_t>(partitionBox(v, id).voxelCount());
  return points * (colors ? 8u : 4u);
}
}

vtkSparseDictionaryVolume::vtkSparseDictionaryVolume() = default;
vtkSparseDictionaryVolume::~vtkSparseDictionaryVolume() = default;

void vtkSparseDictionaryVolume::SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  this->Superclass::Initialize();
  this->Volume = std::move(volume);
  this->PartitionsBuilt = false;
  this->OwnsAll = true;
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
  this->Modified();
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

bool vtkSparseDictionaryVolume::UpdatePartitions()
{
  if (this->PartitionsBuilt || !this->Volume) return true;
  const lvdif::DictionaryVolume& v = *this->Volume;
  const std::vector<std::int64_t> ids = neededPartitions(v, this->OwnsAll ? nullptr : this->Owned);
  try
  {
    lvdif::requireMemory(partitionBytes(v, ids, this->PartitionColors),
      "the image partitions of the sparse volume (for generic VTK filters)");
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  const bool colors = this->PartitionColors;
  const auto& o = v.options();
  std::vector<float*> sdfData(ids.size());
  std::vector<unsigned char*> rgbaData(ids.size(), nullptr);
  this->Superclass::SetNumberOfPartitions(static_cast<unsigned int>(ids.size()));
  // VTK objects are made serially; the decoding below runs in parallel.
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    const lvdif::VoxelBox b = partitionBox(v, ids[i]);
    vtkNew<vtkImageData> image;
    image->SetExtent(static_cast<int>(b.lo[0]), static_cast<int>(b.hi[0]), static_cast<int>(b.lo[1]),
      static_cast<int>(b.hi[1]), static_cast<int>(b.lo[2]), static_cast<int>(b.hi[2]));
    image->SetOrigin(o.origin[0], o.origin[1], o.origin[2]);
    image->SetSpacing(o.spacing[0], o.spacing[1], o.spacing[2]);
    vtkNew<vtkFloatArray> sdf;
    sdf->SetName("sdf");
    sdf->SetNumberOfTuples(static_cast<vtkIdType>(b.voxelCount()));
    sdfData[i] = sdf->GetPointer(0);
    image->GetPointData()->SetScalars(sdf);
    if (colors)
    {
      vtkNew<vtkUnsignedCharArray> rgba;
      rgba->SetName("rgba");
      rgba->SetNumberOfComponents(4);
      rgba->SetNumberOfTuples(static_cast<vtkIdType>(b.voxelCount()));
      rgbaData[i] = rgba->GetPointer(0);
      image->GetPointData()->AddArray(rgba);
    }
    const lvdif::Index3 c = v.chunkCoord(ids[i]);
    vtkNew<vtkIdTypeArray> chunkId;
    chunkId->SetName("chunk_id");
    chunkId->InsertNextValue(static_cast<vtkIdType>(ids[i]));
    vtkNew<vtkIntArray> ijk;
    ijk->SetName("chunk_ijk");
    ijk->SetNumberOfComponents(3);
    ijk->InsertNextTuple3(c[0], c[1], c[2]);
    image->GetFieldData()->AddArray(chunkId);
    image->GetFieldData()->AddArray(ijk);
    this->Superclass::SetPartition(static_cast<unsigned int>(i), image);
  }
  const lvdif::ColorDictionary& palette = v.colors();
  const std::int64_t count = static_cast<std::int64_t>(ids.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t i = 0; i < count; ++i)
  {
    const lvdif::VoxelBox b = partitionBox(v, ids[i]);
    float* s = sdfData[i];
    unsigned char* c = rgbaData[i];
    std::int64_t p = 0;
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x, ++p)
        {
          const lvdif::Voxel vox = v.get(x, y, z);
          s[p] = v.decode(vox.sdf);
          if (c)
          {
            const lvdif::Rgba col = vox.color < palette.size() ? palette[vox.color] : palette[0];
            c[4 * p + 0] = col.r;
            c[4 * p + 1] = col.g;
            c[4 * p + 2] = col.b;
            c[4 * p + 3] = col.a;
          }
        }
  }
  this->PartitionsBuilt = true;
  return true;
}

unsigned int vtkSparseDictionaryVolume::GetNumberOfPartitions()
{
  this->UpdatePartitions();
  return this->Superclass::GetNumberOfPartitions();
}

vtkDataSet* vtkSparseDictionaryVolume::GetPartition(unsigned int idx)
{
  this->UpdatePartitions();
  return this->Superclass::GetPartition(idx);
}

vtkCompositeDataIterator* vtkSparseDictionaryVolume::NewIterator()
{
  this->UpdatePartitions();
  return this->Superclass::NewIterator();
}

vtkDataObjectTreeIterator* vtkSparseDictionaryVolume::NewTreeIterator()
{
  this->UpdatePartitions();
  return this->Superclass::NewTreeIterator();
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
  this->Volume = s ? s->Volume : nullptr;
  this->PartitionsBuilt = s != nullptr && s->PartitionsBuilt;
  this->OwnsAll = s ? s->OwnsAll : true;
  if (s)
  {
    this->PartitionColors = s->PartitionColors;
    std::copy(s->Owned, s->Owned + 6, this->Owned);
  }
}

void vtkSparseDictionaryVolume::SetDataSet(vtkCompositeDataIterator* iter, vtkDataObject* dataObj)
{
  if (this->Volume && dataObj && !vtkImageData::SafeDownCast(dataObj))
  {
    this->Volume.reset(); // a filter's result over the partitions, not a view of the volume
  }
  this->Superclass::SetDataSet(iter, dataObj);
}

void vtkSparseDictionaryVolume::Initialize()
{
  this->Superclass::Initialize();
  this->Volume.reset();
  this->PartitionsBuilt = false;
  this->OwnsAll = true;
}

void vtkSparseDictionaryVolume::ShallowCopy(vtkDataObject* src)
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
    this->Superclass::ShallowCopy(src);
  }
  this->Volume = s ? s->Volume : nullptr;
  this->PartitionColors = s ? s->PartitionColors : this->PartitionColors;
  this->PartitionsBuilt = s ? s->PartitionsBuilt : false;
  this->OwnsAll = s ? s->OwnsAll : true;
  if (s) std::copy(s->Owned, s->Owned + 6, this->Owned);
  this->Modified();
}

#if VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 2)
void vtkSparseDictionaryVolume::CompositeShallowCopy(vtkCompositeDataSet* src)
{
  if (src == this) return;
  auto* s = vtkSparseDictionaryVolume::SafeDownCast(src);
  if (s && !s->PartitionsBuilt)
  {
    this->Superclass::SetNumberOfPartitions(0);
    this->vtkDataObject::ShallowCopy(src);
  }
  else
  {
    this->Superclass::CompositeShallowCopy(src);
  }
  this->Volume = s ? s->Volume : nullptr;
  this->PartitionColors = s ? s->PartitionColors : this->PartitionColors;
  this->PartitionsBuilt = s ? s->PartitionsBuilt : false;
  this->OwnsAll = s ? s->OwnsAll : true;
  if (s) std::copy(s->Owned, s->Owned + 6, this->Owned);
  this->Modified();
}
#endif

void vtkSparseDictionaryVolume::DeepCopy(vtkDataObject* src)
{
  if (src == this) return;
  auto* s = vtkSparseDictionaryVolume::SafeDownCast(src);
  if (!s)
  {
    this->Superclass::DeepCopy(src);
    this->Volume.reset();
    this->PartitionsBuilt = false;
    return;
  }
  this->Superclass::SetNumberOfPartitions(0);
  this->vtkDataObject::DeepCopy(src);
  this->Volume = s->Volume ? std::shared_ptr<lvdif::DictionaryVolume>(s->Volume->clone()) : nullptr;
  this->PartitionColors = s->PartitionColors;
  this->PartitionsBuilt = false;
  this->OwnsAll = s->OwnsAll;
  std::copy(s->Owned, s->Owned + 6, this->Owned);
  this->Modified();
}

unsigned long vtkSparseDictionaryVolume::GetActualMemorySize()
{
  unsigned long kib = this->Volume ? static_cast<unsigned long>(this->Volume->memoryBytes() / 1024) : 0;
  if (this->PartitionsBuilt || !this->Volume)
  {
    kib += this->Superclass::GetActualMemorySize();
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
}
