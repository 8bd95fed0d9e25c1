// vtkChunkedMarchingCubes against VTK's own vtkFlyingEdges3D and
// vtkMarchingCubes on the same image: the same triangles up to float rounding
// (hence Hausdorff distance ~0), area and enclosed volume within 1e-5, equal
// triangle counts, for chunk edges 16, 23, 32 on a sphere (divisible and
// non-divisible grids), a torus, a noisy field with many ambiguous cells, the
// wavelet, and all 256 single-cell cases; watertightness; the per-chunk
// output's field data; the colour arrays against the input image.
#include "vtkChunkedMarchingCubes.h"

#include "MeshingTestUtil.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMarchingCubes.h"
#include "vtkPartitionedDataSet.h"
#include "vtkRTAnalyticSource.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

using namespace meshtest;

namespace
{
vtkSmartPointer<vtkPolyData> reference(vtkAlgorithm* contour, vtkDataObject* input, const char* array, double iso)
{
  contour->SetInputDataObject(input);
  contour->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, array);
  if (auto* fe = vtkFlyingEdges3D::SafeDownCast(contour))
  {
    fe->SetValue(0, iso);
    fe->ComputeNormalsOff();
    fe->ComputeScalarsOff();
    fe->ComputeGradientsOff();
  }
  if (auto* mc = vtkMarchingCubes::SafeDownCast(contour))
  {
    mc->SetValue(0, iso);
    mc->ComputeNormalsOff();
    mc->ComputeScalarsOff();
    mc->ComputeGradientsOff();
  }
  contour->Update();
  return vtkPolyData::SafeDownCast(contour->GetOutputDataObject(0));
}

vtkSmartPointer<vtkPolyData> chunked(vtkDataObject* input, const char* array, double iso, int edge, int mode)
{
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputDataObject(input);
  mc->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, array);
  mc->SetIsoValue(iso);
  mc->SetChunkEdge(edge);
  mc->SetOutputMode(mode);
  mc->Update();
  if (mode == vtkChunkedMarchingCubes::MERGED) return vtkPolyData::SafeDownCast(mc->GetOutputDataObject(0));
  // partitions: append, then join the duplicated boundary vertices by position
  auto* pds = vtkPartitionedDataSet::SafeDownCast(mc->GetOutputDataObject(0));
  vtkNew<vtkAppendPolyData> append;
  for (unsigned int i = 0; i < pds->GetNumberOfPartitions(); ++i)
    append->AddInputData(vtkPolyData::SafeDownCast(pds->GetPartition(i)));
  append->Update();
  return mergeByPosition(append->GetOutput());
}

