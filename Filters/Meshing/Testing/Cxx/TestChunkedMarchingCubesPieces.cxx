// Piece-wise execution: UpdatePiece(i, n, 1) for n = 2, 3 together give the
// one-piece surface (same triangle count, area, points and normals after
// merging by position), with no triangle emitted by two pieces.
#include "vtkChunkedMarchingCubes.h"

#include "MeshingTestUtil.h"

#include "vtkPartitionedDataSet.h"
#include "vtkRTAnalyticSource.h"
#include "vtkTrivialProducer.h"

#include <gtest/gtest.h>

#include <map>

using namespace meshtest;

namespace
{
vtkSmartPointer<vtkPolyData> runPieces(vtkAlgorithm* source, const char* array, double iso, int pieces, int mode,
  std::vector<int>* sizes = nullptr)
{
  vtkNew<vtkAppendPolyData> append;
  for (int i = 0; i < pieces; ++i)
  {
    vtkNew<vtkChunkedMarchingCubes> mc;
    mc->SetInputConnection(source->GetOutputPort());
    mc->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, array);
    mc->SetIsoValue(iso);
    mc->SetChunkEdge(16);
    mc->SetOutputMode(mode);
    mc->UpdatePiece(i, pieces, 1);
    vtkDataObject* out = mc->GetOutputDataObject(0);
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    if (auto* pd = vtkPolyData::SafeDownCast(out))
    {
      copy->DeepCopy(pd);
    }
    else
    {
      auto* pds = vtkPartitionedDataSet::SafeDownCast(out);
      vtkNew<vtkAppendPolyData> a;
      for (unsigned int p = 0; p < pds->GetNumberOfPartitions(); ++p)
        a->AddInputData(vtkPolyData::SafeDownCast(pds->GetPartition(p)));
      a->Update();
      copy->DeepCopy(a->GetOutput());
    }
    if (sizes) sizes->push_back(static_cast<int>(copy->GetNumberOfCells()));
    append->AddInputData(copy);
  }
  append->Update();
  return mergeByPosition(append->GetOutput());
}

/// Point -> normal, keyed by exact coordinates.
std::map<std::array<float, 3>, std::array<float, 3>> normalsByPosition(vtkPolyData* pd)
{
  std::map<std::array<float, 3>, std::array<float, 3>> m;
  auto* n = vtkFloatArray::SafeDownCast(pd->GetPointData()->GetArray("Normals"));
  auto* p = vtkFloatArray::SafeDownCast(pd->GetPoints()->GetData());
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    std::array<float, 3> x, v;
    p->GetTypedTuple(i, x.data());
    n->GetTypedTuple(i, v.data());
    m[x] = v;
  }
  return m;
}

void expectPiecesSeamless(vtkAlgorithm* source, const char* array, double iso, bool closed)
{
  for (int mode : { vtkChunkedMarchingCubes::MERGED, vtkChunkedMarchingCubes::PARTITIONED })
  {
    vtkSmartPointer<vtkPolyData> one = runPieces(source, array, iso, 1, mode);
    const Measures m1 = measure(one);
    ASSERT_GT(m1.triangles, 100);
    const auto n1 = normalsByPosition(one);
    for (int n : { 2, 3 })
    {
      SCOPED_TRACE(std::to_string(n) + (mode ? " merged pieces" : " partitioned pieces"));
      std::vector<int> sizes;
      vtkSmartPointer<vtkPolyData> all = runPieces(source, array, iso, n, mode, &sizes);
      int nonEmpty = 0;
      for (int s : sizes) nonEmpty += s > 0;
      EXPECT_GE(nonEmpty, 2) << "the split must actually cut the surface";
      const Measures mn = measure(all);
      EXPECT_EQ(mn.triangles, m1.triangles);
      EXPECT_EQ(all->GetNumberOfPoints(), one->GetNumberOfPoints());
      EXPECT_NEAR(mn.area, m1.area, 1e-9 * m1.area);
      EXPECT_EQ(duplicatedTriangles(all), 0);
      if (closed) EXPECT_EQ(openEdges(all), 0);
      // the ghost layer makes gradients at piece borders what they are in one piece
      const auto nn = normalsByPosition(all);
      ASSERT_EQ(nn.size(), n1.size());
      EXPECT_TRUE(nn == n1) << "normals differ from the one-piece run";
    }
  }
}
} // namespace

TEST(ChunkedMarchingCubesPieces, WaveletPiecesAreSeamless)
{
  // the source produces exactly the requested (ghost-grown) extent
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(0, 60, -5, 44, 0, 37);
  expectPiecesSeamless(wavelet, "RTData", 150.5, false);
}

TEST(ChunkedMarchingCubesPieces, WholeImageInputTorusPiecesAreSeamlessAndWatertight)
{
  // a trivial producer hands every piece the whole image: ownership alone must split the cells
  const int dims[3] = { 64, 57, 43 };
  const double origin[3] = { -1, -2, -3 }, spacing[3] = { 1, 1, 1 };
  auto img = sampled(dims, origin, spacing, torus(30.3, 26.1, 18.7, 18.2, 8.4));
  vtkNew<vtkTrivialProducer> tp;
  tp->SetOutput(img);
  expectPiecesSeamless(tp, "sdf", 0.0, true);
}
