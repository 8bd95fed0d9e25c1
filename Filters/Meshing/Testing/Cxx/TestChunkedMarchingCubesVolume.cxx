// vtkChunkedMarchingCubes on an lvdif::DictionaryVolume given with SetVolume
// (no input, no dense copy) against the same filter on the volume's dense
// image (vtkDictionaryVolumeToImage): identical output arrays, byte for byte
// (points, normals, colours, connectivity, cell_ijk, corner_rgba), in merged
// and per-chunk mode, in one piece and in pieces; and the same surface as
// vtkFlyingEdges3D on the dense image. Errors: input and volume both set,
// neither set.
#include "vtkChunkedMarchingCubes.h"

#include "MeshingTestUtil.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDictionaryVolumeToImage.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkPartitionedDataSet.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace meshtest;

namespace
{
/// A torus with two painted regions (three colour keys), storage chunks of 16.
std::shared_ptr<lvdif::DictionaryVolume> paintedTorus()
{
  lvdif::VolumeOptions vo;
  vo.dims = { 61, 54, 37 };
  vo.chunkEdge = 16;
  vo.origin = { -2.5, 1.25, 0.5 };
  vo.spacing = { 0.5, 0.75, 1.0 };
  auto v = std::make_shared<lvdif::DictionaryVolume>(vo);
  lvdif::fillFromFunction(*v, [](double x, double y, double z) {
    const double q = std::sqrt((x - 30.2) * (x - 30.2) + (y - 26.9) * (y - 26.9)) - 17.3;
    return static_cast<float>(std::sqrt(q * q + (z - 18.4) * (z - 18.4)) - 7.1);
  });
  const lvdif::ColorKey red = v->colors().add(lvdif::Rgba{ 250, 10, 10, 255 });
  const lvdif::ColorKey blue = v->colors().add(lvdif::Rgba{ 10, 20, 240, 128 });
  for (std::int64_t z = 0; z < vo.dims[2]; ++z)
    for (std::int64_t y = 0; y < vo.dims[1]; ++y)
      for (std::int64_t x = 0; x < vo.dims[0]; ++x)
      {
        if (x < 25 && y < 30)
        {
          lvdif::Voxel w = v->get(x, y, z);
          w.color = (x + z) % 3 ? red : blue;
          v->set(x, y, z, w);
        }
      }
  return v;
}

vtkDataObject* runVolume(vtkChunkedMarchingCubes* mc, std::shared_ptr<lvdif::DictionaryVolume> v, int edge, int mode,
  int piece = 0, int pieces = 1)
{
  mc->SetVolume(std::move(v));
  mc->SetChunkEdge(edge);
  mc->SetOutputMode(mode);
  mc->UpdatePiece(piece, pieces, 0);
  return mc->GetOutputDataObject(0);
}

vtkDataObject* runImage(vtkChunkedMarchingCubes* mc, vtkDictionaryVolumeToImage* src, int edge, int mode,
  int piece = 0, int pieces = 1)
{
  mc->SetInputConnection(src->GetOutputPort());
  mc->SetChunkEdge(edge);
  mc->SetOutputMode(mode);
  mc->UpdatePiece(piece, pieces, 0);
  return mc->GetOutputDataObject(0);
}

void expectSameArray(vtkDataArray* a, vtkDataArray* b, const char* what)
{
  ASSERT_EQ(a == nullptr, b == nullptr) << what;
  if (!a) return;
  ASSERT_EQ(a->GetDataType(), b->GetDataType()) << what;
  ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents()) << what;
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << what;
  const std::size_t bytes =
    static_cast<std::size_t>(a->GetNumberOfValues()) * static_cast<std::size_t>(a->GetDataTypeSize());
  EXPECT_EQ(std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0), bytes), 0) << what << " differs";
}

void expectSamePolyData(vtkPolyData* a, vtkPolyData* b)
{
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  ASSERT_EQ(a->GetNumberOfCells(), b->GetNumberOfCells());
  if (a->GetNumberOfPoints() == 0) return;
  expectSameArray(a->GetPoints()->GetData(), b->GetPoints()->GetData(), "points");
  expectSameArray(a->GetPolys()->GetConnectivityArray(), b->GetPolys()->GetConnectivityArray(), "connectivity");
  expectSameArray(a->GetPolys()->GetOffsetsArray(), b->GetPolys()->GetOffsetsArray(), "offsets");
  for (const char* name : { "Normals", "rgba" })
    expectSameArray(a->GetPointData()->GetArray(name), b->GetPointData()->GetArray(name), name);
  for (const char* name : { "cell_ijk", "corner_rgba" })
    expectSameArray(a->GetCellData()->GetArray(name), b->GetCellData()->GetArray(name), name);
  for (const char* name : { "chunk_id", "chunk_ijk" })
    expectSameArray(a->GetFieldData()->GetArray(name), b->GetFieldData()->GetArray(name), name);
}

void expectSameOutput(vtkDataObject* a, vtkDataObject* b)
{
  if (auto* pa = vtkPolyData::SafeDownCast(a))
  {
    expectSamePolyData(pa, vtkPolyData::SafeDownCast(b));
    return;
  }
  auto* da = vtkPartitionedDataSet::SafeDownCast(a);
  auto* db = vtkPartitionedDataSet::SafeDownCast(b);
  ASSERT_TRUE(da && db);
  ASSERT_EQ(da->GetNumberOfPartitions(), db->GetNumberOfPartitions());
  for (unsigned int i = 0; i < da->GetNumberOfPartitions(); ++i)
  {
    SCOPED_TRACE("partition " + std::to_string(i));
    expectSamePolyData(vtkPolyData::SafeDownCast(da->GetPartition(i)), vtkPolyData::SafeDownCast(db->GetPartition(i)));
  }
}

} // namespace

