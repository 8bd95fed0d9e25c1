#include "vtkChunkActorManager.h"

#include "lvdifTriangleChanges.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkBoundingBox.h"
#include "vtkCallbackCommand.h"
#include "vtkCornerColorAttributes.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkPartitionedDataSet.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkPoints.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTetrahedralColorMapper.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <unordered_set>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkChunkActorManager);

using lvdif::render::changedBoundsOf;
using lvdif::render::sameMesh;
using lvdif::render::sortedWithIndex;
using lvdif::render::triangleHashes;
using lvdif::render::unionBounds;

// A mesh's triangle hashes (triangleHashes), sorted, each with its triangle's index.
struct vtkChunkActorManager::Hashes
{
  lvdif::render::SortedTriangleHashes sorted;
};

// The triangles by which a new mesh differs from a chunk's current one.
struct vtkChunkActorManager::Change
{
  bool Known = false;
  double Bounds[6];
  std::vector<double> Points; // x, y, z of each changed triangle's points
};

struct vtkChunkActorManager::Internals
{
  struct Entry
  {
    vtkSmartPointer<vtkActor> Actor;
    vtkSmartPointer<vtkTetrahedralColorMapper> Mapper;
    vtkSmartPointer<vtkPolyData> Source; // the mesh as given
    vtkMTimeType SourceMTime = 0;         // its MTime when it was given
    double PreparedOrigin[3] = { 0, 0, 0 }; // the geometry it was prepared with
    double PreparedSpacing[3] = { 1, 1, 1 };
    Hashes SourceHashes; // of Source, for the next ChangedBounds
    bool HashesValid = false;
    bool OwnsInput = false; // the mapper's input was made here (PrepareChunk): it may be refilled
  };
  std::map<vtkIdType, Entry> Chunks;
  vtkSmartPointer<vtkRenderer> Renderer;
  vtkNew<vtkProperty> Property;
  bool Visible = true;
  vtkSmartPointer<vtkPartialRedrawCuller> Culler;
  vtkTimeStamp FrameStart;        // the renderer's last StartEvent
  unsigned long StartObserver = 0; // on Renderer
};

namespace
{
// Same arrays (names, types, components, attribute roles) in the same order.
bool sameArrays(vtkDataSetAttributes* a, vtkDataSetAttributes* b)
{
  if (a->GetNumberOfArrays() != b->GetNumberOfArrays())
  {
    return false;
  }
  for (int i = 0; i < a->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* x = a->GetAbstractArray(i);
    vtkAbstractArray* y = b->GetAbstractArray(i);
    const char* nx = x->GetName();
    const char* ny = y->GetName();
    if (x->GetDataType() != y->GetDataType() || x->GetNumberOfComponents() != y->GetNumberOfComponents() ||
      (nx == nullptr) != (ny == nullptr) || (nx && std::strcmp(nx, ny) != 0))
    {
      return false;
    }
  }
  int ia[vtkDataSetAttributes::NUM_ATTRIBUTES], ib[vtkDataSetAttributes::NUM_ATTRIBUTES];
  a->GetAttributeIndices(ia);
  b->GetAttributeIndices(ib);
  return std::equal(ia, ia + vtkDataSetAttributes::NUM_ATTRIBUTES, ib);
}

// Refills `shown` with `next` when they hold the same arrays: every array
// object stays, so the render window's vertex buffer cache (keyed by array)
// re-uploads the chunk's buffers in place instead of freeing and creating
// them, which in VTK searches the whole cache per freed buffer (thousands
// of entries with hundreds of chunks). False if the layouts differ.
bool refill(vtkPolyData* shown, vtkPolyData* next)
{
  vtkPoints* ps = shown->GetPoints();
  vtkPoints* pn = next->GetPoints();
  if (!ps || !pn || ps->GetDataType() != pn->GetDataType() || !sameArrays(shown->GetPointData(), next->GetPointData()) ||
    !sameArrays(shown->GetCellData(), next->GetCellData()) || next->GetFieldData()->GetNumberOfArrays() ||
    shown->GetFieldData()->GetNumberOfArrays())
  {
    return false;
  }
  // (the new arrays' buffers are shared, not copied: `next` is dropped after;
  // copying does not mark an array modified, and the buffer upload and the
  // cached ranges go by the array's MTime)
  ps->GetData()->ShallowCopy(pn->GetData());
  ps->Modified(); // the points and their array
  // the ranges cached with the new coordinates (PrepareChunk), set after the
  // modification so that they count as current; the old ones cleared first
  // (an entry left over would count as current too)
  ps->GetData()->GetInformation()->Clear();
  ps->GetData()->GetInformation()->Copy(pn->GetData()->GetInformation(), 1);
  for (vtkDataSetAttributes* d : { static_cast<vtkDataSetAttributes*>(shown->GetPointData()),
         static_cast<vtkDataSetAttributes*>(shown->GetCellData()) })
  {
    vtkDataSetAttributes* from = d == shown->GetPointData() ? static_cast<vtkDataSetAttributes*>(next->GetPointData())
                                                             : static_cast<vtkDataSetAttributes*>(next->GetCellData());
    for (int i = 0; i < d->GetNumberOfArrays(); ++i)
    {
      vtkAbstractArray* to = d->GetAbstractArray(i);
      vtkDataArray* toData = vtkDataArray::SafeDownCast(to);
      vtkDataArray* fromData = vtkDataArray::SafeDownCast(from->GetAbstractArray(i));
      if (toData && fromData)
      {
        toData->ShallowCopy(fromData);
      }
      else
      {
        to->DeepCopy(from->GetAbstractArray(i));
      }
      to->Modified();
    }
    d->Modified();
  }
  shown->SetVerts(next->GetVerts());
  shown->SetLines(next->GetLines());
  shown->SetPolys(next->GetPolys());
  shown->SetStrips(next->GetStrips());
  shown->Modified();
  return true;
}
} // namespace

