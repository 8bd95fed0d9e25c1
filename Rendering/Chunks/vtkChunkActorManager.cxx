#include "vtkChunkActorManager.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkBoundingBox.h"
#include "vtkCornerColorAttributes.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkFieldData.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"

#include <map>
#include <vector>

vtkStandardNewMacro(vtkChunkActorManager);

struct vtkChunkActorManager::Internals
{
  struct Entry
  {
    vtkSmartPointer<vtkActor> Actor;
    vtkSmartPointer<vtkTetrahedralColorMapper> Mapper;
    vtkSmartPointer<vtkPolyData> Source; // the mesh as given
    vtkMTimeType SourceMTime = 0;         // its MTime when it was given
  };
  std::map<vtkIdType, Entry> Chunks;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkNew<vtkProperty> Property;
  bool Visible = true;
};

vtkChunkActorManager::vtkChunkActorManager()
  : Internal(new Internals)
{
  this->Internal->Property->SetInterpolationToGouraud();
}

vtkChunkActorManager::~vtkChunkActorManager()
{
  this->RemoveAllChunks();
}

void vtkChunkActorManager::SetRenderer(vtkRenderer* renderer)
{
  if (this->Internal->Renderer == renderer)
  {
    return;
  }
  for (auto& kv : this->Internal->Chunks)
  {
    if (this->Internal->Renderer)
    {
      this->Internal->Renderer->RemoveActor(kv.second.Actor);
    }
    if (renderer)
    {
      renderer->AddActor(kv.second.Actor);
    }
  }
  this->Internal->Renderer = renderer;
  this->Modified();
}

vtkRenderer* vtkChunkActorManager::GetRenderer()
{
  return this->Internal->Renderer;
}

void vtkChunkActorManager::SetInterpolationMode(int mode)
{
  if (mode == this->InterpolationMode)
  {
    return;
  }
  this->InterpolationMode = mode;
  for (auto& kv : this->Internal->Chunks)
  {
    kv.second.Mapper->SetInterpolationMode(mode);
  }
  this->Modified();
}

vtkProperty* vtkChunkActorManager::GetProperty()
{
  return this->Internal->Property;
}

void vtkChunkActorManager::SetMatcapTexture(vtkTexture* texture)
{
  vtkProperty* p = this->Internal->Property;
  const char* name = vtkTetrahedralColorMapper::MatcapTextureName();
  if (p->GetTexture(name) == texture)
  {
    return;
  }
  if (p->GetTexture(name))
  {
    p->RemoveTexture(name);
  }
  if (texture)
  {
    p->SetTexture(name, texture);
  }
  for (auto& kv : this->Internal->Chunks)
  {
    kv.second.Mapper->SetMatcap(texture != nullptr);
  }
  this->Modified();
}

vtkTexture* vtkChunkActorManager::GetMatcapTexture()
{
  return this->Internal->Property->GetTexture(vtkTetrahedralColorMapper::MatcapTextureName());
}

vtkSmartPointer<vtkPolyData> vtkChunkActorManager::PrepareChunk(vtkPolyData* mesh) const
{
  if (!mesh || mesh->GetNumberOfCells() == 0)
  {
    return nullptr;
  }
  if (!vtkCornerColorAttributes::HasCornerColors(mesh))
  {
    return mesh;
  }
  vtkNew<vtkCornerColorAttributes> attributes;
  attributes->SetOrigin(const_cast<double*>(this->Origin));
  attributes->SetSpacing(const_cast<double*>(this->Spacing));
  attributes->SetInputData(mesh);
  attributes->Update();
  vtkSmartPointer<vtkPolyData> out = attributes->GetOutput();
  return out;
}

void vtkChunkActorManager::SetChunk(vtkIdType chunkId, vtkPolyData* mesh, bool prepared)
{
  vtkSmartPointer<vtkPolyData> ready = prepared ? vtkSmartPointer<vtkPolyData>(mesh) : this->PrepareChunk(mesh);
  if (!ready || ready->GetNumberOfCells() == 0)
  {
    this->RemoveChunk(chunkId);
    return;
  }
  auto& chunks = this->Internal->Chunks;
  auto it = chunks.find(chunkId);
  if (it == chunks.end())
  {
    Internals::Entry e;
    e.Mapper = vtkSmartPointer<vtkTetrahedralColorMapper>::New();
    e.Mapper->SetInterpolationMode(this->InterpolationMode);
    e.Mapper->SetMatcap(this->GetMatcapTexture() != nullptr);
    e.Actor = vtkSmartPointer<vtkActor>::New();
    e.Actor->SetMapper(e.Mapper);
    e.Actor->SetProperty(this->Internal->Property);
    e.Actor->SetVisibility(this->Internal->Visible);
    if (this->Internal->Renderer)
    {
      this->Internal->Renderer->AddActor(e.Actor);
    }
    it = chunks.emplace(chunkId, e).first;
  }
  // Only this mapper sees a new input: only its buffers are rebuilt.
  it->second.Mapper->SetInputData(ready);
  it->second.Source = mesh;
  it->second.SourceMTime = mesh ? mesh->GetMTime() : 0;
  ++this->NumberOfChunkUpdates;
  this->Modified();
}

