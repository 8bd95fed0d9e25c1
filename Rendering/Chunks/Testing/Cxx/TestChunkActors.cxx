// Non-rendering checks of the chunk actor manager: its bookkeeping (only the
// replaced chunk's mapper gets a new input, SetChunks as SetChunk one by one,
// refilled arrays and bounds), and the changed-triangle bounds against a
// brute-force triangle comparison. vtkCornerColorAttributes' checks are in
// TestCornerColorAttributes.
#include "ChunkTestData.h"

#include "vtkActor.h"
#include "vtkBoundingBox.h"
#include "vtkCellData.h"
#include "vtkPointData.h"
#include "vtkChunkActorManager.h"
#include "vtkIdList.h"
#include "vtkMapper.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace lvdiftest;

namespace
{
/// The mesh a manager's chunk actor shows (its mapper's input).
vtkPolyData* shownMesh(vtkChunkActorManager* mgr, vtkIdType id)
{
  return vtkPolyData::SafeDownCast(mgr->GetChunkActor(id)->GetMapper()->GetInputDataObject(0, 0));
}

/// Two managers, each with its own renderer and enabled culler: one given
/// chunks one by one (SetChunk), the other the same chunks in one SetChunks.
struct TwinManagers
{
  TwinManagers()
  {
    for (int i = 0; i < 2; ++i)
    {
      vtkChunkActorManager* m = i == 0 ? one.Get() : many.Get();
      m->SetRenderer(renderers[i]);
      cullers[i]->SetEnabled(true);
      m->SetRedrawCuller(cullers[i]);
    }
  }
  vtkNew<vtkChunkActorManager> one, many;

private:
  vtkNew<vtkRenderer> renderers[2];
  vtkNew<vtkPartialRedrawCuller> cullers[2];
};

/// A manager showing the chunks of one sphere, and the chunks of a larger
/// sphere that replace those it shares with it, ready for one SetChunks call
/// (ids, meshes).
struct RefillScene
{
  RefillScene()
  {
    for (auto& kv : first)
    {
      mgr->SetChunk(kv.first, kv.second);
      if (second.count(kv.first))
      {
        ids.push_back(kv.first);
        meshes.push_back(second[kv.first]);
      }
    }
  }
  std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> first = splitChunks(sphereMesh(40), 16, 39);
  std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> second = splitChunks(sphereMesh(46), 16, 45);
  vtkNew<vtkChunkActorManager> mgr;
  std::vector<vtkIdType> ids;
  std::vector<vtkPolyData*> meshes;
};
} // namespace

TEST(ChunkActorManager, ReplacesOnlyTheChangedChunk)
{
  auto mesh = sphereMesh(40);
  auto chunks = splitChunks(mesh, 16, 39);
  ASSERT_GE(chunks.size(), 8u);
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  vtkIdType total = 0;
  for (auto& kv : chunks)
  {
    mgr->SetChunk(kv.first, kv.second);
    total += kv.second->GetNumberOfPolys();
  }
  EXPECT_EQ(mgr->GetNumberOfChunks(), static_cast<int>(chunks.size()));
  EXPECT_EQ(ren->GetActors()->GetNumberOfItems(), static_cast<int>(chunks.size()));
  EXPECT_EQ(mgr->GetNumberOfTriangles(), total);
  EXPECT_EQ(mgr->GetMergedMesh()->GetNumberOfPolys(), total);

  // Remember every actor and the data object its mapper draws.
  std::map<vtkIdType, std::pair<vtkActor*, vtkDataObject*>> before;
  std::map<vtkIdType, vtkMTimeType> mtimes;
  for (auto& kv : chunks)
  {
    vtkActor* a = mgr->GetChunkActor(kv.first);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(mgr->GetChunkId(a), kv.first);
    before[kv.first] = { a, a->GetMapper()->GetInputDataObject(0, 0) };
    mtimes[kv.first] = a->GetMapper()->GetInputDataObject(0, 0)->GetMTime();
  }
  const vtkIdType changed = chunks.begin()->first;
  auto other = sphereMesh(40); // a fresh mesh object for the changed chunk
  auto replacement = splitChunks(other, 16, 39)[changed];
  // ... with one point moved (an equal mesh would leave the chunk as shown:
  // AnEqualMeshLeavesTheChunkAsShown)
  double x[3];
  replacement->GetPoints()->GetPoint(0, x);
  x[0] += 0.25;
  replacement->GetPoints()->SetPoint(0, x);
  const vtkIdType updates = mgr->GetNumberOfChunkUpdates();
  mgr->SetChunk(changed, replacement);
  EXPECT_EQ(mgr->GetNumberOfChunkUpdates(), updates + 1);
  for (auto& kv : before)
  {
    vtkActor* a = mgr->GetChunkActor(kv.first);
    EXPECT_EQ(a, kv.second.first); // actors are kept
    // the changed chunk's prepared mesh is refilled in place (same object, new
    // contents: ReplacingAChunkRefillsItsArrays); the others are untouched
    EXPECT_EQ(a->GetMapper()->GetInputDataObject(0, 0), kv.second.second);
    if (kv.first != changed)
    {
      EXPECT_EQ(a->GetMapper()->GetInputDataObject(0, 0)->GetMTime(), mtimes[kv.first]);
    }
  }
  // An empty mesh removes the chunk's actor.
  vtkNew<vtkPolyData> empty;
  mgr->SetChunk(changed, empty);
  EXPECT_EQ(mgr->GetChunkActor(changed), nullptr);
  EXPECT_EQ(ren->GetActors()->GetNumberOfItems(), static_cast<int>(chunks.size()) - 1);
  mgr->RemoveAllChunks();
  EXPECT_EQ(ren->GetActors()->GetNumberOfItems(), 0);
}