bool vtkChunkActorManager::ChangedBounds(vtkPolyData* before, vtkPolyData* after, double bounds[6])
{
  std::vector<std::uint64_t> hb, ha;
  if (!triangleHashes(before, hb) || !triangleHashes(after, ha))
  {
    return unionBounds(before, after, bounds);
  }
  return changedBoundsOf(before, sortedWithIndex(hb), after, sortedWithIndex(ha), bounds);
}

void vtkChunkActorManager::SetRedrawCuller(vtkPartialRedrawCuller* culler)
{
  vtkPartialRedrawCuller* old = this->Internal->Culler;
  if (old == culler)
  {
    return;
  }
  // Every change of a chunk actor's input goes through ApplyChunk, which
  // announces it: the culler need not read the inputs' MTimes each frame.
  for (auto& kv : this->Internal->Chunks)
  {
    if (old)
    {
      old->SetInputChangesAnnounced(kv.second.Actor, false);
    }
    if (culler)
    {
      culler->SetInputChangesAnnounced(kv.second.Actor, true);
    }
  }
  this->Internal->Culler = culler;
}

vtkChunkActorManager::vtkChunkActorManager()
  : Internal(new Internals)
{
  this->Internal->Property->SetInterpolationToGouraud();
}

vtkChunkActorManager::~vtkChunkActorManager()
{
  this->RemoveAllChunks();
  if (this->Internal->Renderer && this->Internal->StartObserver)
  {
    this->Internal->Renderer->RemoveObserver(this->Internal->StartObserver);
  }
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
  if (this->Internal->Renderer && this->Internal->StartObserver)
  {
    this->Internal->Renderer->RemoveObserver(this->Internal->StartObserver);
    this->Internal->StartObserver = 0;
  }
  this->Internal->Renderer = renderer;
  if (renderer)
  {
    vtkNew<vtkCallbackCommand> cb;
    cb->SetClientData(this->Internal.get());
    cb->SetCallback(
      [](vtkObject*, unsigned long, void* cd, void*) { static_cast<Internals*>(cd)->FrameStart.Modified(); });
    this->Internal->StartObserver = renderer->AddObserver(vtkCommand::StartEvent, cb);
  }
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
  attributes->SpatialOrderOn(); // consecutive triangles together: the mapper's draw ranges
  attributes->SetInputData(mesh);
  attributes->Update();
  vtkSmartPointer<vtkPolyData> out = attributes->GetOutput();
  // The buffer upload asks for the coordinates' ranges (VTK's automatic shift
  // and scale of the vertex buffer); the array caches them, so they are
  // computed here (by the filter itself for marching cubes' meshes), where the
  // chunks are prepared in parallel, not in the render (refill carries them
  // over). They are also the cells' bounds, which ApplyChunk hands to the
  // mapper.
  vtkDataArray* xyz = out->GetPoints()->GetData();
  for (int c = 0; c < xyz->GetNumberOfComponents(); ++c)
  {
    double range[2];
    xyz->GetRange(range, c);
  }
  return out;
}

