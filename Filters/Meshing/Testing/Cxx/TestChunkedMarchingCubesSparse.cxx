// vtkChunkedMarchingCubes on a vtkSparseDictionaryVolume edited in place: the
// incremental run (only the chunks the dirty storage chunks reach) gives the
// triangles a fresh filter gives on the edited volume (an independent full
// run), touches only the chunks near the edit, and settings changes or a new
// volume mesh everything again.
#include "MeshingTestUtil.h"
#include "vtkChunkedMarchingCubes.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCompositeDataIterator.h"
#include "vtkPartitionedDataSet.h"
#include "vtkTrivialProducer.h"

#include <gtest/gtest.h>

namespace
{
/// All partitions in one polydata, shared chunk-seam points merged by position.
vtkSmartPointer<vtkPolyData> mergedSurface(vtkDataObject* out)
{
  vtkNew<vtkAppendPolyData> append;
  auto* pds = vtkPartitionedDataSet::SafeDownCast(out);
  for (unsigned int i = 0; i < pds->GetNumberOfPartitions(); ++i)
    append->AddInputData(vtkPolyData::SafeDownCast(pds->GetPartition(i)));
  append->Update();
  return meshtest::mergeByPosition(append->GetOutput());
}

vtkSmartPointer<vtkPolyData> freshSurface(vtkSparseDictionaryVolume* sparse)
{
  vtkNew<vtkSparseDictionaryVolume> copy; // shares the Core volume, a new filter with no cache
  copy->ShallowCopy(sparse);
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputData(copy);
  mc->SetChunkEdge(16);
  mc->Update();
  EXPECT_EQ(mc->GetLastChunksMeshed(), -1);
  return mergedSurface(mc->GetOutputDataObject(0));
}
}

TEST(ChunkedMarchingCubesSparse, EditedInPlaceRemeshesOnlyDirtyChunks)
{
  lvdif::VolumeOptions o;
  o.dims = { 160, 144, 128 };
  o.chunkEdge = 16;
  auto volume = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*volume, lvdif::sphereSdf(80, 72, 64, 50));
  volume->takeDirtyChunks();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(sparse);
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputConnection(producer->GetOutputPort());
  mc->SetChunkEdge(16);
  mc->Update();
  EXPECT_EQ(mc->GetLastChunksMeshed(), -1); // the first run meshes everything
  const vtkIdType before = mergedSurface(mc->GetOutputDataObject(0))->GetNumberOfCells();
  ASSERT_GT(before, 1000);

  // a small bump on the sphere's top (80, 72, 114): a union with a small sphere
  const auto bump = lvdif::sphereSdf(80, 72, 116, 5);
  for (std::int64_t z = 105; z < 128; ++z)
    for (std::int64_t y = 62; y < 83; ++y)
      for (std::int64_t x = 70; x < 91; ++x)
      {
        const float d = std::min(volume->sdf(x, y, z), bump(static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)));
        volume->setSdf(x, y, z, d);
      }
  sparse->VolumeModified();
  mc->Update();
  const vtkIdType remeshed = mc->GetLastChunksMeshed();
  EXPECT_GT(remeshed, 0);
  const vtkIdType total = vtkPartitionedDataSet::SafeDownCast(mc->GetOutputDataObject(0))->GetNumberOfPartitions();
  EXPECT_LT(remeshed, total / 3) << "only the chunks near the edit";
  vtkSmartPointer<vtkPolyData> incremental = mergedSurface(mc->GetOutputDataObject(0));
  vtkSmartPointer<vtkPolyData> full = freshSurface(sparse);
  EXPECT_NE(incremental->GetNumberOfCells(), before);
  const meshtest::TriangleMatch m = meshtest::matchTriangles(incremental, full, 1e-6);
  EXPECT_TRUE(m.identical()) << m.unmatchedPoints << " unmatched points, " << m.onlyInA << " / " << m.onlyInB
                             << " unmatched triangles";
  EXPECT_EQ(meshtest::openEdges(incremental), 0);

  // nothing dirty: nothing meshed, the same surface
  sparse->VolumeModified();
  mc->Update();
  EXPECT_EQ(mc->GetLastChunksMeshed(), 0);
  EXPECT_EQ(mergedSurface(mc->GetOutputDataObject(0))->GetNumberOfCells(), incremental->GetNumberOfCells());

  // a setting changed: everything again
  mc->SetIsoValue(0.5);
  mc->Update();
  EXPECT_EQ(mc->GetLastChunksMeshed(), -1);
}

