#include "vtkVolumeEditFilter.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
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
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  return 1;
}

int vtkVolumeEditFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkVolumeEditFilter::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // sparse in, sparse out; image in, image out
  // without an input the output is an image, so that the executive's input
  // check says what is missing (returning 0 here gave only its cryptic
  // "returned failure for request: REQUEST_DATA_OBJECT")
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (vtkSparseDictionaryVolume::SafeDownCast(input))
  {
    LVDIFVolumeBridge::EnsureSparseOutput(outputVector);
  }
  else if (!vtkImageData::SafeDownCast(outInfo->Get(vtkDataObject::DATA_OBJECT())))
  {
    vtkNew<vtkImageData> image;
    outInfo->Set(vtkDataObject::DATA_OBJECT(), image);
  }
  return 1;
}

int vtkVolumeEditFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkSparseDictionaryVolume* sparseIn = vtkSparseDictionaryVolume::GetData(inputVector[0]);
  vtkSparseDictionaryVolume* sparseOut = vtkSparseDictionaryVolume::GetData(outputVector);
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  this->LastError.clear();
  this->LastErrorLine = this->LastErrorColumn = 0;
  // a failure below is reported once: no executive "returned failure" dump after it
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  LVDIFVolumeBridge::BeginInformation(outInfo);
  if (LVDIFVolumeBridge::IsEmptyInput(vtkDataObject::GetData(inputVector[0])))
  {
    // VTK's rule for an empty input (a failed upstream said why): empty output, no error
    if (vtkDataObject* out = vtkDataObject::GetData(outputVector)) out->Initialize();
    return 1;
  }
  if (!sparseIn && (!input || !output))
  {
    this->LastError = "no input image";
  }
  vtkDataArray* sdf = input ? input->GetPointData()->GetArray(LVDIFVolumeBridge::SdfArrayName) : nullptr;
  vtkDataArray* rgba = input ? input->GetPointData()->GetArray(LVDIFVolumeBridge::ColorArrayName) : nullptr;
  if (this->LastError.empty() && !sparseIn && !sdf)
  {
    this->LastError = "the input has no point array named 'sdf'";
  }
  if (!this->LastError.empty())
  {
    vtkErrorMacro(<< this->LastError);
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  try
  {
    LVDIFInterrupter interrupter(this, 0.0, 0.1);
    lvdif::VolumeOptions o;
    o.chunkEdge = this->ChunkEdge;
    if (!sparseIn) // a sparse input keeps its own band and chunk edge (as the writers')
      o.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    // a sparse input is edited in a copy (as sparse as the input); an image is encoded first
    std::shared_ptr<lvdif::DictionaryVolume> volume = sparseIn
      ? std::shared_ptr<lvdif::DictionaryVolume>(sparseIn->GetVolume()->clone())
      : std::shared_ptr<lvdif::DictionaryVolume>(LVDIFVolumeBridge::VolumeFromImage(input, sdf, rgba, o));
    if (sparseIn) o = volume->options();
    auto editor = std::make_unique<lvdif::Editor>(*volume);
    this->UpdateProgress(0.1);
    if (!this->RecordingFileName.empty())
    {
      interrupter.setStage(0.1, 0.4);
      const lvdif::Recording recording = lvdif::loadRecording(this->RecordingFileName);
      if (!recording.warning.empty()) vtkWarningMacro(<< recording.warning); // a version 1 file
      editor->play(recording, interrupter);
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
    if (sparseOut)
    {
      // every rank edits the whole volume (an edit can reach anywhere), but a
      // piece (pvbatch rank r of n) owns only its block of chunks, by the
      // .lvdv reader's rule: every rank's partitions were the whole volume,
      // and ParaView's Contour over 2 ranks gave every triangle twice
      int owned[6] = { 0, -1, 0, -1, 0, -1 };
      lvdif::VoxelBox region;
      const int kind = LVDIFVolumeBridge::RequestedVoxels(outInfo, volume->options(), owned, region);
      if (kind < 0)
      {
        sparseOut->Initialize(); // a piece without chunks: empty
        return 1;
      }
      sparseOut->SetVolume(volume);
      if (kind == 1)
        sparseOut->SetOwnedChunks(owned);
      sparseOut->SetPartitionColors(sparseIn->GetPartitionColors() && this->WithColor);
    }
    else
    {
      int extent[6];
      for (int i = 0; i < 3; ++i)
      {
        extent[2 * i] = 0;
        extent[2 * i + 1] = static_cast<int>(volume->dims()[i]) - 1;
      }
      LVDIFVolumeBridge::FillImage(*volume, extent, output, this->WithColor);
      // keep the input's extent (the bridge works in the volume's 0-based indices)
      const int* inExt = input->GetExtent();
      if (volume->dims()[0] == inExt[1] - inExt[0] + 1 && volume->dims()[1] == inExt[3] - inExt[2] + 1 &&
        volume->dims()[2] == inExt[5] - inExt[4] + 1)
      {
        output->SetExtent(const_cast<int*>(inExt));
        output->SetOrigin(input->GetOrigin());
      }
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
    vtkDataObject::GetData(outputVector)->Initialize();
    vtkErrorMacro(<< this->LastError);
    return LVDIFVolumeBridge::FailReported(outInfo);
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