TEST(ChunkedMarchingCubesVolume, VolumeEqualsItsDenseImage)
{
  auto v = paintedTorus();
  vtkNew<vtkDictionaryVolumeToImage> src;
  src->SetVolume(v);
  for (int edge : { 16, 23, 32 })
    for (int mode : { vtkChunkedMarchingCubes::MERGED, vtkChunkedMarchingCubes::PARTITIONED })
    {
      SCOPED_TRACE("chunk edge " + std::to_string(edge) + (mode ? " merged" : " partitioned"));
      vtkNew<vtkChunkedMarchingCubes> a, b;
      vtkDataObject* va = runVolume(a, v, edge, mode);
      vtkDataObject* vb = runImage(b, src, edge, mode);
      expectSameOutput(va, vb);
      if (mode == vtkChunkedMarchingCubes::MERGED)
      {
        auto* pd = vtkPolyData::SafeDownCast(va);
        ASSERT_GT(pd->GetNumberOfCells(), 1000);
        EXPECT_EQ(openEdges(pd), 0);
        EXPECT_GT(measure(pd).volume, 0);
        // the painted colours reach the corner colours (not all default grey)
        auto* corner = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("corner_rgba"));
        ASSERT_NE(corner, nullptr);
        int red = 0;
        for (vtkIdType t = 0; t < corner->GetNumberOfTuples(); ++t) red += corner->GetValue(32 * t) == 250;
        EXPECT_GT(red, 10);
      }
    }
}

TEST(ChunkedMarchingCubesVolume, VolumePiecesEqualImagePiecesAndVtk)
{
  auto v = paintedTorus();
  vtkNew<vtkDictionaryVolumeToImage> src;
  src->SetVolume(v);
  vtkNew<vtkAppendPolyData> all;
  for (int piece = 0; piece < 3; ++piece)
  {
    SCOPED_TRACE("piece " + std::to_string(piece));
    vtkNew<vtkChunkedMarchingCubes> a, b;
    vtkDataObject* va = runVolume(a, v, 16, vtkChunkedMarchingCubes::MERGED, piece, 3);
    vtkDataObject* vb = runImage(b, src, 16, vtkChunkedMarchingCubes::MERGED, piece, 3);
    expectSameOutput(va, vb);
    auto copy = vtkSmartPointer<vtkPolyData>::New();
    copy->DeepCopy(vtkPolyData::SafeDownCast(va));
    EXPECT_GT(copy->GetNumberOfCells(), 0);
    all->AddInputData(copy);
  }
  all->Update();
  vtkSmartPointer<vtkPolyData> ours = mergeByPosition(all->GetOutput());
  EXPECT_EQ(openEdges(ours), 0);
  // the union of the pieces is vtkFlyingEdges3D's surface on the dense image
  src->Update();
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputConnection(src->GetOutputPort());
  fe->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  fe->SetValue(0, 0.0);
  fe->ComputeNormalsOff();
  fe->ComputeScalarsOff();
  fe->Update();
  vtkSmartPointer<vtkPolyData> ref = mergeByPosition(fe->GetOutput());
  const TriangleMatch tm = matchTriangles(ours, ref, 1e-6 * 45.0);
  EXPECT_TRUE(tm.identical()) << "unmatched points " << tm.unmatchedPoints << ", triangles only ours " << tm.onlyInA
                              << ", only VTK's " << tm.onlyInB;
  const Measures m = measure(ours), q = measure(ref);
  EXPECT_EQ(m.triangles, q.triangles);
  EXPECT_NEAR(m.area, q.area, 1e-5 * q.area);
  EXPECT_NEAR(std::abs(m.volume), std::abs(q.volume), 1e-5 * std::abs(q.volume));
}

TEST(ChunkedMarchingCubesVolume, EditThenModifiedIsSeen)
{
  auto v = paintedTorus();
  vtkNew<vtkChunkedMarchingCubes> mc;
  auto* before = vtkPolyData::SafeDownCast(runVolume(mc, v, 16, vtkChunkedMarchingCubes::MERGED));
  const vtkIdType n0 = before->GetNumberOfCells();
  // carve a hole through the tube's wall: more surface after Modified()
  for (std::int64_t z = 15; z < 22; ++z)
    for (std::int64_t y = 24; y < 30; ++y)
      for (std::int64_t x = 8; x < 20; ++x) v->setSdf(x, y, z, 3.0f);
  mc->Modified();
  mc->Update();
  EXPECT_NE(vtkPolyData::SafeDownCast(mc->GetOutputDataObject(0))->GetNumberOfCells(), n0);
}

TEST(ChunkedMarchingCubesVolume, InputAndVolumeTogetherOrNeitherIsAnError)
{
  auto v = paintedTorus();
  vtkNew<vtkDictionaryVolumeToImage> src;
  src->SetVolume(v);
  vtkNew<vtkChunkedMarchingCubes> both;
  both->SetInputConnection(src->GetOutputPort());
  both->SetVolume(v);
  EXPECT_GE(countErrors(both), 1);
  vtkNew<vtkChunkedMarchingCubes> neither;
  EXPECT_GE(countErrors(neither), 1);
}