// A sparse volume of one batch of marching-cubes chunks (at most 64: the
// filter meshes 64 at a time) reported no progress between 0 and 1 (Core
// forwarded every 64th chunk only), so ParaView's progress bar jumped and a
// cancel asked from a progress event came only after the work. Now progress
// within the batch, in both output modes, and a cancel at the first report
// past 0 leaves an empty output. Oracle for "it stopped": the same run
// without the cancel has triangles.
namespace
{
struct McProgress
{
  std::vector<double> values;
  bool abortPastZero = false;
};
void onMcProgress(vtkObject* caller, unsigned long, void* client, void* call)
{
  auto* p = static_cast<McProgress*>(client);
  const double v = *static_cast<double*>(call);
  p->values.push_back(v);
  if (p->abortPastZero && v > 0) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
}
vtkIdType triangles(vtkDataObject* out)
{
  if (auto* pd = vtkPolyData::SafeDownCast(out)) return pd->GetNumberOfCells();
  auto* pds = vtkPartitionedDataSet::SafeDownCast(out);
  vtkIdType n = 0;
  for (unsigned int i = 0; pds && i < pds->GetNumberOfPartitions(); ++i)
    n += pds->GetPartition(i) ? pds->GetPartition(i)->GetNumberOfCells() : 0;
  return n;
}
}

TEST(ChunkedMarchingCubesSparse, OneBatchReportsProgressAndHonoursACancel)
{
  lvdif::VolumeOptions o;
  o.dims = { 128, 128, 128 };
  o.chunkEdge = 32;
  auto volume = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*volume, lvdif::sphereSdf(64, 64, 64, 50));
  for (const int mode : { vtkChunkedMarchingCubes::PARTITIONED, vtkChunkedMarchingCubes::MERGED })
    for (const bool cancel : { false, true })
    {
      vtkNew<vtkSparseDictionaryVolume> sparse;
      sparse->SetVolume(volume);
      vtkNew<vtkChunkedMarchingCubes> mc;
      mc->SetInputData(sparse);
      mc->SetChunkEdge(32); // 4 x 4 x 4 chunks: one batch
      mc->SetOutputMode(mode);
      McProgress log;
      log.abortPastZero = cancel;
      vtkNew<vtkCallbackCommand> cb;
      cb->SetCallback(onMcProgress);
      cb->SetClientData(&log);
      mc->AddObserver(vtkCommand::ProgressEvent, cb);
      mc->Update();
      int within = 0;
      for (const double v : log.values) within += v > 0 && v < 1 ? 1 : 0;
      const vtkIdType n = triangles(mc->GetOutputDataObject(0));
      if (!cancel)
      {
        EXPECT_GT(n, 1000) << "mode " << mode;
        EXPECT_GT(within, 5) << "progress between 0 and 1, mode " << mode;
        ASSERT_FALSE(log.values.empty());
        EXPECT_EQ(log.values.back(), 1.0);
        EXPECT_TRUE(std::is_sorted(log.values.begin(), log.values.end())) << "progress never goes back";
      }
      else
      {
        EXPECT_EQ(n, 0) << "the cancelled filter's output, mode " << mode;
        EXPECT_LE(within, 3) << "it stopped soon after the cancel, mode " << mode;
      }
    }
}