namespace
{
// "" when the two poly data hold the same points, arrays (by name, value for
// value) and cells, else what differs.
std::string differsFrom(vtkPolyData* a, vtkPolyData* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() || a->GetNumberOfPolys() != b->GetNumberOfPolys() ||
    a->GetNumberOfCells() != b->GetNumberOfCells())
    return "counts";
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double x[3], y[3];
    a->GetPoint(i, x);
    b->GetPoint(i, y);
    if (!std::equal(x, x + 3, y))
      return "point " + std::to_string(i);
  }
  for (int which = 0; which < 2; ++which)
  {
    vtkDataSetAttributes* da = which ? static_cast<vtkDataSetAttributes*>(a->GetCellData()) : a->GetPointData();
    vtkDataSetAttributes* db = which ? static_cast<vtkDataSetAttributes*>(b->GetCellData()) : b->GetPointData();
    if (da->GetNumberOfArrays() != db->GetNumberOfArrays())
      return "array count";
    for (int k = 0; k < da->GetNumberOfArrays(); ++k)
    {
      vtkDataArray* x = da->GetArray(k);
      vtkDataArray* y = x && x->GetName() ? db->GetArray(x->GetName()) : nullptr;
      if (!x || !y || x->GetNumberOfValues() != y->GetNumberOfValues())
        return std::string("array ") + (x && x->GetName() ? x->GetName() : "?");
      for (vtkIdType v = 0; v < x->GetNumberOfValues(); ++v)
        if (x->GetComponent(v / x->GetNumberOfComponents(), static_cast<int>(v % x->GetNumberOfComponents())) !=
          y->GetComponent(v / y->GetNumberOfComponents(), static_cast<int>(v % y->GetNumberOfComponents())))
          return std::string("value of ") + x->GetName();
    }
  }
  for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c)
  {
    vtkNew<vtkIdList> x, y;
    a->GetCellPoints(c, x);
    b->GetCellPoints(c, y);
    if (x->GetNumberOfIds() != y->GetNumberOfIds())
      return "cell " + std::to_string(c);
    for (vtkIdType k = 0; k < x->GetNumberOfIds(); ++k)
      if (x->GetId(k) != y->GetId(k))
        return "cell " + std::to_string(c);
  }
  return "";
}
} // namespace

