#include "vtkLVDIFMeshReport.h"

#include "LVDIFMeshCheck.h"
#include "LVDIFVolumeBridge.h"

#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <cmath>

vtkStandardNewMacro(vtkLVDIFMeshReport);

vtkLVDIFMeshReport::vtkLVDIFMeshReport() = default;
vtkLVDIFMeshReport::~vtkLVDIFMeshReport() = default;

namespace
{
void addCount(vtkFieldData* fd, const char* name, std::int64_t value)
{
  vtkNew<vtkIdTypeArray> a;
  a->SetName(name);
  a->InsertNextValue(static_cast<vtkIdType>(value));
  fd->AddArray(a);
}
} // namespace

int vtkLVDIFMeshReport::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->Summary.clear();
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  LVDIFVolumeBridge::BeginInformation(outInfo);
  if (this->Weld && !(std::isfinite(this->WeldTolerance) && this->WeldTolerance >= 0))
  {
    vtkErrorMacro("WeldTolerance must be a finite length >= 0 (world units), not " << this->WeldTolerance);
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  lvdif::TriangleMesh mesh;
  const vtkIdType np = input->GetNumberOfPoints();
  mesh.points.resize(static_cast<std::size_t>(np));
  for (vtkIdType i = 0; i < np; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    mesh.points[i] = { static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]) };
  }
  vtkCellArray* polys = input->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 1; k + 1 < n; ++k) // fan
      mesh.triangles.push_back({ static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[k]),
        static_cast<std::uint32_t>(ids[k + 1]) });
  }
  if (mesh.triangles.empty())
  {
    vtkErrorMacro("the input has no polygons");
    return 0;
  }
  this->UpdateProgress(0.1);
  const lvdif_mesh_check::Report r = lvdif_mesh_check::check(mesh, this->Weld ? this->WeldTolerance : 0.0);
  this->UpdateProgress(0.9);

  if (this->Weld)
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToFloat();
    points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.points.size()));
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      points->SetPoint(static_cast<vtkIdType>(i), mesh.points[i][0], mesh.points[i][1], mesh.points[i][2]);
    vtkNew<vtkCellArray> tris;
    for (const auto& t : mesh.triangles)
    {
      const vtkIdType c[3] = { t[0], t[1], t[2] };
      tris->InsertNextCell(3, c);
    }
    output->SetPoints(points);
    output->SetPolys(tris);
  }
  else
  {
    output->ShallowCopy(input);
  }
  vtkFieldData* fd = output->GetFieldData();
  addCount(fd, "BoundaryEdges", r.boundaryEdges);
  addCount(fd, "NonManifoldEdges", r.nonManifoldEdges);
  addCount(fd, "NonManifoldVertices", r.nonManifoldVertices);
  addCount(fd, "RefusedFaces", r.refusedFaces);
  addCount(fd, "DuplicatedFaces", r.duplicatedFaces);
  addCount(fd, "DegenerateFaces", r.degenerateFaces);
  addCount(fd, "ConnectedComponents", r.components);
  addCount(fd, "WeldedVertices", r.weldedVertices);
  this->Summary = r.summary();
  vtkNew<vtkStringArray> s;
  s->SetName("MeshReport");
  s->InsertNextValue(this->Summary);
  fd->AddArray(s);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkLVDIFMeshReport::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Weld: " << this->Weld << "\n";
  os << indent << "WeldTolerance: " << this->WeldTolerance << "\n";
  os << indent << "Summary: " << this->Summary << "\n";
}
