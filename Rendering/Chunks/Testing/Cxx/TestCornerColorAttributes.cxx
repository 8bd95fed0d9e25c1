// Non-rendering checks of vtkCornerColorAttributes: its output arrays against
// the input arrays recomputed in double, its spatial (Morton) order, its typed
// path against its generic one, and its refusal of an input without the
// marching cubes contract. The actor manager's checks are in TestChunkActors.
#include "ChunkTestData.h"

#include "vtkCallbackCommand.h"
#include "vtkCornerColorAttributes.h"
#include "vtkExecutive.h"
#include "vtkIdList.h"
#include "vtkIntArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

using namespace lvdiftest;

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
      float packed[12];
      for (int c = 0; c < 3; ++c)
      {
        vtkDataArray* pa = out->GetPointData()->GetArray(vtkCornerColorAttributes::PackedCornerArrayName(c));
        ASSERT_NE(pa, nullptr);
        for (int q4 = 0; q4 < 4; ++q4)
          packed[4 * c + q4] = static_cast<float>(pa->GetComponent(o[v], q4));
      }
      unsigned char rgba[32];
      vtkCornerColorAttributes::UnpackCorners(packed, rgba);
      for (int c = 0; c < 8; ++c)
      {
        for (int q4 = 0; q4 < 4; ++q4)
        {
          ASSERT_EQ(rgba[4 * c + q4], corners->GetComponent(t, 4 * c + q4));
        }
      }
    }
  }
}

// SpatialOrder: the same triangles (each with its points, local coordinates and
// corner colours, as without it), in non-decreasing Morton order of their cells.
TEST(CornerColorAttributes, SpatialOrderPermutesTrianglesByMortonCode)
{
  auto mesh = sphereMesh(24, 0.5);
  vtkNew<vtkCornerColorAttributes> plain, ordered;
  for (vtkCornerColorAttributes* f : { plain.Get(), ordered.Get() })
  {
    f->SetInputData(mesh);
    f->SetSpacing(0.5, 0.5, 0.5);
  }
  ordered->SpatialOrderOn();
  plain->Update();
  ordered->Update();
  vtkPolyData* a = plain->GetOutput();
  vtkPolyData* b = ordered->GetOutput();
  const vtkIdType nt = mesh->GetNumberOfPolys();
  ASSERT_EQ(b->GetNumberOfPolys(), nt);
  ASSERT_EQ(b->GetNumberOfPoints(), 3 * nt);
  vtkDataArray* ijk = mesh->GetCellData()->GetArray("cell_ijk");
  // each output triangle as the bytes of its three points' position and point arrays
  auto key = [](vtkPolyData* pd, vtkIdType t) {
    vtkIdType n;
    const vtkIdType* ids;
    pd->GetCellPoints(t, n, ids);
    std::vector<double> k;
    for (vtkIdType v = 0; v < n; ++v)
    {
      double x[3];
      pd->GetPoint(ids[v], x);
      k.insert(k.end(), x, x + 3);
      for (int i = 0; i < pd->GetPointData()->GetNumberOfArrays(); ++i)
      {
        vtkDataArray* arr = pd->GetPointData()->GetArray(i);
        for (int c = 0; c < arr->GetNumberOfComponents(); ++c)
          k.push_back(arr->GetComponent(ids[v], c));
      }
    }
    return k;
  };
  std::vector<std::vector<double>> ka, kb;
  for (vtkIdType t = 0; t < nt; ++t)
  {
    ka.push_back(key(a, t));
    kb.push_back(key(b, t));
  }
  // the Morton codes along the output: non-decreasing (the input triangle of
  // each output one found by its points)
  std::map<std::vector<double>, std::vector<vtkIdType>> inputOf;
  for (vtkIdType t = 0; t < nt; ++t)
    inputOf[ka[static_cast<std::size_t>(t)]].push_back(t);
  unsigned long long last = 0;
  bool ordered_ = true, permutation = true;
  for (vtkIdType t = 0; t < nt; ++t)
  {
    auto it = inputOf.find(kb[static_cast<std::size_t>(t)]);
    if (it == inputOf.end() || it->second.empty())
    {
      permutation = false;
      break;
    }
    const vtkIdType in = it->second.back();
    it->second.pop_back();
    const unsigned long long code = vtkCornerColorAttributes::MortonCode(static_cast<int>(ijk->GetComponent(in, 0)),
      static_cast<int>(ijk->GetComponent(in, 1)), static_cast<int>(ijk->GetComponent(in, 2)));
    ordered_ = ordered_ && code >= last;
    last = code;
  }
  EXPECT_TRUE(permutation);
  EXPECT_TRUE(ordered_);
  std::sort(ka.begin(), ka.end());
  std::sort(kb.begin(), kb.end());
  EXPECT_EQ(ka, kb);
  // and the order did change (the scan order of the input is not Morton order)
  bool moved = false;
  for (vtkIdType t = 0; t < nt && !moved; ++t)
    moved = key(a, t) != key(b, t);
  EXPECT_TRUE(moved);
  EXPECT_EQ(vtkCornerColorAttributes::MortonCode(1, 0, 0), 1ull);
  EXPECT_EQ(vtkCornerColorAttributes::MortonCode(0, 1, 0), 2ull);
  EXPECT_EQ(vtkCornerColorAttributes::MortonCode(0, 0, 1), 4ull);
  EXPECT_EQ(vtkCornerColorAttributes::MortonCode(3, 5, 6), 0b110101011ull);
}