TEST(ChunkActorManager, ReplacingAChunkRefillsItsArrays)
{
  // A re-meshed chunk keeps its data object and array objects (the render
  // window's buffer cache is keyed by array) and shows exactly what a fresh
  // preparation of the new mesh holds, even with another number of triangles.
  auto chunks = splitChunks(sphereMesh(40), 16, 39);
  auto bigger = splitChunks(sphereMesh(46), 16, 45);
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  int compared = 0;
  for (auto& kv : chunks)
  {
    if (!bigger.count(kv.first))
      continue;
    mgr->SetChunk(kv.first, kv.second);
    auto* shown = shownMesh(mgr, kv.first);
    ASSERT_NE(shown, nullptr);
    std::vector<vtkAbstractArray*> arrays{ shown->GetPoints()->GetData() };
    for (int k = 0; k < shown->GetPointData()->GetNumberOfArrays(); ++k)
      arrays.push_back(shown->GetPointData()->GetAbstractArray(k));
    const vtkMTimeType mtime = shown->GetMTime();
    std::vector<vtkMTimeType> arrayTimes;
    for (vtkAbstractArray* a : arrays)
      arrayTimes.push_back(a->GetMTime());
    vtkPolyData* next = bigger[kv.first];
    mgr->SetChunk(kv.first, next);
    auto* now = shownMesh(mgr, kv.first);
    EXPECT_EQ(now, shown);
    EXPECT_GT(now->GetMTime(), mtime);
    EXPECT_EQ(now->GetPoints()->GetData(), arrays[0]);
    for (std::size_t k = 0; k < arrays.size(); ++k)
      EXPECT_GT(arrays[k]->GetMTime(), arrayTimes[k]) << "array " << k << " not marked modified: its buffer would not be re-uploaded";
    for (int k = 0; k < now->GetPointData()->GetNumberOfArrays(); ++k)
      EXPECT_EQ(now->GetPointData()->GetAbstractArray(k), arrays[static_cast<std::size_t>(k) + 1]);
    vtkSmartPointer<vtkPolyData> fresh = mgr->PrepareChunk(next);
    EXPECT_EQ(differsFrom(now, fresh), "") << "chunk " << kv.first;
    ++compared;
  }
  EXPECT_GE(compared, 8);
}

TEST(ChunkActorManager, SetChunksEqualsSetChunkOneByOne)
{
  // the parallel path shows, chunk by chunk, what SetChunk shows, and declares
  // the same changed boxes to a culler
  auto first = splitChunks(sphereMesh(40), 16, 39);
  auto second = splitChunks(sphereMesh(46), 16, 45);
  TwinManagers twins;
  vtkNew<vtkChunkActorManager>& one = twins.one;
  vtkNew<vtkChunkActorManager>& many = twins.many;
  for (auto* step : { &first, &second })
  {
    std::vector<vtkIdType> ids;
    std::vector<vtkPolyData*> meshes;
    for (auto& kv : *step)
    {
      one->SetChunk(kv.first, kv.second);
      ids.push_back(kv.first);
      meshes.push_back(kv.second);
    }
    many->SetChunks(ids, meshes);
  }
  ASSERT_EQ(one->GetNumberOfChunks(), many->GetNumberOfChunks());
  EXPECT_EQ(one->GetNumberOfChunkUpdates(), many->GetNumberOfChunkUpdates());
  for (auto& kv : second)
  {
    auto* a = shownMesh(one, kv.first);
    auto* b = shownMesh(many, kv.first);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(differsFrom(a, b), "") << "chunk " << kv.first;
  }
}

// The coordinates' ranges (which the vertex buffer upload asks for) are
// computed when a chunk is prepared and cached in the array; a refilled array
// carries the new mesh's ranges, never the old ones.
TEST(ChunkActorManager, RefilledCoordinatesCarryTheirOwnRanges)
{
  RefillScene scene;
  auto& [first, second, mgr, ids, meshes] = scene;
  ASSERT_FALSE(ids.empty());
  std::map<vtkIdType, vtkDataArray*> shownBefore;
  for (vtkIdType id : ids)
    shownBefore[id] = shownMesh(mgr, id)->GetPoints()->GetData();
  mgr->SetChunks(ids, meshes);
  int refilled = 0, differ = 0;
  for (vtkIdType id : ids)
  {
    vtkDataArray* xyz = shownMesh(mgr, id)->GetPoints()->GetData();
    refilled += xyz == shownBefore[id];
    for (int c = 0; c < 3; ++c)
    {
      double cached[2], computed[2] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
      xyz->GetRange(cached, c);
      for (vtkIdType t = 0; t < xyz->GetNumberOfTuples(); ++t) // (a copy would carry the cache)
      {
        computed[0] = std::min(computed[0], xyz->GetComponent(t, c));
        computed[1] = std::max(computed[1], xyz->GetComponent(t, c));
      }
      EXPECT_EQ(cached[0], computed[0]) << "chunk " << id << " component " << c;
      EXPECT_EQ(cached[1], computed[1]) << "chunk " << id << " component " << c;
    }
    // negative control: the first mesh's ranges differ from the second's
    vtkSmartPointer<vtkPolyData> old = mgr->PrepareChunk(first[id]);
    double a[2], b[2];
    old->GetPoints()->GetData()->GetRange(a, 0);
    xyz->GetRange(b, 0);
    differ += a[0] != b[0] || a[1] != b[1];
  }
  EXPECT_EQ(refilled, static_cast<int>(ids.size())); // the refill path was taken
  EXPECT_GT(differ, 0);
}

