#include "vtkLVDIFVolumeWriter.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/ByteStream.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

vtkLVDIFVolumeWriter::vtkLVDIFVolumeWriter() = default;
vtkLVDIFVolumeWriter::~vtkLVDIFVolumeWriter() = default;

vtkImageData* vtkLVDIFVolumeWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkLVDIFVolumeWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

std::unique_ptr<lvdif::DictionaryVolume> vtkLVDIFVolumeWriter::ImageToVolume(
  vtkImageData* image, vtkDataArray* sdf, vtkDataArray* rgba)
{
  return LVDIFVolumeBridge::VolumeFromImage(image, sdf, rgba, this->ImageVolumeOptions());
}

bool vtkLVDIFVolumeWriter::UpdateWholeInput(vtkWriter* writer)
{
  // vtkWriter::Write ignores a failed RequestInformation upstream (a reader's
  // error then comes twice) and answers by the writer's error code alone,
  // which stays NoError when WriteData never ran
  auto* exec = vtkStreamingDemandDrivenPipeline::SafeDownCast(writer->GetExecutive());
  writer->Modified(); // always write, even if the data did not change
  return exec && exec->UpdateInformation() && exec->UpdateWholeExtent();
}

bool vtkLVDIFVolumeWriter::CheckTarget()
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return false;
  }
  try
  {
    lvdif::requireWritable(this->FileName); // before the work, as the CLI
    this->CheckSettings();
    return true;
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< LVDIFVolumeBridge::FileError("write", this->FileName, e.what()));
    this->SetErrorCode(
      e.code() == lvdif::ErrorCode::IoFailure ? vtkErrorCode::CannotOpenFileError : vtkErrorCode::UnknownError);
    return false;
  }
}

bool vtkLVDIFVolumeWriter::CheckInputGrid()
{
  vtkInformation* inInfo = this->GetInputInformation(0, 0);
  if (!inInfo || !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    return true; // nothing announced: the save checks the volume
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  const std::int64_t dims[3] = { std::int64_t(whole[1]) - whole[0] + 1, std::int64_t(whole[3]) - whole[2] + 1,
    std::int64_t(whole[5]) - whole[4] + 1 };
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
    return true; // an empty input: WriteData refuses it
  double spacing[3];
  if (inInfo->Has(vtkDataObject::SPACING()))
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  try
  {
    this->CheckGrid(dims, inInfo->Has(vtkDataObject::SPACING()) ? spacing : nullptr);
    return true;
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< LVDIFVolumeBridge::FileError("write", this->FileName, e.what()));
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return false;
  }
}

int vtkLVDIFVolumeWriter::Write()
{
  if (this->GetNumberOfInputConnections(0) < 1)
    return this->Superclass::Write(); // VTK's "No input provided!"
  this->SetErrorCode(vtkErrorCode::NoError);
  // the place and the settings before the input is brought up to date: a
  // writer to a missing folder ran the whole pipeline (a mesh's conversion
  // upstream: minutes) and only then said the folder was missing
  if (!this->CheckTarget())
    return 0;
  // what the format cannot hold, from the input's information pass (cheap):
  // a non-cubic volume into a .bv ran the whole pipeline above the writer first
  auto* exec = vtkStreamingDemandDrivenPipeline::SafeDownCast(this->GetExecutive());
  if (!exec || !exec->UpdateInformation())
  {
    if (this->GetErrorCode() == vtkErrorCode::NoError)
      this->SetErrorCode(vtkErrorCode::UnknownError); // (the input's own error says why)
    return 0;
  }
  if (!this->CheckInputGrid())
    return 0;
  this->Cancelled = false;
  if (!UpdateWholeInput(this) && this->GetErrorCode() == vtkErrorCode::NoError)
    this->SetErrorCode(vtkErrorCode::UnknownError);
  // a cancel is no error, but nothing was written: 0 (it answered 1, and the
  // caller took the old file, or none, for the volume it had asked for)
  return this->GetErrorCode() == vtkErrorCode::NoError && !this->Cancelled ? 1 : 0;
}

void vtkLVDIFVolumeWriter::WriteData()
{
  auto fail = [this](const std::string& what, unsigned long code) {
    vtkErrorMacro(<< what);
    this->SetErrorCode(code);
  };
  if (!this->CheckTarget())
    return; // (ParaView's writers run WriteData through the executive, not Write)
  vtkSparseDictionaryVolume* sparse = vtkSparseDictionaryVolume::SafeDownCast(this->Superclass::GetInput());
  vtkImageData* image = this->GetInput();
  vtkDataArray* sdf = image ? image->GetPointData()->GetArray(LVDIFVolumeBridge::SdfArrayName) : nullptr;
  if (sparse && !sparse->HasVolume())
    return fail("the input sparse volume holds no dictionary volume", vtkErrorCode::UnknownError);
  if (!sparse && !sdf)
    return fail("the input has no point array named 'sdf'", vtkErrorCode::UnknownError);
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  try
  {
    if (sparse)
    {
      this->Save(*sparse->GetVolume(), SaveSource(), interrupter);
      return;
    }
    SaveSource source;
    source.fromImage = true;
    source.imageColors =
      this->ReadsImageColors() ? image->GetPointData()->GetArray(LVDIFVolumeBridge::ColorArrayName) : nullptr;
    interrupter.setStage(0.0, 0.3);
    const std::unique_ptr<lvdif::DictionaryVolume> volume = this->ImageToVolume(image, sdf, source.imageColors);
    interrupter.setStage(0.3, 1.0);
    this->Save(*volume, source, interrupter);
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() == lvdif::ErrorCode::Cancelled)
    {
      this->Cancelled = true; // AbortExecute: not an error, but Write() answers 0
      return;
    }
    fail(LVDIFVolumeBridge::FileError("write", this->FileName, e.what()),
      e.code() == lvdif::ErrorCode::IoFailure ? vtkErrorCode::CannotOpenFileError : vtkErrorCode::UnknownError);
  }
}

void vtkLVDIFVolumeWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