bool vtkChunkActorManager::ShowsEqualMesh(vtkIdType chunkId, vtkPolyData* mesh)
{
  // A re-meshed chunk often comes back the same (an edit that rewrote voxels
  // away from the surface, or recoloured the inside): its preparation, buffer
  // upload and redraw would change no pixel.
  auto it = this->Internal->Chunks.find(chunkId);
  if (it == this->Internal->Chunks.end() || !mesh || mesh->GetNumberOfCells() == 0)
  {
    return false;
  }
  const Internals::Entry& e = it->second;
  // the shown mesh as it was given (a caller may have changed its object since)
  // and prepared with today's geometry
  return e.Source && e.Source.Get() != mesh && e.Source->GetMTime() == e.SourceMTime &&
    std::equal(this->Origin, this->Origin + 3, e.PreparedOrigin) &&
    std::equal(this->Spacing, this->Spacing + 3, e.PreparedSpacing) && sameMesh(e.Source, mesh);
}

void vtkChunkActorManager::SetChunk(vtkIdType chunkId, vtkPolyData* mesh, bool prepared)
{
  if (this->ShowsEqualMesh(chunkId, mesh))
  {
    ++this->NumberOfUnchangedMeshes;
    return;
  }
  vtkSmartPointer<vtkPolyData> ready = prepared ? vtkSmartPointer<vtkPolyData>(mesh) : this->PrepareChunk(mesh);
  Hashes hashes; // only with a culler to declare changes to
  vtkPartialRedrawCuller* culler = this->Internal->Culler;
  const bool hashed = culler && culler->GetEnabled() && hashesOf(mesh, hashes);
  this->ApplyChunk(chunkId, mesh, ready, !prepared && ready.Get() != mesh, hashed ? &hashes : nullptr);
}

void vtkChunkActorManager::SetChunks(const std::vector<vtkIdType>& chunkIds, const std::vector<vtkPolyData*>& meshes)
{
  const std::size_t n = std::min(chunkIds.size(), meshes.size());
  std::vector<vtkSmartPointer<vtkPolyData>> ready(n);
  std::vector<Hashes> hashes(n);
  std::vector<char> hashed(n, 0);
  std::vector<Change> changes(n);
  vtkPartialRedrawCuller* culler = this->Internal->Culler;
  const bool declare = culler && culler->GetEnabled();
  // Each mesh object is read by one thread only: a chunk is compared with its
  // current mesh in the parallel part (ApplyChunk then only declares the
  // result) when it is named once in this call and its current mesh is no
  // other chunk's and none of this call's; otherwise in ApplyChunk, in order.
  // A mesh given twice is prepared on this thread.
  const auto& chunks = this->Internal->Chunks;
  std::map<vtkIdType, int> named;
  for (std::size_t i = 0; i < n; ++i)
  {
    ++named[chunkIds[i]];
  }
  // a chunk named once whose mesh equals its shown one stays as it is
  std::vector<char> unchanged(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    unchanged[i] = named[chunkIds[i]] == 1 && this->ShowsEqualMesh(chunkIds[i], meshes[i]);
  }
  std::map<vtkPolyData*, int> reads; // per mesh object: the threads' readers
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!unchanged[i])
    {
      ++reads[meshes[i]];
    }
  }
  bool distinct = true;
  for (const auto& kv : reads)
  {
    distinct = distinct && (kv.first == nullptr || kv.second == 1);
  }
  std::vector<vtkPolyData*> before(n, nullptr);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (unchanged[i])
    {
      continue;
    }
    auto it = chunks.find(chunkIds[i]);
    if (named[chunkIds[i]] == 1 && it != chunks.end() && it->second.Source && it->second.HashesValid)
    {
      before[i] = it->second.Source;
      ++reads[before[i]];
    }
  }
  // the per-triangle work of each chunk (preparation, hashes, the changed
  // triangles) in parallel, reading the chunk table's meshes (nothing writes
  // them meanwhile: this thread waits in For); the actors, mappers and the
  // culler on this thread
  auto prepare = [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      if (unchanged[i])
      {
        continue;
      }
      ready[i] = this->PrepareChunk(meshes[i]);
      hashed[i] = declare && hashesOf(meshes[i], hashes[i]);
      if (hashed[i] && before[i] && reads.at(before[i]) == 1)
      {
        const Internals::Entry& e = chunks.at(chunkIds[i]);
        changedBoundsOf(before[i], e.SourceHashes.sorted, meshes[i], hashes[i].sorted, changes[i].Bounds,
          &changes[i].Points);
        changes[i].Known = true;
      }
    }
  };
  if (distinct)
  {
    vtkSMPTools::For(0, static_cast<vtkIdType>(n), prepare);
  }
  else
  {
    prepare(0, static_cast<vtkIdType>(n));
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (unchanged[i])
    {
      ++this->NumberOfUnchangedMeshes;
      continue;
    }
    this->ApplyChunk(chunkIds[i], meshes[i], ready[i], ready[i].Get() != meshes[i], hashed[i] ? &hashes[i] : nullptr,
      &changes[i]);
  }
}

