#include "vtkOpenVDBLevelSetWriter.h"

#include "LVDIFOpenVDB.h"
#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

vtkStandardNewMacro(vtkOpenVDBLevelSetWriter);

vtkOpenVDBLevelSetWriter::vtkOpenVDBLevelSetWriter() = default;
vtkOpenVDBLevelSetWriter::~vtkOpenVDBLevelSetWriter() = default;

vtkImageData* vtkOpenVDBLevelSetWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkOpenVDBLevelSetWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

void vtkOpenVDBLevelSetWriter::WriteData()
{
  if (auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(this->Superclass::GetInput()))
  {
    // the volume as it is (its band; HalfWidth caps the exported narrow band)
    if (this->FileName.empty() || !sparse->HasVolume())
    {
      vtkErrorMacro(<< (this->FileName.empty() ? "no file name: call SetFileName() first" : "the input holds no volume"));
      this->SetErrorCode(this->FileName.empty() ? vtkErrorCode::NoFileNameError : vtkErrorCode::UnknownError);
      return;
    }
    lvdif::vdb::ExportOptions exportOptions;
    exportOptions.halfWidth = this->HalfWidth;
    exportOptions.withColor = this->WithColor;
    exportOptions.sdfName = this->GridName;
    LVDIFInterrupter interrupter(this);
    if (!LVDIFVolumeBridge::CallCore(
          this, [&] { lvdif::vdb::exportLevelSet(*sparse->GetVolume(), this->FileName, exportOptions, interrupter); },
          "cannot write '" + this->FileName + "': "))
    {
      this->SetErrorCode(vtkErrorCode::UnknownError);
    }
    return;
  }
  vtkImageData* image = this->GetInput();
  vtkDataArray *sdf, *rgba;
  bool missingFileName;
  const std::string problem =
    LVDIFVolumeBridge::WriterInput(image, this->FileName, this->WithColor, sdf, rgba, missingFileName);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    this->SetErrorCode(missingFileName ? vtkErrorCode::NoFileNameError : vtkErrorCode::UnknownError);
    return;
  }
  lvdif::VolumeOptions options;
  options.bandWidth = static_cast<float>(this->HalfWidth);
  lvdif::vdb::ExportOptions exportOptions;
  exportOptions.halfWidth = this->HalfWidth;
  exportOptions.withColor = rgba != nullptr;
  exportOptions.sdfName = this->GridName;
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  try
  {
    interrupter.setStage(0.0, 0.4);
    auto volume = LVDIFVolumeBridge::VolumeFromImage(image, sdf, rgba, options);
    interrupter.setStage(0.4, 0.6);
    lvdif::vdb::exportLevelSet(*volume, this->FileName, exportOptions, interrupter);
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() != lvdif::ErrorCode::Cancelled)
    {
      vtkErrorMacro(<< "cannot write '" << this->FileName << "': " << e.what());
    }
    this->SetErrorCode(e.code() == lvdif::ErrorCode::IoFailure ? vtkErrorCode::CannotOpenFileError
                                                               : vtkErrorCode::UnknownError);
  }
}

void vtkOpenVDBLevelSetWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "HalfWidth: " << this->HalfWidth << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
}
