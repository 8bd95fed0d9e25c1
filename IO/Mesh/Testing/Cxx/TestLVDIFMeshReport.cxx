// vtkLVDIFMeshReport on tiny hand-made meshes whose counts were worked out by
// hand (in the comments): a closed tetrahedron, two separate pieces, a fin
// (three faces on one edge), a bowtie (two fans at one vertex), duplicated
// and degenerate faces, and a seam closed by welding.
#include "vtkLVDIFMeshReport.h"

#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkPolyData> makeMesh(
  const std::vector<std::array<double, 3>>& pts, const std::vector<std::array<vtkIdType, 3>>& tris)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (const auto& p : pts)
    points->InsertNextPoint(p.data());
  vtkNew<vtkCellArray> cells;
  for (const auto& t : tris)
    cells->InsertNextCell(3, t.data());
  pd->SetPoints(points);
  pd->SetPolys(cells);
  return pd;
}

using Counts = std::map<std::string, vtkIdType>;

Counts run(vtkPolyData* pd, bool weld = false, double tol = 1e-6, vtkIdType* outPoints = nullptr,
  std::string* summary = nullptr)
{
  vtkNew<vtkLVDIFMeshReport> report;
  report->SetInputData(pd);
  report->SetWeld(weld);
  report->SetWeldTolerance(tol);
  report->Update();
  Counts c;
  vtkFieldData* fd = report->GetOutput()->GetFieldData();
  for (const char* name : { "BoundaryEdges", "NonManifoldEdges", "NonManifoldVertices", "RefusedFaces",
         "DuplicatedFaces", "DegenerateFaces", "ConnectedComponents", "WeldedVertices" })
  {
    auto* a = vtkIdTypeArray::SafeDownCast(fd->GetAbstractArray(name));
    EXPECT_NE(a, nullptr) << name;
    c[name] = a ? a->GetValue(0) : -1;
  }
  if (outPoints)
    *outPoints = report->GetOutput()->GetNumberOfPoints();
  if (summary)
  {
    *summary = report->GetSummary();
    auto* s = vtkStringArray::SafeDownCast(fd->GetAbstractArray("MeshReport"));
    EXPECT_NE(s, nullptr);
    if (s)
      EXPECT_EQ(s->GetValue(0), *summary);
  }
  return c;
}

const std::vector<std::array<double, 3>> Tet = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
const std::vector<std::array<vtkIdType, 3>> TetFaces = { { 0, 2, 1 }, { 0, 1, 3 }, { 1, 2, 3 }, { 0, 3, 2 } };
} // namespace

TEST(LVDIFMeshReport, ClosedTetrahedronIsClean)
{
  std::string summary;
  const Counts c = run(makeMesh(Tet, TetFaces), false, 0, nullptr, &summary);
  EXPECT_EQ(c.at("BoundaryEdges"), 0);
  EXPECT_EQ(c.at("NonManifoldEdges"), 0);
  EXPECT_EQ(c.at("NonManifoldVertices"), 0);
  EXPECT_EQ(c.at("RefusedFaces"), 0);
  EXPECT_EQ(c.at("DuplicatedFaces"), 0);
  EXPECT_EQ(c.at("DegenerateFaces"), 0);
  EXPECT_EQ(c.at("ConnectedComponents"), 1);
  EXPECT_NE(summary.find("0 boundary edges"), std::string::npos) << summary;
  EXPECT_NE(summary.find("1 connected components"), std::string::npos) << summary;
}

TEST(LVDIFMeshReport, TwoPiecesHaveSevenBoundaryEdges)
{
  // a triangle (3 boundary edges) and a square of two triangles (4 boundary
  // edges, the diagonal is interior)
  const Counts c = run(makeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 5, 0, 0 }, { 6, 0, 0 }, { 6, 1, 0 }, { 5, 1, 0 } },
    { { 0, 1, 2 }, { 3, 4, 5 }, { 3, 5, 6 } }));
  EXPECT_EQ(c.at("BoundaryEdges"), 7);
  EXPECT_EQ(c.at("ConnectedComponents"), 2);
  EXPECT_EQ(c.at("NonManifoldEdges"), 0);
  EXPECT_EQ(c.at("RefusedFaces"), 0);
}