bool vtkChunkActorManager::hashesOf(vtkPolyData* mesh, Hashes& out)
{
  std::vector<std::uint64_t> order;
  if (!triangleHashes(mesh, order))
  {
    return false;
  }
  out.sorted = sortedWithIndex(order);
  return true;
}

void vtkChunkActorManager::ApplyChunk(
  vtkIdType chunkId, vtkPolyData* mesh, vtkPolyData* ready, bool owned, Hashes* hashes, const Change* change)
{
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
    e.Mapper->SetDrawRangeTriangles(this->DrawRangeTriangles);
    // The input is set as data, never produced by a pipeline: no pipeline
    // update per render and per bounds query (with hundreds of chunk actors
    // those updates were most of the cost of a frame that draws little).
    e.Mapper->StaticOn();
    e.Actor = vtkSmartPointer<vtkActor>::New();
    e.Actor->SetMapper(e.Mapper);
    e.Actor->SetProperty(this->Internal->Property);
    e.Actor->SetVisibility(this->Internal->Visible);
    if (this->Internal->Renderer)
    {
      this->Internal->Renderer->AddActor(e.Actor);
    }
    if (this->Internal->Culler)
    {
      this->Internal->Culler->SetInputChangesAnnounced(e.Actor, true);
    }
    it = chunks.emplace(chunkId, e).first;
  }
  // Only this mapper sees a new input: only its buffers are rebuilt.
  Internals::Entry& e = it->second;
  vtkPartialRedrawCuller* culler = this->Internal->Culler;
  const bool declare = culler && culler->GetEnabled() && e.Source && mesh && e.Actor->GetIsIdentity() &&
    std::equal(this->Origin, this->Origin + 3, e.PreparedOrigin) &&
    std::equal(this->Spacing, this->Spacing + 3, e.PreparedSpacing);
  if (declare)
  {
    culler->BeginChange(e.Actor);
  }
  // A mesh prepared here (a new object) may be refilled into the previous one
  // (made here too, so nobody else holds it); a caller's object is shown as given.
  vtkPolyData* shown = vtkPolyData::SafeDownCast(e.Mapper->GetInputDataObject(0, 0));
  if (!(owned && e.OwnsInput && shown && refill(shown, ready)))
  {
    e.Mapper->SetInputData(ready);
    e.OwnsInput = owned;
  }
  if (culler)
  {
    culler->InputDataChanged(e.Actor); // refilled in place, or a new input: announced
  }
  if (owned)
  {
    // Made by PrepareChunk: every point is a corner of one triangle (the
    // points are un-shared), so the cells' bounds are the coordinates' ranges,
    // cached there; refilled or not, the mapper's input holds the same cells.
    vtkDataArray* xyz = ready->GetPoints()->GetData();
    double bounds[6];
    for (int a = 0; a < 3; ++a)
    {
      xyz->GetRange(bounds + 2 * a, a);
    }
    e.Mapper->SetInputBounds(bounds);
  }
  const bool hashed = hashes != nullptr;
  if (declare)
  {
    // Preparation is per triangle (vtkCornerColorAttributes), so the prepared
    // meshes differ only where the given ones do. The previous mesh's hashes
    // were kept when it was given.
    // The changed triangles' points, when known: the culler bounds their
    // projections, which is tighter than the projection of their box.
    double changed[6];
    vtkPolyData* before = e.Source;
    if (change && change->Known)
    {
      culler->EndChange(e.Actor, change->Bounds, change->Points.data(),
        static_cast<vtkIdType>(change->Points.size() / 3));
    }
    else if (hashed && e.HashesValid)
    {
      std::vector<double> points;
      changedBoundsOf(before, e.SourceHashes.sorted, mesh, hashes->sorted, changed, &points);
      culler->EndChange(e.Actor, changed, points.data(), static_cast<vtkIdType>(points.size() / 3));
    }
    else
    {
      ChangedBounds(before, mesh, changed);
      culler->EndChange(e.Actor, changed);
    }
  }
  std::copy(this->Origin, this->Origin + 3, e.PreparedOrigin);
  std::copy(this->Spacing, this->Spacing + 3, e.PreparedSpacing);
  e.Source = mesh;
  e.SourceMTime = mesh ? mesh->GetMTime() : 0;
  if (hashed)
  {
    std::swap(e.SourceHashes, *hashes);
  }
  e.HashesValid = hashed;
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
  if (this->Internal->Culler)
  {
    this->Internal->Culler->SetInputChangesAnnounced(it->second.Actor, false);
  }
  this->Internal->Chunks.erase(it);
  this->Modified();
}