// The cells' bounds are computed when a chunk is prepared and handed to its
// mapper (vtkTetrahedralColorMapper::SetInputBounds): the mapper's bounds are
// those of the mesh it shows, after a refill too, and once the mesh is
// changed in place, those of the changed mesh.
TEST(ChunkActorManager, MapperBoundsAreThoseOfTheShownMesh)
{
  RefillScene scene;
  auto& [first, second, mgr, ids, meshes] = scene;
  mgr->SetChunks(ids, meshes); // refilled
  // the cells' bounds of a poly data, from its cells' points
  auto cellsBounds = [](vtkPolyData* pd) {
    std::vector<double> b = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
      -VTK_DOUBLE_MAX };
    vtkNew<vtkIdList> cell;
    for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
    {
      pd->GetCellPoints(c, cell);
      for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
        for (int a = 0; a < 3; ++a)
        {
          b[2 * a] = std::min(b[2 * a], pd->GetPoint(cell->GetId(k))[a]);
          b[2 * a + 1] = std::max(b[2 * a + 1], pd->GetPoint(cell->GetId(k))[a]);
        }
    }
    return b;
  };
  for (vtkIdType id : ids)
  {
    vtkMapper* m = mgr->GetChunkActor(id)->GetMapper();
    auto* shown = vtkPolyData::SafeDownCast(m->GetInputDataObject(0, 0));
    const double* mb = m->GetBounds();
    EXPECT_EQ(std::vector<double>(mb, mb + 6), cellsBounds(shown)) << "chunk " << id;
  }
  // changed in place (a point moved out of the box): the mapper's bounds follow
  vtkMapper* m = mgr->GetChunkActor(ids.front())->GetMapper();
  auto* shown = vtkPolyData::SafeDownCast(m->GetInputDataObject(0, 0));
  double p[3];
  shown->GetPoint(0, p);
  p[0] += 100;
  shown->GetPoints()->SetPoint(0, p);
  shown->GetPoints()->Modified();
  const double* mb = m->GetBounds();
  EXPECT_EQ(std::vector<double>(mb, mb + 6), cellsBounds(shown));
  EXPECT_GE(mb[1], p[0]);
}

// One mesh object given for two chunks, then replaced in both with one call
// (each object read by one thread at a time: such calls take the serial
// path): the same pictures' inputs as SetChunk one by one.
TEST(ChunkActorManager, SetChunksWithSharedMeshesEqualsSetChunk)
{
  auto first = splitChunks(sphereMesh(40), 16, 39);
  auto second = splitChunks(sphereMesh(46), 16, 45);
  ASSERT_GE(first.size(), 2u);
  const vtkIdType a = first.begin()->first, b = std::next(first.begin())->first;
  TwinManagers twins;
  vtkNew<vtkChunkActorManager>& one = twins.one;
  vtkNew<vtkChunkActorManager>& many = twins.many;
  vtkPolyData* shared = first[a];
  for (vtkChunkActorManager* m : { one.Get(), many.Get() })
  {
    m->SetChunk(a, shared);
    m->SetChunk(b, shared);
  }
  // b gets the mesh a had (still a's current one), a gets a new one, then b once more
  one->SetChunk(a, second[a]);
  one->SetChunk(b, shared);
  one->SetChunk(b, second[a]);
  many->SetChunks({ a, b, b }, { second[a].Get(), shared, second[a].Get() });
  for (vtkIdType id : { a, b })
  {
    auto* x = shownMesh(one, id);
    auto* y = shownMesh(many, id);
    ASSERT_TRUE(x && y);
    EXPECT_EQ(differsFrom(x, y), "") << "chunk " << id;
  }
}

