#include "vtkDictionaryVolumeWriter.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/VolumeFile.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <limits>

vtkStandardNewMacro(vtkDictionaryVolumeWriter);

vtkDictionaryVolumeWriter::vtkDictionaryVolumeWriter()
  : CompressionLevel(lvdif::VolumeFileWriteOptions().compressionLevel)
{
}

vtkDictionaryVolumeWriter::~vtkDictionaryVolumeWriter() = default;

vtkImageData* vtkDictionaryVolumeWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkDictionaryVolumeWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

void vtkDictionaryVolumeWriter::WriteData()
{
  if (auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(this->Superclass::GetInput()))
  {
    this->WriteSparse(sparse);
    return;
  }
  vtkImageData* image = this->GetInput();
  vtkDataArray *sdf, *rgba;
  bool missingFileName;
  const std::string problem =
    LVDIFVolumeBridge::WriterInput(image, this->FileName, true, sdf, rgba, missingFileName);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    this->SetErrorCode(missingFileName ? vtkErrorCode::NoFileNameError : vtkErrorCode::UnknownError);
    return;
  }
  lvdif::VolumeOptions options;
  options.chunkEdge = this->ChunkEdge;
  options.bandWidth = this->BandWidth >= std::numeric_limits<float>::max()
    ? std::numeric_limits<float>::infinity()
    : static_cast<float>(this->BandWidth);
  lvdif::VolumeFileWriteOptions writeOptions;
  writeOptions.compressionLevel = this->CompressionLevel;
  writeOptions.metadata = this->Metadata;
  if (!this->VolumeName.empty())
  {
    writeOptions.metadata["name"] = this->VolumeName;
  }
  writeOptions.metadata["creation parameters"] =
    "vtkDictionaryVolumeWriter band " + std::to_string(this->BandWidth) + " chunk " + std::to_string(this->ChunkEdge);
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  try
  {
    interrupter.setStage(0.0, 0.3);
    auto volume = LVDIFVolumeBridge::VolumeFromImage(image, sdf, rgba, options);
    interrupter.setStage(0.3, 0.7);
    lvdif::saveVolume(*volume, this->FileName, writeOptions, interrupter);
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

void vtkDictionaryVolumeWriter::WriteSparse(vtkSparseDictionaryVolume* sparse)
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  if (!sparse->HasVolume())
  {
    vtkErrorMacro("the input sparse volume holds no dictionary volume");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  lvdif::VolumeFileWriteOptions writeOptions;
  writeOptions.compressionLevel = this->CompressionLevel;
  writeOptions.metadata = this->Metadata;
  if (!this->VolumeName.empty())
  {
    writeOptions.metadata["name"] = this->VolumeName;
  }
  LVDIFInterrupter interrupter(this);
  bool cancelled = false;
  if (!LVDIFVolumeBridge::CallCore(
        this, [&] { lvdif::saveVolume(*sparse->GetVolume(), this->FileName, writeOptions, interrupter); },
        "cannot write '" + this->FileName + "': ", &cancelled))
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
  }
}

void vtkDictionaryVolumeWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "VolumeName: " << this->VolumeName << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "CompressionLevel: " << this->CompressionLevel << "\n";
}
