// Non-rendering checks of the chunk pipeline: vtkCornerColorAttributes
// against the input arrays recomputed in double, and the actor manager's
// bookkeeping (only the replaced chunk's mapper gets a new input).
#include "ChunkTestData.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkChunkActorManager.h"
#include "vtkCornerColorAttributes.h"
#include "vtkExecutive.h"
#include "vtkMapper.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"

#include <gtest/gtest.h>

using namespace lvdiftest;

namespace
{
vtkSmartPointer<vtkPolyData> sphereMesh(int n = 24, double spacing = 1.0)
{
  auto img = sdfImage(n, [n](double x, double y, double z) {
    const double c = 0.5 * (n - 1);
    return std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - 0.33 * n;
  }, spacing);
  return contractMesh(img, checkerColor);
}
} // namespace

TEST(CornerColorAttributes, UnsharesAndCarriesCornerColours)
{
  auto mesh = sphereMesh(24, 0.5);
  ASSERT_GT(mesh->GetNumberOfPolys(), 100);
  vtkNew<vtkCornerColorAttributes> f;
  f->SetInputData(mesh);
  f->SetSpacing(0.5, 0.5, 0.5);
  f->Update();
  vtkPolyData* out = f->GetOutput();
  const vtkIdType nt = mesh->GetNumberOfPolys();
  ASSERT_EQ(out->GetNumberOfPolys(), nt);
  ASSERT_EQ(out->GetNumberOfPoints(), 3 * nt);
  auto* local = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("lvdif_cell_local"));
  ASSERT_NE(local, nullptr);
  auto* corners = vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetArray("corner_rgba"));
  vtkDataArray* ijk = mesh->GetCellData()->GetArray("cell_ijk");
  vtkDataArray* inRgba = mesh->GetPointData()->GetArray("rgba");
  vtkDataArray* outRgba = out->GetPointData()->GetArray("rgba");
  ASSERT_NE(outRgba, nullptr);
  ASSERT_NE(out->GetPointData()->GetArray("Normals"), nullptr);
  EXPECT_EQ(out->GetCellData()->GetArray("corner_rgba"), nullptr); // not carried twice
  for (vtkIdType t = 0; t < nt; ++t)
  {
    vtkIdType n;
    const vtkIdType* in;
    const vtkIdType* o;
    mesh->GetCellPoints(t, n, in);
    out->GetCellPoints(t, n, o);
    ASSERT_EQ(n, 3);
    for (int v = 0; v < 3; ++v)
    {
      double p[3], q[3];
      mesh->GetPoint(in[v], p);
      out->GetPoint(o[v], q);
      for (int a = 0; a < 3; ++a)
      {
        ASSERT_NEAR(p[a], q[a], 1e-6);
        const double u = p[a] / 0.5 - ijk->GetComponent(t, a);
        ASSERT_NEAR(local->GetComponent(o[v], a), u, 1e-5);
        ASSERT_GE(u, -1e-6); // the triangle lies in its cell
        ASSERT_LE(u, 1 + 1e-6);
      }
      for (int q4 = 0; q4 < 4; ++q4)
      {
        ASSERT_EQ(outRgba->GetComponent(o[v], q4), inRgba->GetComponent(in[v], q4));
      }
      for (int c = 0; c < 8; ++c)
      {
        vtkDataArray* ca = out->GetPointData()->GetArray(vtkCornerColorAttributes::CornerArrayName(c));
        for (int q4 = 0; q4 < 4; ++q4)
        {
          ASSERT_EQ(ca->GetComponent(o[v], q4), corners->GetComponent(t, 4 * c + q4));
        }
      }
    }
  }
}

TEST(CornerColorAttributes, RefusesInputWithoutContract)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkCornerColorAttributes> f;
  f->SetInputData(empty);
  int errors = 0;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&errors);
  cb->SetCallback([](vtkObject*, unsigned long, void* cd, void*) { ++*static_cast<int*>(cd); });
  f->AddObserver(vtkCommand::ErrorEvent, cb);
  f->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, cb);
  f->Update();
  EXPECT_GE(errors, 1);
}

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
  for (auto& kv : chunks)
  {
    vtkActor* a = mgr->GetChunkActor(kv.first);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(mgr->GetChunkId(a), kv.first);
    before[kv.first] = { a, a->GetMapper()->GetInputDataObject(0, 0) };
  }
  const vtkIdType changed = chunks.begin()->first;
  auto other = sphereMesh(40); // a fresh mesh object for the changed chunk
  auto replacement = splitChunks(other, 16, 39)[changed];
  const vtkIdType updates = mgr->GetNumberOfChunkUpdates();
  mgr->SetChunk(changed, replacement);
  EXPECT_EQ(mgr->GetNumberOfChunkUpdates(), updates + 1);
  for (auto& kv : before)
  {
    vtkActor* a = mgr->GetChunkActor(kv.first);
    EXPECT_EQ(a, kv.second.first); // actors are kept
    if (kv.first == changed)
    {
      EXPECT_NE(a->GetMapper()->GetInputDataObject(0, 0), kv.second.second);
    }
    else
    {
      EXPECT_EQ(a->GetMapper()->GetInputDataObject(0, 0), kv.second.second);
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