TEST(ChunkActorManager, PlainMeshesKeepTheirPoints)
{
  auto mesh = sphereMesh(20);
  mesh->GetCellData()->RemoveArray("corner_rgba"); // per-vertex colour only
  vtkNew<vtkChunkActorManager> mgr;
  auto prepared = mgr->PrepareChunk(mesh);
  EXPECT_EQ(prepared.Get(), mesh.Get());
  mgr->SetChunk(0, mesh);
  auto* mapper = vtkTetrahedralColorMapper::SafeDownCast(mgr->GetChunkActor(0)->GetMapper());
  ASSERT_NE(mapper, nullptr);
  EXPECT_EQ(mapper->GetInput()->GetNumberOfPoints(), mesh->GetNumberOfPoints());
}

namespace
{
// The same triangles in another order, each starting at another vertex, the
// points renumbered (reversed): the same surface as drawn.
vtkSmartPointer<vtkPolyData> shuffled(vtkPolyData* in)
{
  const vtkIdType np = in->GetNumberOfPoints(), nt = in->GetNumberOfPolys();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetNumberOfPoints(np);
  out->GetPointData()->CopyAllocate(in->GetPointData(), np);
  for (vtkIdType p = 0; p < np; ++p)
  {
    pts->SetPoint(np - 1 - p, in->GetPoint(p));
    out->GetPointData()->CopyData(in->GetPointData(), p, np - 1 - p);
  }
  out->SetPoints(pts);
  vtkNew<vtkCellArray> polys;
  out->GetCellData()->CopyAllocate(in->GetCellData(), nt);
  for (vtkIdType k = 0; k < nt; ++k)
  {
    const vtkIdType t = (k * 7919) % nt; // nt is not a multiple of the prime
    vtkIdType n;
    const vtkIdType* ids;
    in->GetCellPoints(t, n, ids);
    const vtkIdType r[3] = { np - 1 - ids[(k + 1) % 3], np - 1 - ids[(k + 2) % 3], np - 1 - ids[k % 3] };
    polys->InsertNextCell(3, r);
    out->GetCellData()->CopyData(in->GetCellData(), t, k);
  }
  out->SetPolys(polys);
  return out;
}

// Brute force: whether triangle t of a has an equal in b (every point value
// and cell value compared, each rotation of b's triangle tried).
bool hasEqual(vtkPolyData* a, vtkIdType t, vtkPolyData* b)
{
  auto pointValues = [](vtkPolyData* pd, vtkIdType p) {
    std::vector<double> v(3);
    pd->GetPoint(p, v.data());
    for (int i = 0; i < pd->GetPointData()->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* arr = pd->GetPointData()->GetArray(i);
      for (int c = 0; c < arr->GetNumberOfComponents(); ++c)
        v.push_back(arr->GetComponent(p, c));
    }
    return v;
  };
  auto cellValues = [](vtkPolyData* pd, vtkIdType c) {
    std::vector<double> v;
    for (int i = 0; i < pd->GetCellData()->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* arr = pd->GetCellData()->GetArray(i);
      for (int k = 0; k < arr->GetNumberOfComponents(); ++k)
        v.push_back(arr->GetComponent(c, k));
    }
    return v;
  };
  vtkIdType n;
  const vtkIdType* ia;
  a->GetCellPoints(t, n, ia);
  const auto ca = cellValues(a, t);
  for (vtkIdType u = 0; u < b->GetNumberOfPolys(); ++u)
  {
    const vtkIdType* ib;
    b->GetCellPoints(u, n, ib);
    if (cellValues(b, u) != ca)
      continue;
    for (int r = 0; r < 3; ++r)
    {
      bool same = true;
      for (int v = 0; v < 3 && same; ++v)
        same = pointValues(a, ia[v]) == pointValues(b, ib[(v + r) % 3]);
      if (same)
        return true;
    }
  }
  return false;
}

void expectBruteForceBounds(vtkPolyData* before, vtkPolyData* after)
{
  vtkBoundingBox expected;
  for (vtkPolyData* pd : { before, after })
  {
    vtkPolyData* other = pd == before ? after : before;
    for (vtkIdType t = 0; t < pd->GetNumberOfPolys(); ++t)
      if (!hasEqual(pd, t, other))
      {
        vtkIdType n;
        const vtkIdType* ids;
        pd->GetCellPoints(t, n, ids);
        for (int v = 0; v < 3; ++v)
          expected.AddPoint(pd->GetPoint(ids[v]));
      }
  }
  double b[6];
  const bool changed = vtkChunkActorManager::ChangedBounds(before, after, b);
  ASSERT_EQ(changed, expected.IsValid());
  if (changed)
  {
    double e[6];
    expected.GetBounds(e);
    for (int i = 0; i < 6; ++i)
      EXPECT_EQ(b[i], e[i]) << "bound " << i;
  }
}
} // namespace