/// The chunked surface IS both VTK filters' surface (the filter uses VTK's
/// case table by default): after merging points by position on both sides
/// (vertices within float rounding of a grid point collapse onto it, making
/// degenerate triangles that vtkCleanPolyData drops), every triangle of ours
/// equals one of VTK's as a set of 3 vertex positions up to float rounding of
/// a coordinate of size `scale` (1e-6 scale), and vice versa (matchTriangles; this bounds
/// the Hausdorff distance by that tolerance). Area and enclosed volume (our
/// divergence-theorem sum in double) agree within 1e-5 relative, triangle and
/// point counts are equal.
void expectSameSurface(vtkDataObject* input, const char* array, double iso, bool closed, double scale)
{
  vtkNew<vtkFlyingEdges3D> fe;
  vtkNew<vtkMarchingCubes> vmc;
  vtkSmartPointer<vtkPolyData> refs[2] = { mergeByPosition(reference(fe, input, array, iso)),
    mergeByPosition(reference(vmc, input, array, iso)) };
  ASSERT_GT(measure(refs[0]).triangles, 100);
  const double tol = 1e-6 * scale; // a few float ulps of the largest coordinate
  for (int edge : { 16, 23, 32 })
    for (int mode : { vtkChunkedMarchingCubes::MERGED, vtkChunkedMarchingCubes::PARTITIONED })
    {
      SCOPED_TRACE("chunk edge " + std::to_string(edge) + (mode ? " merged" : " partitioned"));
      vtkSmartPointer<vtkPolyData> raw = chunked(input, array, iso, edge, mode);
      if (closed && mode == vtkChunkedMarchingCubes::MERGED)
      {
        EXPECT_EQ(openEdges(raw), 0) << "merged output (one point per cut edge) must be watertight as it is";
      }
      vtkSmartPointer<vtkPolyData> ours = mergeByPosition(raw);
      const Measures m = measure(ours);
      for (int r = 0; r < 2; ++r)
      {
        SCOPED_TRACE(r == 0 ? "vs vtkFlyingEdges3D" : "vs vtkMarchingCubes");
        vtkPolyData* ref = refs[r];
        const Measures q = measure(ref);
        EXPECT_EQ(m.triangles, q.triangles);
        EXPECT_EQ(ours->GetNumberOfPoints(), ref->GetNumberOfPoints());
        EXPECT_NEAR(m.area, q.area, 1e-5 * q.area);
        if (closed)
        {
          EXPECT_NEAR(std::abs(m.volume), std::abs(q.volume), 1e-5 * std::abs(q.volume));
        }
        const TriangleMatch tm = matchTriangles(ours, ref, tol);
        EXPECT_TRUE(tm.identical()) << "unmatched points " << tm.unmatchedPoints << ", ambiguous " << tm.ambiguousPoints
                                    << ", triangles only ours " << tm.onlyInA << ", only VTK's " << tm.onlyInB;
        EXPECT_LE(tm.maxPointDistance, tol);
        if (std::getenv("LVDIF_PRINT_MATCH")) // the measured differences, for docs/MARCHING_CUBES.md
          std::printf("edge %d mode %d ref %d: %lld triangles, max point distance %.3g (tol %.3g), ambiguous %lld, "
                      "area rel diff %.2g, volume rel diff %.2g\n",
            edge, mode, r, static_cast<long long>(m.triangles), tm.maxPointDistance, tol,
            static_cast<long long>(tm.ambiguousPoints), std::abs(m.area - q.area) / q.area,
            q.volume != 0 ? std::abs(std::abs(m.volume) - std::abs(q.volume)) / std::abs(q.volume) : 0.0);
        // VTK lists its triangles the other way round (ours: counter-clockwise seen from outside)
        EXPECT_EQ(tm.sameOrientation, 0);
        EXPECT_EQ(tm.reversedOrientation, m.triangles);
      }
      if (closed)
      {
        EXPECT_GT(m.volume, 0) << "triangles must be counter-clockwise seen from outside";
        EXPECT_EQ(openEdges(ours), 0);
      }
      EXPECT_EQ(duplicatedTriangles(ours), 0);
    }
}
} // namespace

TEST(ChunkedMarchingCubes, SphereEqualsFlyingEdgesAndMarchingCubes)
{
  const int dims[3] = { 70, 61, 66 }; // 69 x 60 x 65 cells: no chunk edge divides them
  const double origin[3] = { -3.0, 1.0, 0.5 }, spacing[3] = { 0.25, 0.3, 0.27 };
  auto img = sampled(dims, origin, spacing, sphere(5.1, 10.2, 9.3, 7.77));
  expectSameSurface(img, "sdf", 0.0, true, 20.0);
}

TEST(ChunkedMarchingCubes, SphereOnDivisibleGridEqualsVtk)
{
  const int dims[3] = { 65, 65, 33 }; // 64 x 64 x 32 cells: 16 and 32 divide them, 23 does not
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  auto img = sampled(dims, origin, spacing, sphere(31.7, 32.2, 16.1, 14.3));
  expectSameSurface(img, "sdf", 0.0, true, 64.0);
}

TEST(ChunkedMarchingCubes, TorusEqualsFlyingEdgesAndMarchingCubes)
{
  const int dims[3] = { 81, 77, 40 };
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  auto img = sampled(dims, origin, spacing, torus(40.3, 38.1, 19.7, 25.2, 9.4));
  expectSameSurface(img, "sdf", 0.0, true, 80.0);
}

