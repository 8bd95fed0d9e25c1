#include "vtkLVDIFMeshReader.h"

#include "lvdif/MeshFile.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <cstring>

vtkStandardNewMacro(vtkLVDIFMeshReader);

vtkLVDIFMeshReader::vtkLVDIFMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkLVDIFMeshReader::~vtkLVDIFMeshReader() = default;

bool vtkLVDIFMeshReader::CanReadFile(const char* fileName)
{
  try
  {
    lvdif::meshFormatFromName(fileName ? fileName : "");
    return true;
  }
  catch (const lvdif::Error&)
  {
    return false;
  }
}

int vtkLVDIFMeshReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return 0;
  }
  static const lvdif::MeshFormat formats[] = { lvdif::MeshFormat::Auto, lvdif::MeshFormat::Obj,
    lvdif::MeshFormat::Off, lvdif::MeshFormat::Stl, lvdif::MeshFormat::Ply };
  lvdif::TriangleMesh mesh;
  try
  {
    mesh = lvdif::loadMesh(this->FileName, formats[this->Format]);
  }
  catch (const lvdif::Error& e)
  {
    output->Initialize();
    vtkErrorMacro(<< "cannot read '" << this->FileName << "': " << e.what());
    return 0;
  }
  this->UpdateProgress(0.7);

  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.points.size()));
  std::memcpy(vtkFloatArray::SafeDownCast(points->GetData())->GetPointer(0), mesh.points.data(),
    mesh.points.size() * sizeof(lvdif::Vec3f));
  const vtkIdType n = static_cast<vtkIdType>(mesh.triangles.size());
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(3 * n);
  for (vtkIdType t = 0; t < n; ++t)
  {
    offsets->SetValue(t, 3 * t);
    for (int c = 0; c < 3; ++c)
    {
      connectivity->SetValue(3 * t + c, mesh.triangles[t][c]);
    }
  }
  offsets->SetValue(n, 3 * n);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  output->SetPoints(points);
  output->SetPolys(polys);
  if (!mesh.normals.empty())
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(static_cast<vtkIdType>(mesh.normals.size()));
    std::memcpy(normals->GetPointer(0), mesh.normals.data(), mesh.normals.size() * sizeof(lvdif::Vec3f));
    output->GetPointData()->SetNormals(normals);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkLVDIFMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Format: " << this->Format << "\n";
}