TEST(ChunkActorManager, ChangedBoundsAreThoseOfTheDifferingTriangles)
{
  const int n = 16;
  const double c = 0.5 * (n - 1);
  auto sphere = [=](double x, double y, double z) {
    return std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - 0.33 * n;
  };
  auto before = contractMesh(sdfImage(n, sphere), checkerColor);
  // a dent on the +x side
  auto dented = contractMesh(sdfImage(n, [=](double x, double y, double z) {
    const double d = std::sqrt((x - c - 0.33 * n) * (x - c - 0.33 * n) + (y - c) * (y - c) + (z - c) * (z - c));
    return std::max(sphere(x, y, z), 2.5 - d);
  }), checkerColor);
  SCOPED_TRACE("dent");
  expectBruteForceBounds(before, dented);
  double b[6];
  ASSERT_TRUE(vtkChunkActorManager::ChangedBounds(before, dented, b));
  EXPECT_GT(b[0], c); // only around the dent
  // The same triangles, reordered and renumbered: nothing changed.
  auto same = shuffled(before);
  EXPECT_FALSE(vtkChunkActorManager::ChangedBounds(before, same, b));
  expectBruteForceBounds(before, same);
  // One triangle's corner colour changed: that triangle alone.
  auto painted = vtkSmartPointer<vtkPolyData>::New();
  painted->DeepCopy(same);
  painted->GetCellData()->GetArray("corner_rgba")->SetComponent(5, 7, 1);
  expectBruteForceBounds(before, painted);
  ASSERT_TRUE(vtkChunkActorManager::ChangedBounds(before, painted, b));
  vtkIdType np;
  const vtkIdType* ids;
  painted->GetCellPoints(5, np, ids);
  vtkBoundingBox tri;
  for (int v = 0; v < 3; ++v)
    tri.AddPoint(painted->GetPoint(ids[v]));
  double e[6];
  tri.GetBounds(e);
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(b[i], e[i]);
  // Nothing before: the whole new mesh.
  vtkNew<vtkPolyData> empty;
  ASSERT_TRUE(vtkChunkActorManager::ChangedBounds(empty, before, b));
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(b[i], before->GetBounds()[i]);
}