TEST(LVDIFMeshReport, FinHasOneNonManifoldEdgeAndOneRefusal)
{
  // three faces on edge 0-1: the third reuses halfedge 0->1 (a complex edge
  // for OpenMesh). Edges used once: 1-2 2-0 0-3 3-1 1-4 4-0 = 6.
  const Counts c = run(makeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, 1, 0 }, { 0.5, -1, 0 }, { 0.5, 0, 1 } },
    { { 0, 1, 2 }, { 1, 0, 3 }, { 0, 1, 4 } }));
  EXPECT_EQ(c.at("NonManifoldEdges"), 1);
  EXPECT_EQ(c.at("RefusedFaces"), 1);
  EXPECT_EQ(c.at("BoundaryEdges"), 6);
  EXPECT_EQ(c.at("ConnectedComponents"), 1);
}

TEST(LVDIFMeshReport, BowtieHasOneNonManifoldVertex)
{
  // two triangles sharing only vertex 0
  const Counts c = run(makeMesh({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { -1, 0, 0 }, { -1, -1, 0 } },
    { { 0, 1, 2 }, { 0, 3, 4 } }));
  EXPECT_EQ(c.at("NonManifoldVertices"), 1);
  EXPECT_EQ(c.at("NonManifoldEdges"), 0);
  EXPECT_EQ(c.at("RefusedFaces"), 0);
  EXPECT_EQ(c.at("BoundaryEdges"), 6);
  EXPECT_EQ(c.at("ConnectedComponents"), 1);
}

TEST(LVDIFMeshReport, DuplicatedAndDegenerateFacesAreCountedAndSkipped)
{
  // the tetrahedron, plus: face 1 reversed (duplicate), face 2 again in
  // rotated order (duplicate), a face with a repeated corner (degenerate) and
  // a face on three collinear points (degenerate). The rest is closed.
  std::vector<std::array<double, 3>> pts = Tet;
  pts.push_back({ 2, 0, 0 });
  pts.push_back({ 3, 0, 0 });
  pts.push_back({ 4, 0, 0 });
  std::vector<std::array<vtkIdType, 3>> faces = TetFaces;
  faces.push_back({ 3, 1, 0 });
  faces.push_back({ 2, 3, 1 });
  faces.push_back({ 0, 0, 1 });
  faces.push_back({ 4, 5, 6 });
  const Counts c = run(makeMesh(pts, faces));
  EXPECT_EQ(c.at("DuplicatedFaces"), 2);
  EXPECT_EQ(c.at("DegenerateFaces"), 2);
  EXPECT_EQ(c.at("BoundaryEdges"), 0);
  EXPECT_EQ(c.at("NonManifoldEdges"), 0);
  EXPECT_EQ(c.at("RefusedFaces"), 0);
  EXPECT_EQ(c.at("ConnectedComponents"), 1);
}

TEST(LVDIFMeshReport, WeldingClosesASeam)
{
  // two triangles whose shared edge is stored twice, 1e-7 apart
  const std::vector<std::array<double, 3>> pts = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1e-7, 0 },
    { 1e-7, 1, 0 }, { 1, 1, 0 } };
  const std::vector<std::array<vtkIdType, 3>> faces = { { 0, 1, 2 }, { 4, 3, 5 } };
  vtkIdType np = 0;
  Counts c = run(makeMesh(pts, faces), false, 0, &np);
  EXPECT_EQ(c.at("BoundaryEdges"), 6);
  EXPECT_EQ(c.at("ConnectedComponents"), 2);
  EXPECT_EQ(c.at("WeldedVertices"), 0);
  EXPECT_EQ(np, 6);
  c = run(makeMesh(pts, faces), true, 1e-5, &np);
  EXPECT_EQ(c.at("BoundaryEdges"), 4);
  EXPECT_EQ(c.at("ConnectedComponents"), 1);
  EXPECT_EQ(c.at("WeldedVertices"), 2);
  EXPECT_EQ(np, 4);
  // a tolerance below the gap welds nothing
  c = run(makeMesh(pts, faces), true, 1e-8, &np);
  EXPECT_EQ(c.at("WeldedVertices"), 0);
  EXPECT_EQ(c.at("BoundaryEdges"), 6);
}