void vtkChunkActorManager::RemoveAllChunks()
{
  if (vtkRenderer* ren = this->Internal->Renderer)
  {
    // vtkRenderer::RemoveActor finds the actor by a scan of the renderer's
    // props (and actors) from the first: removed in chunk id order, which is
    // not the order they were added in, n chunks cost up to n^2 / 2 steps.
    // In the order of that list each is found among the first few.
    std::unordered_set<vtkProp*> ours;
    ours.reserve(this->Internal->Chunks.size());
    for (auto& kv : this->Internal->Chunks)
    {
      ours.insert(kv.second.Actor.Get());
    }
    std::vector<vtkProp*> inOrder;
    inOrder.reserve(ours.size());
    vtkPropCollection* props = ren->GetViewProps();
    vtkCollectionSimpleIterator it;
    props->InitTraversal(it);
    while (vtkProp* p = props->GetNextProp(it))
    {
      if (ours.count(p))
      {
        inOrder.push_back(p);
      }
    }
    for (vtkProp* p : inOrder)
    {
      ren->RemoveActor(p); // the manager's Entry keeps it alive until the clear below
    }
  }
  for (auto& kv : this->Internal->Chunks)
  {
    if (this->Internal->Culler)
    {
      this->Internal->Culler->SetInputChangesAnnounced(kv.second.Actor, false);
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

void vtkChunkActorManager::SetDrawRangeTriangles(int triangles)
{
  this->DrawRangeTriangles = std::max(0, triangles);
  for (auto& kv : this->Internal->Chunks)
  {
    kv.second.Mapper->SetDrawRangeTriangles(this->DrawRangeTriangles);
  }
}

vtkIdType vtkChunkActorManager::GetLastNumberOfTrianglesDrawn(int* drawCalls)
{
  vtkIdType n = 0;
  int calls = 0;
  vtkRenderer* ren = this->Internal->Renderer;
  for (auto& kv : this->Internal->Chunks)
  {
    vtkTetrahedralColorMapper* m = kv.second.Mapper;
    // drawn in the renderer's last frame: since its start
    if (ren && kv.second.Actor->GetVisibility() && m->GetLastDrawTime() > this->Internal->FrameStart.GetMTime())
    {
      n += m->GetLastNumberOfTrianglesDrawn();
      calls += m->GetLastNumberOfDrawCalls();
    }
  }
  if (drawCalls)
  {
    *drawCalls = calls;
  }
  return n;
}

void vtkChunkActorManager::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Chunks: " << this->Internal->Chunks.size() << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " " << this->Origin[2] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " " << this->Spacing[2] << "\n";
  os << indent << "InterpolationMode: " << this->InterpolationMode << "\n";
  os << indent << "NumberOfChunkUpdates: " << this->NumberOfChunkUpdates << "\n";
  os << indent << "NumberOfUnchangedMeshes: " << this->NumberOfUnchangedMeshes << "\n";
}