namespace
{
// Every output array value and the connectivity of two preparations (same
// point array names in the same order); the first difference, or "".
std::string firstDifference(vtkPolyData* a, vtkPolyData* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() || a->GetNumberOfPolys() != b->GetNumberOfPolys())
    return "sizes";
  for (vtkIdType p = 0; p < a->GetNumberOfPoints(); ++p)
  {
    double x[3], y[3];
    a->GetPoint(p, x);
    b->GetPoint(p, y);
    if (!std::equal(x, x + 3, y))
      return "point " + std::to_string(p);
  }
  if (a->GetPointData()->GetNumberOfArrays() != b->GetPointData()->GetNumberOfArrays())
    return "point array count";
  for (int i = 0; i < a->GetPointData()->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* u = a->GetPointData()->GetArray(i);
    vtkDataArray* v = b->GetPointData()->GetArray(i);
    if (std::string(u->GetName()) != v->GetName() || u->GetDataType() != v->GetDataType() ||
      u->GetNumberOfComponents() != v->GetNumberOfComponents())
      return std::string("array ") + u->GetName();
    for (vtkIdType t = 0; t < u->GetNumberOfTuples(); ++t)
      for (int c = 0; c < u->GetNumberOfComponents(); ++c)
        if (u->GetComponent(t, c) != v->GetComponent(t, c))
          return std::string("array ") + u->GetName() + " tuple " + std::to_string(t);
  }
  if (a->GetPolys()->IsStorage64Bit() != b->GetPolys()->IsStorage64Bit())
    return "cell storage";
  for (vtkIdType t = 0; t < a->GetNumberOfPolys(); ++t)
  {
    vtkNew<vtkIdList> ia, ib;
    a->GetPolys()->GetCellAtId(t, ia);
    b->GetPolys()->GetCellAtId(t, ib);
    if (ia->GetNumberOfIds() != ib->GetNumberOfIds() ||
      !std::equal(ia->begin(), ia->end(), ib->begin()))
      return "triangle " + std::to_string(t);
  }
  return "";
}

vtkSmartPointer<vtkPolyData> prepared(vtkPolyData* mesh, const double origin[3])
{
  vtkNew<vtkCornerColorAttributes> f;
  f->SetInputData(mesh);
  f->SetOrigin(const_cast<double*>(origin));
  f->SetSpacing(0.5, 0.5, 0.5);
  f->SpatialOrderOn();
  f->Update();
  return f->GetOutput();
}
} // namespace

// Marching cubes' meshes (float points, int cell_ijk, triangles only) take the
// filter's typed loops; any other input the generic ones. Both give the same
// output: here the same mesh with double points (the generic path).
TEST(CornerColorAttributes, TypedPathEqualsGenericPath)
{
  auto mesh = sphereMesh(24, 0.5);
  ASSERT_EQ(mesh->GetPoints()->GetDataType(), VTK_FLOAT);
  ASSERT_NE(vtkIntArray::SafeDownCast(mesh->GetCellData()->GetArray("cell_ijk")), nullptr);
  vtkNew<vtkPolyData> asDouble;
  asDouble->ShallowCopy(mesh);
  vtkNew<vtkPoints> dp;
  dp->SetDataTypeToDouble();
  dp->SetNumberOfPoints(mesh->GetNumberOfPoints());
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
    dp->SetPoint(p, mesh->GetPoint(p)); // float values, exact in double
  asDouble->SetPoints(dp);
  ASSERT_EQ(asDouble->GetPoints()->GetDataType(), VTK_DOUBLE);
  const double origin[3] = { 0.25, -1.5, 3.0 };
  auto typed = prepared(mesh, origin);
  auto generic = prepared(asDouble, origin);
  ASSERT_GT(typed->GetNumberOfPolys(), 100);
  EXPECT_EQ(firstDifference(typed, generic), "");
  // the typed path caches its coordinates' ranges: those of the values, as
  // VTK computes them for the generic path's output
  for (int c = 0; c < 3; ++c)
  {
    vtkDataArray* xyz = typed->GetPoints()->GetData();
    double cached[2], computed[2], brute[2] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    xyz->GetRange(cached, c);
    generic->GetPoints()->GetData()->GetRange(computed, c);
    for (vtkIdType t = 0; t < xyz->GetNumberOfTuples(); ++t)
    {
      brute[0] = std::min(brute[0], xyz->GetComponent(t, c));
      brute[1] = std::max(brute[1], xyz->GetComponent(t, c));
    }
    EXPECT_EQ(cached[0], brute[0]);
    EXPECT_EQ(cached[1], brute[1]);
    EXPECT_EQ(cached[0], computed[0]);
    EXPECT_EQ(cached[1], computed[1]);
  }
  // negative control: another origin changes the local coordinates, and the comparison sees it
  const double shifted[3] = { 0.5, -1.5, 3.0 };
  EXPECT_NE(firstDifference(typed, prepared(asDouble, shifted)), "");
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
  vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on
  f->Update();
  // one error, the filter's: the executive's "returned failure for request" dump followed it
  EXPECT_EQ(errors, 1);
  // a bad spacing too
  vtkNew<vtkCornerColorAttributes> g;
  g->SetInputData(empty);
  g->SetSpacing(0, 1, 1);
  errors = 0;
  g->AddObserver(vtkCommand::ErrorEvent, cb);
  g->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, cb);
  g->Update();
  EXPECT_EQ(errors, 1);
}
