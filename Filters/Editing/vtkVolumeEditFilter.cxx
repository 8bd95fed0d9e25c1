#include "vtkVolumeEditFilter.h"

#include "vtkLVDIFInterrupter.h"
#include "vtkLVDIFVolumeBridge.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h"

vtkStandardNewMacro(vtkVolumeEditFilter);

vtkVolumeEditFilter::vtkVolumeEditFilter() = default;
vtkVolumeEditFilter::~vtkVolumeEditFilter() = default;

int vtkVolumeEditFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // edits reach anywhere: always work on the whole input
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

int vtkVolumeEditFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  this->LastError.clear();
  this->LastErrorLine = this->LastErrorColumn = 0;
  if (!input || !output)
  {
    this->LastError = "no input image";
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  vtkDataArray* sdf = input->GetPointData()->GetArray("sdf");
  vtkDataArray* rgba = input->GetPointData()->GetArray("rgba");
  if (!sdf)
  {
    this->LastError = "the input has no point array named 'sdf'";
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  try
  {
    vtkLVDIFInterrupter interrupter(this, 0.0, 0.1);
    lvdif::VolumeOptions o;
    o.chunkEdge = this->ChunkEdge;
    o.bandWidth = static_cast<float>(this->BandWidth);
    std::unique_ptr<lvdif::DictionaryVolume> volume = vtkLVDIFVolumeBridge::VolumeFromImage(input, sdf, rgba, o);
    auto editor = std::make_unique<lvdif::Editor>(*volume);
    this->UpdateProgress(0.1);
    if (!this->RecordingFileName.empty())
    {
      interrupter.setStage(0.1, 0.4);
      editor->play(lvdif::loadRecording(this->RecordingFileName), interrupter);
    }
    if (!this->ScriptText.empty())
    {
      interrupter.setStage(0.5, 0.4);
      lvdif::ScriptOptions so;
      so.canvas = o;
      so.interrupter = &interrupter;
      lvdif::ScriptRunner runner(so);
      runner.attach(*editor);
      runner.run(this->ScriptText);
      if (std::unique_ptr<lvdif::DictionaryVolume> made = runner.takeVolume())
      {
        editor.reset();
        volume = std::move(made);
      }
    }
    int extent[6];
    for (int i = 0; i < 3; ++i)
    {
      extent[2 * i] = 0;
      extent[2 * i + 1] = static_cast<int>(volume->dims()[i]) - 1;
    }
    vtkLVDIFVolumeBridge::FillImage(*volume, extent, output, this->WithColor);
    // keep the input's extent (the bridge works in the volume's 0-based indices)
    const int* inExt = input->GetExtent();
    if (volume->dims()[0] == inExt[1] - inExt[0] + 1 && volume->dims()[1] == inExt[3] - inExt[2] + 1 &&
      volume->dims()[2] == inExt[5] - inExt[4] + 1)
    {
      output->SetExtent(const_cast<int*>(inExt));
      output->SetOrigin(input->GetOrigin());
    }
    this->UpdateProgress(1.0);
  }
  catch (const lvdif::ScriptError& e)
  {
    this->LastError = e.what();
    this->LastErrorLine = e.line();
    this->LastErrorColumn = e.column();
  }
  catch (const std::exception& e)
  {
    this->LastError = e.what();
  }
  if (!this->LastError.empty())
  {
    output->Initialize();
    vtkErrorMacro(<< this->LastError);
    return 0;
  }
  return 1;
}

void vtkVolumeEditFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScriptText: " << this->ScriptText.size() << " characters\n";
  os << indent << "RecordingFileName: " << this->RecordingFileName << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}