namespace
{
/// A closed but very rough surface: a sphere plus per-point noise of 1.5 voxels
/// (the border stays outside), with thousands of ambiguous cells.
vtkSmartPointer<vtkImageData> noisyBlob()
{
  const int dims[3] = { 57, 50, 45 };
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  return sampledNoisy(dims, origin, spacing, sphere(28.2, 24.7, 22.1, 15.3), 1.5, 2024);
}
}

TEST(ChunkedMarchingCubes, NoisyFieldWithManyAmbiguousCasesEqualsVtk)
{
  auto img = noisyBlob();
  EXPECT_GT(ambiguousCells(img, "sdf", 0.0), 1000);
  expectSameSurface(img, "sdf", 0.0, true, 60.0);
}

TEST(ChunkedMarchingCubes, OwnCaseTableHasOtherDiagonalsThanVtk)
{
  // the check above can fail: lvdif's own table (UseVTKCaseTableOff) gives the
  // same vertices and triangle count but other triangles
  auto img = noisyBlob();
  vtkNew<vtkFlyingEdges3D> fe;
  vtkSmartPointer<vtkPolyData> ref = mergeByPosition(reference(fe, img, "sdf", 0.0));
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputData(img);
  mc->SetChunkEdge(23);
  mc->SetOutputModeToMerged();
  mc->UseVTKCaseTableOff();
  mc->Update();
  vtkSmartPointer<vtkPolyData> ours = mergeByPosition(vtkPolyData::SafeDownCast(mc->GetOutputDataObject(0)));
  EXPECT_EQ(openEdges(ours), 0);
  EXPECT_EQ(measure(ours).triangles, measure(ref).triangles);
  const TriangleMatch tm = matchTriangles(ours, ref, 1e-6 * 60.0);
  EXPECT_EQ(tm.unmatchedPoints, 0);
  EXPECT_GT(tm.onlyInA, 100) << "lvdif's own table should differ from VTK's on a noisy field";
  EXPECT_EQ(tm.onlyInA, tm.onlyInB);
}

TEST(ChunkedMarchingCubes, EverySingleCellCaseEqualsVtk)
{
  // all 256 sign patterns of one cell (values +-1: vertices at edge midpoints,
  // exact in float): the same triangles as vtkMarchingCubes and vtkFlyingEdges3D
  int differ = 0;
  for (int cs = 1; cs < 255; ++cs)
  {
    const int dims[3] = { 2, 2, 2 };
    const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
    auto img = sampled(dims, origin, spacing, [cs](double x, double y, double z) {
      const int c = static_cast<int>(x) + 2 * static_cast<int>(y) + 4 * static_cast<int>(z);
      return ((cs >> c) & 1) ? 1.0 : -1.0;
    });
    vtkSmartPointer<vtkPolyData> ours = chunked(img, "sdf", 0.0, 16, vtkChunkedMarchingCubes::MERGED);
    vtkNew<vtkMarchingCubes> vmc;
    vtkNew<vtkFlyingEdges3D> fe;
    for (vtkAlgorithm* alg : { static_cast<vtkAlgorithm*>(vmc), static_cast<vtkAlgorithm*>(fe) })
    {
      vtkSmartPointer<vtkPolyData> ref = reference(alg, img, "sdf", 0.0);
      const TriangleMatch tm = matchTriangles(ours, ref, 1e-7);
      EXPECT_TRUE(tm.identical()) << "case " << cs << " vs " << alg->GetClassName();
      EXPECT_EQ(tm.reversedOrientation, ref->GetNumberOfCells()) << "case " << cs;
    }
    // and the cases where lvdif's own table differs exist (so this test can fail)
    vtkNew<vtkChunkedMarchingCubes> own;
    own->SetInputData(img);
    own->SetOutputModeToMerged();
    own->UseVTKCaseTableOff();
    own->Update();
    differ += !matchTriangles(vtkPolyData::SafeDownCast(own->GetOutputDataObject(0)), ours, 1e-7).identical();
  }
  EXPECT_GT(differ, 100);
}

