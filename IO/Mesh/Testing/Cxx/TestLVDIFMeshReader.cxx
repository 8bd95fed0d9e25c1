// vtkLVDIFMeshReader against VTK's own vtkOBJReader and vtkPLYReader (same
// points, same triangles), polygons as triangles, and bad files as one error with
// the core's message and an empty output.
#include "vtkLVDIFMeshReader.h"

#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <unistd.h>

namespace
{
std::string tempFile(const char* name)
{
  return ::testing::TempDir() + "lvdif_mesh_" + std::to_string(::getpid()) + "_" + name;
}

std::string write(const char* name, const std::string& text)
{
  const std::string path = tempFile(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// An irregular closed tetrahedron-like mesh plus a stray triangle, as OBJ and ASCII PLY.
const char* OBJ = "# test\nv 0 0 0\nv 1.5 0 0.25\nv 0 2 0\nv 0.1 0.2 3\nv -1 -1 -1\n"
                  "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 5 1 2\n";
const char* PLY = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 5\nproperty list uchar int vertex_indices\nend_header\n"
                  "0 0 0\n1.5 0 0.25\n0 2 0\n0.1 0.2 3\n-1 -1 -1\n"
                  "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n3 4 0 1\n";

void expectSame(vtkPolyData* a, vtkPolyData* b)
{
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  ASSERT_EQ(a->GetNumberOfPolys(), b->GetNumberOfPolys());
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(p[c], q[c]) << "point " << i;
  }
  vtkNew<vtkIdList> ca, cb;
  a->GetPolys()->InitTraversal();
  b->GetPolys()->InitTraversal();
  while (a->GetPolys()->GetNextCell(ca))
  {
    ASSERT_TRUE(b->GetPolys()->GetNextCell(cb));
    ASSERT_EQ(ca->GetNumberOfIds(), cb->GetNumberOfIds());
    for (vtkIdType k = 0; k < ca->GetNumberOfIds(); ++k)
      EXPECT_EQ(ca->GetId(k), cb->GetId(k));
  }
}

struct ErrorCatcher : vtkCommand
{
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Last += static_cast<const char*>(data);
  }
  int Count = 0;
  std::string Last;
};
} // namespace

TEST(LVDIFMeshReader, ObjMatchesVtkOBJReader)
{
  const std::string path = write("a.obj", OBJ);
  vtkNew<vtkLVDIFMeshReader> ours;
  ours->SetFileName(path.c_str());
  ours->Update();
  vtkNew<vtkOBJReader> vtk;
  vtk->SetFileName(path.c_str());
  vtk->Update();
  expectSame(ours->GetOutput(), vtk->GetOutput());
  std::remove(path.c_str());
}

TEST(LVDIFMeshReader, PlyMatchesVtkPLYReader)
{
  const std::string path = write("a.ply", PLY);
  vtkNew<vtkLVDIFMeshReader> ours;
  ours->SetFileName(path.c_str());
  ours->Update();
  vtkNew<vtkPLYReader> vtk;
  vtk->SetFileName(path.c_str());
  vtk->Update();
  expectSame(ours->GetOutput(), vtk->GetOutput());
  std::remove(path.c_str());
}

TEST(LVDIFMeshReader, PolygonsBecomeTriangles)
{
  const std::string path = write("quad.off", "OFF\n5 1 0\n0 0 0\n1 0 0\n1 1 0\n0.5 1.5 0\n0 1 0\n5 0 1 2 3 4\n");
  vtkNew<vtkLVDIFMeshReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  EXPECT_EQ(r->GetOutput()->GetNumberOfPoints(), 5);
  EXPECT_EQ(r->GetOutput()->GetNumberOfPolys(), 3);
  std::remove(path.c_str());
}

TEST(LVDIFMeshReader, BadFilesGiveTheCoreMessageAndNoMesh)
{
  struct Case
  {
    const char* name;
    const char* text;
    const char* message;
  };
  const Case cases[] = {
    { "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "out of range" },
    { "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "index 0" },
    { "nan.obj", "v 0 nan 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "NaN" },
    { "two.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "a face needs at least 3 vertices, this one has 2" },
    { "neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "out of range" },
    { "huge.off", "OFF\n2000000000 1 0\n0 0 0\n", "cannot fit" },
    { "empty.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n",
      "no triangles" },
  };
  for (const Case& c : cases)
  {
    const std::string path = write(c.name, c.text);
    vtkNew<ErrorCatcher> catcher;
    vtkNew<vtkLVDIFMeshReader> r;
    r->AddObserver(vtkCommand::ErrorEvent, catcher);
    r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
    r->SetFileName(path.c_str());
    r->Update();
    EXPECT_GE(catcher->Count, 1) << c.name;
    EXPECT_NE(catcher->Last.find(c.message), std::string::npos) << c.name << ": " << catcher->Last;
    EXPECT_EQ(r->GetOutput()->GetNumberOfPoints(), 0) << c.name;
    std::remove(path.c_str());
  }
  EXPECT_TRUE(vtkLVDIFMeshReader::CanReadFile("x.PLY"));
  EXPECT_FALSE(vtkLVDIFMeshReader::CanReadFile("x.vtk"));
}