// A re-meshed chunk whose new mesh equals the one it shows (another object,
// the same values) is left as it is: not prepared, refilled or uploaded again.
// What it shows is then still exactly a fresh preparation of the new mesh; a
// mesh differing in one point coordinate, one point colour or one corner
// colour is shown; a shown mesh whose object the caller changed in place is
// never taken as equal (its preparation would be stale).
TEST(ChunkActorManager, AnEqualMeshLeavesTheChunkAsShown)
{
  auto chunks = splitChunks(sphereMesh(40), 16, 39);
  auto copies = splitChunks(sphereMesh(40), 16, 39); // built again: equal values, other objects
  ASSERT_EQ(chunks.size(), copies.size());
  ASSERT_GE(chunks.size(), 8u);
  vtkNew<vtkRenderer> ren;
  vtkNew<vtkPartialRedrawCuller> culler;
  culler->SetEnabled(true);
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  mgr->SetRedrawCuller(culler);
  std::vector<vtkIdType> ids;
  std::vector<vtkPolyData*> meshes;
  for (auto& kv : chunks)
  {
    mgr->SetChunk(kv.first, kv.second);
    ids.push_back(kv.first);
    meshes.push_back(copies.at(kv.first));
  }
  EXPECT_EQ(mgr->GetNumberOfUnchangedMeshes(), 0);
  // three chunks differ in one value each: a coordinate, a point colour, a corner colour
  auto it = copies.begin();
  vtkPolyData* moved = (it++)->second;
  vtkPolyData* repainted = (it++)->second;
  vtkPolyData* recornered = (it++)->second;
  double x[3];
  moved->GetPoints()->GetPoint(1, x);
  x[2] += 1e-3;
  moved->GetPoints()->SetPoint(1, x);
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(repainted->GetPointData()->GetArray("rgba"));
  auto* corners = vtkUnsignedCharArray::SafeDownCast(recornered->GetCellData()->GetArray("corner_rgba"));
  ASSERT_TRUE(rgba && corners);
  rgba->SetValue(5, static_cast<unsigned char>(rgba->GetValue(5) ^ 1));
  corners->SetValue(7, static_cast<unsigned char>(corners->GetValue(7) ^ 1));
  const std::set<vtkPolyData*> differing{ moved, repainted, recornered };

  std::map<vtkIdType, std::pair<vtkPolyData*, vtkMTimeType>> shown;
  for (vtkIdType id : ids)
    shown[id] = { shownMesh(mgr, id), shownMesh(mgr, id)->GetMTime() };
  const vtkIdType updates = mgr->GetNumberOfChunkUpdates();
  mgr->SetChunks(ids, meshes);
  EXPECT_EQ(mgr->GetNumberOfChunkUpdates(), updates + 3);
  EXPECT_EQ(mgr->GetNumberOfUnchangedMeshes(), static_cast<vtkIdType>(ids.size()) - 3);
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    vtkPolyData* now = shownMesh(mgr, ids[i]);
    ASSERT_NE(now, nullptr);
    EXPECT_EQ(now, shown[ids[i]].first); // refilled in place or untouched
    if (differing.count(meshes[i]))
      EXPECT_GT(now->GetMTime(), shown[ids[i]].second) << "chunk " << ids[i] << " was not updated";
    else
      EXPECT_EQ(now->GetMTime(), shown[ids[i]].second) << "chunk " << ids[i] << " was prepared again";
    // the oracle: whatever was skipped, each chunk shows its new mesh's preparation
    vtkSmartPointer<vtkPolyData> fresh = mgr->PrepareChunk(meshes[i]);
    EXPECT_EQ(differsFrom(now, fresh), "") << "chunk " << ids[i];
  }
  // SetChunk does the same
  const vtkIdType first = ids.front();
  auto again = splitChunks(sphereMesh(40), 16, 39);
  const vtkIdType unchangedBefore = mgr->GetNumberOfUnchangedMeshes();
  vtkPolyData* equalToFirst = again.at(ids[3]);
  mgr->SetChunk(ids[3], equalToFirst);
  EXPECT_EQ(mgr->GetNumberOfUnchangedMeshes(), unchangedBefore + 1);
  // The shown mesh's own object changed in place by its caller: its chunk's
  // preparation is of the old values, so a mesh equal to the new values is shown.
  vtkPolyData* given = meshes[0]; // the chunk's source now (it was updated: moved)
  ASSERT_EQ(ids[0], first);
  vtkSmartPointer<vtkPolyData> sameValues = vtkSmartPointer<vtkPolyData>::New();
  sameValues->DeepCopy(given);
  given->GetPoints()->GetPoint(2, x);
  x[1] += 0.5;
  given->GetPoints()->SetPoint(2, x);
  given->GetPoints()->Modified(); // as VTK asks of a change in place
  sameValues->GetPoints()->SetPoint(2, x);
  const vtkIdType updatesBefore = mgr->GetNumberOfChunkUpdates();
  mgr->SetChunk(first, sameValues);
  EXPECT_EQ(mgr->GetNumberOfChunkUpdates(), updatesBefore + 1);
  EXPECT_EQ(mgr->GetNumberOfUnchangedMeshes(), unchangedBefore + 1);
  EXPECT_EQ(differsFrom(shownMesh(mgr, first), mgr->PrepareChunk(sameValues)), "");
  // another geometry (origin) prepares every chunk again, equal mesh or not
  mgr->SetOrigin(1, 0, 0);
  mgr->SetChunk(ids[3], again.at(ids[3]));
  EXPECT_EQ(mgr->GetNumberOfUnchangedMeshes(), unchangedBefore + 1);
}