TEST(ChunkedMarchingCubes, WaveletIsoSurfaceEqualsVtk)
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(-30, 30, -25, 25, -20, 28);
  wavelet->Update();
  // an open surface cut by the volume's boundary: no volume or watertightness claim
  expectSameSurface(wavelet->GetOutput(), "RTData", 157.3, false, 30.0);
}

TEST(ChunkedMarchingCubes, PartitionsCarryChunkIdsAndColourArrays)
{
  const int dims[3] = { 50, 45, 40 };
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  auto img = sampled(dims, origin, spacing, sphere(24.6, 22.3, 19.1, 15.2));
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputData(img);
  mc->SetChunkEdge(16);
  mc->Update();
  auto* pds = vtkPartitionedDataSet::SafeDownCast(mc->GetOutputDataObject(0));
  ASSERT_NE(pds, nullptr);
  ASSERT_GT(pds->GetNumberOfPartitions(), 8u);
  std::set<vtkIdType> ids;
  const vtkIdType counts[3] = { 4, 3, 3 }; // ceil(49/16), ceil(44/16), ceil(39/16)
  for (unsigned int p = 0; p < pds->GetNumberOfPartitions(); ++p)
  {
    auto* pd = vtkPolyData::SafeDownCast(pds->GetPartition(p));
    ASSERT_NE(pd, nullptr);
    ASSERT_GT(pd->GetNumberOfCells(), 0);
    auto* id = vtkIdTypeArray::SafeDownCast(pd->GetFieldData()->GetArray("chunk_id"));
    auto* ijk = vtkIntArray::SafeDownCast(pd->GetFieldData()->GetArray("chunk_ijk"));
    ASSERT_TRUE(id && ijk);
    const int* c = ijk->GetPointer(0);
    EXPECT_EQ(id->GetValue(0), c[0] + counts[0] * (c[1] + counts[1] * c[2]));
    EXPECT_TRUE(ids.insert(id->GetValue(0)).second) << "chunk id twice";
    auto* normals = vtkFloatArray::SafeDownCast(pd->GetPointData()->GetArray("Normals"));
    auto* rgba = vtkUnsignedCharArray::SafeDownCast(pd->GetPointData()->GetArray("rgba"));
    auto* corner = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("corner_rgba"));
    auto* cell = vtkIntArray::SafeDownCast(pd->GetCellData()->GetArray("cell_ijk"));
    ASSERT_TRUE(normals && rgba && corner && cell);
    ASSERT_EQ(corner->GetNumberOfComponents(), 32);
    ASSERT_EQ(cell->GetNumberOfComponents(), 3);
    for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    {
      double x[3], n[3];
      pd->GetPoint(i, x);
      normals->GetTuple(i, n);
      // the sphere's outward normal, and the colour field r = 2x, g = y, b = 3z
      const double d[3] = { x[0] - 24.6, x[1] - 22.3, x[2] - 19.1 };
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      EXPECT_GT((n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / len, 0.99);
      EXPECT_NEAR(rgba->GetComponent(i, 0), 2 * x[0], 1.0);
      EXPECT_NEAR(rgba->GetComponent(i, 1), x[1], 1.0);
      EXPECT_NEAR(rgba->GetComponent(i, 2), 3 * x[2], 1.0);
      EXPECT_EQ(rgba->GetComponent(i, 3), 200);
    }
    for (vtkIdType t = 0; t < pd->GetNumberOfCells(); ++t)
    {
      int g[3];
      cell->GetTypedTuple(t, g);
      // the cell lies in the chunk, and holds the triangle
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_GE(g[a], 16 * c[a]);
        EXPECT_LT(g[a], 16 * (c[a] + 1));
      }
      vtkIdType npts;
      const vtkIdType* pts;
      pd->GetCellPoints(t, npts, pts);
      for (vtkIdType k = 0; k < npts; ++k)
      {
        double x[3];
        pd->GetPoint(pts[k], x);
        for (int a = 0; a < 3; ++a)
        {
          EXPECT_GE(x[a], g[a] - 1e-6);
          EXPECT_LE(x[a], g[a] + 1 + 1e-6);
        }
      }
      for (int q = 0; q < 8; ++q)
      {
        const int p[3] = { g[0] + (q & 1), g[1] + ((q >> 1) & 1), g[2] + ((q >> 2) & 1) };
        const auto* in = static_cast<unsigned char*>(img->GetPointData()->GetArray("rgba")->GetVoidPointer(
          4 * img->ComputePointId(const_cast<int*>(p))));
        for (int ch = 0; ch < 4; ++ch) ASSERT_EQ(corner->GetComponent(t, 4 * q + ch), in[ch]);
      }
    }
  }
}