void vtkChunkActorManager::SetPartitions(vtkPartitionedDataSet* chunks)
{
  std::map<vtkIdType, vtkPolyData*> wanted;
  const unsigned int n = chunks ? chunks->GetNumberOfPartitions() : 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    vtkPolyData* pd = vtkPolyData::SafeDownCast(chunks->GetPartition(i));
    if (!pd)
    {
      continue;
    }
    vtkDataArray* id = pd->GetFieldData()->GetArray("chunk_id");
    wanted[id && id->GetNumberOfTuples() > 0 ? static_cast<vtkIdType>(id->GetTuple1(0)) : i] = pd;
  }
  std::vector<vtkIdType> gone;
  for (auto& kv : this->Internal->Chunks)
  {
    if (!wanted.count(kv.first))
    {
      gone.push_back(kv.first);
    }
  }
  for (vtkIdType id : gone)
  {
    this->RemoveChunk(id);
  }
  for (auto& kv : wanted)
  {
    auto it = this->Internal->Chunks.find(kv.first);
    if (it != this->Internal->Chunks.end() && it->second.Source.Get() == kv.second &&
      kv.second->GetMTime() == it->second.SourceMTime)
    {
      continue; // the same, unmodified mesh object is already shown
    }
    this->SetChunk(kv.first, kv.second);
  }
}

void vtkChunkActorManager::RemoveChunk(vtkIdType chunkId)
{
  auto it = this->Internal->Chunks.find(chunkId);
  if (it == this->Internal->Chunks.end())
  {
    return;
  }
  if (this->Internal->Renderer)
  {
    this->Internal->Renderer->RemoveActor(it->second.Actor);
  }
  this->Internal->Chunks.erase(it);
  this->Modified();
}

void vtkChunkActorManager::RemoveAllChunks()
{
  if (this->Internal->Renderer)
  {
    for (auto& kv : this->Internal->Chunks)
    {
      this->Internal->Renderer->RemoveActor(kv.second.Actor);
    }
  }
  this->Internal->Chunks.clear();
  this->Modified();
}

vtkActor* vtkChunkActorManager::GetChunkActor(vtkIdType chunkId)
{
  auto it = this->Internal->Chunks.find(chunkId);
  return it == this->Internal->Chunks.end() ? nullptr : it->second.Actor.Get();
}

vtkIdType vtkChunkActorManager::GetChunkId(vtkProp* actor)
{
  for (auto& kv : this->Internal->Chunks)
  {
    if (kv.second.Actor.Get() == actor)
    {
      return kv.first;
    }
  }
  return -1;
}

int vtkChunkActorManager::GetNumberOfChunks()
{
  return static_cast<int>(this->Internal->Chunks.size());
}

vtkIdType vtkChunkActorManager::GetNumberOfTriangles()
{
  vtkIdType n = 0;
  for (auto& kv : this->Internal->Chunks)
  {
    n += kv.second.Source ? kv.second.Source->GetNumberOfPolys() : 0;
  }
  return n;
}

void vtkChunkActorManager::GetBounds(double bounds[6])
{
  vtkBoundingBox box;
  for (auto& kv : this->Internal->Chunks)
  {
    box.AddBounds(kv.second.Actor->GetBounds());
  }
  if (!box.IsValid())
  {
    vtkMath::UninitializeBounds(bounds);
    return;
  }
  box.GetBounds(bounds);
}

vtkSmartPointer<vtkPolyData> vtkChunkActorManager::GetMergedMesh()
{
  vtkNew<vtkAppendPolyData> append;
  for (auto& kv : this->Internal->Chunks)
  {
    append->AddInputData(kv.second.Source);
  }
  vtkSmartPointer<vtkPolyData> out = vtkSmartPointer<vtkPolyData>::New();
  if (!this->Internal->Chunks.empty())
  {
    append->Update();
    out->ShallowCopy(append->GetOutput());
  }
  return out;
}

void vtkChunkActorManager::SetVisibility(bool visible)
{
  this->Internal->Visible = visible;
  for (auto& kv : this->Internal->Chunks)
  {
    kv.second.Actor->SetVisibility(visible);
  }
}

void vtkChunkActorManager::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Chunks: " << this->Internal->Chunks.size() << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " " << this->Origin[2] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " " << this->Spacing[2] << "\n";
  os << indent << "InterpolationMode: " << this->InterpolationMode << "\n";
  os << indent << "NumberOfChunkUpdates: " << this->NumberOfChunkUpdates << "\n";
}
