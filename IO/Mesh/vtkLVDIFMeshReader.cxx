#include "vtkLVDIFMeshReader.h"

#include "LVDIFVolumeBridge.h"

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
  // the reader reads in RequestData: its failure is reported once here, and the
  // executive's "returned failure" dump of it dropped (FailReported)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  LVDIFVolumeBridge::BeginInformation(outInfo);
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  static const lvdif::MeshFormat formats[] = { lvdif::MeshFormat::Auto, lvdif::MeshFormat::Obj,
    lvdif::MeshFormat::Off, lvdif::MeshFormat::Stl, lvdif::MeshFormat::Ply };
  lvdif::TriangleMesh mesh;
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        LVDIFVolumeBridge::EnumOption(this->Format, "Format", { "auto", "OBJ", "OFF", "STL", "PLY" });
      }))
  {
    output->Initialize();
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  try
  {
    mesh = lvdif::loadMesh(this->FileName, formats[this->Format]);
  }
  catch (const lvdif::Error& e)
  {
    output->Initialize();
    vtkErrorMacro(<< LVDIFVolumeBridge::FileError("read", this->FileName, e.what()));
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  this->UpdateProgress(0.7);

  output->ShallowCopy(LVDIFVolumeBridge::ToPolyData(mesh));
  this->UpdateProgress(1.0);
  return 1;
}

void vtkLVDIFMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Format: " << this->Format << "\n";
}