TEST(ChunkedMarchingCubes, MissingArrayIsAnErrorAndPrintSelfNamesEveryField)
{
  const int dims[3] = { 20, 20, 20 };
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  auto img = sampled(dims, origin, spacing, sphere(9.5, 9.5, 9.5, 5.3));
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputData(img);
  mc->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "nope");
  EXPECT_GE(countErrors(mc), 1);

  mc->SetChunkEdge(23);
  mc->SetIsoValue(0.25);
  mc->SetOutputModeToMerged();
  mc->SetDevice(vtkChunkedMarchingCubes::DEVICE_CPU);
  mc->ComputeNormalsOff();
  std::ostringstream os;
  mc->Print(os);
  for (const char* field : { "OutputMode: Merged", "IsoValue: 0.25", "ChunkEdge: 23", "ComputeNormals: 0",
         "ComputeColors: 1", "ComputeCornerColors: 1", "ColorArrayName: rgba", "Device: Cpu", "UseVTKCaseTable: 1",
         "Volume: (none)" })
    EXPECT_NE(os.str().find(field), std::string::npos) << field;
}

// An image with a direction matrix (VTK 9: a rotated or flipped grid, e.g. a
// .vti's Direction) was meshed as if axis-aligned: the surface came out
// unrotated, without a word, where VTK's vtkFlyingEdges3D places it by the
// matrix and LVDIF's own image conversions (vtkImageToSparseVolume, the
// writers) refuse it. Now one error naming the matrix (the bridge's one check,
// LVDIFVolumeBridge::RequireAxisAligned) and no triangles; the same image
// without the rotation still meshes as vtkFlyingEdges3D does.
TEST(ChunkedMarchingCubes, ARotatedImageIsRefusedNotMeshedUnrotated)
{
  const int dims[3] = { 24, 20, 22 };
  const double origin[3] = { -1, 2, 0.5 }, spacing[3] = { 0.5, 0.5, 0.5 };
  auto img = sampled(dims, origin, spacing, sphere(5.0, 7.0, 6.0, 3.3));
  img->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1); // 90 degrees about z
  vtkNew<vtkFlyingEdges3D> fe;
  auto oracle = reference(fe, img, "sdf", 0.0);
  ASSERT_GT(oracle->GetNumberOfCells(), 0);
  double want[6];
  oracle->GetBounds(want);
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetInputData(img);
  mc->SetOutputModeToMerged();
  std::vector<std::string> messages;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&messages);
  cb->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call));
  });
  mc->AddObserver(vtkCommand::ErrorEvent, cb);
  mc->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, cb);
  mc->Update();
  auto* out = vtkPolyData::SafeDownCast(mc->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  if (out->GetNumberOfCells() > 0)
  {
    double got[6];
    out->GetBounds(got);
    ADD_FAILURE() << "meshed " << out->GetNumberOfCells() << " triangles in x [" << got[0] << ", " << got[1]
                  << "], VTK's surface of the rotated image lies in x [" << want[0] << ", " << want[1] << "]";
  }
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("direction matrix is not the identity (0 -1 0 1 0 0 0 0 1)"), std::string::npos)
    << messages[0];
  img->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  img->Modified();
  auto axisAligned = reference(fe, img, "sdf", 0.0);
  mc->Update();
  EXPECT_EQ(out->GetNumberOfCells(), axisAligned->GetNumberOfCells());
}
