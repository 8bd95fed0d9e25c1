#include "vtkDictionaryVolumeReader.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>

vtkStandardNewMacro(vtkDictionaryVolumeReader);

struct vtkDictionaryVolumeReader::Internals
{
  lvdif::VolumeFileInfo Info;
};

vtkDictionaryVolumeReader::vtkDictionaryVolumeReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

vtkDictionaryVolumeReader::~vtkDictionaryVolumeReader()
{
  delete this->Internal;
}

bool vtkDictionaryVolumeReader::CanReadFile(const char* fileName)
{
  // the project's file check: a FIFO blocked std::ifstream (ParaView's file
  // dialog asks every reader), a folder opened
  try
  {
    lvdif::FileSource f(fileName ? fileName : "");
    char magic[8] = {};
    if (f.size() < 8)
      return false;
    f.read(0, magic, 8);
    return std::memcmp(magic, "LVDIFVOL", 8) == 0;
  }
  catch (const lvdif::Error&)
  {
    return false;
  }
}

std::string vtkDictionaryVolumeReader::GetMetadata(const std::string& key) const
{
  auto it = this->Internal->Info.metadata.find(key);
  return it == this->Internal->Info.metadata.end() ? std::string() : it->second;
}

int vtkDictionaryVolumeReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkDictionaryVolumeReader::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  LVDIFVolumeBridge::EnsureSparseOutput(out);
  return 1;
}

int vtkDictionaryVolumeReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  try
  {
    this->Internal->Info = lvdif::readVolumeInfo(this->FileName);
  }
  catch (const lvdif::Error& e)
  {
    this->Internal->Info = lvdif::VolumeFileInfo();
    vtkErrorMacro(<< LVDIFVolumeBridge::FileError("read", this->FileName, e.what()));
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  const lvdif::VolumeOptions& o = this->Internal->Info.options;
  for (int a = 0; a < 3; ++a)
  {
    if (o.dims[a] > VTK_INT_MAX)
    {
      vtkErrorMacro("volume dimension " << o.dims[a] << " exceeds VTK's extent range");
      return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
    }
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  LVDIFVolumeBridge::SetSparseInformation(outInfo, o);
  return 1;
}

int vtkDictionaryVolumeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outInfo);
  lvdif::VolumeFileReadOptions options;
  int owned[6] = { 0, -1, 0, -1, 0, -1 };
  // a piece is a block of storage chunks (see the header): it reads them and
  // the one layer of points their partitions share with the next chunks; a
  // smaller update extent reads only its chunks
  const int kind = LVDIFVolumeBridge::RequestedVoxels(outInfo, this->Internal->Info.options, owned, options.region);
  if (kind < 0)
  {
    output->Initialize(); // a piece without chunks: empty
    return 1;
  }
  options.wholeVolume = kind == 0;
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  output->SetPartitionColors(this->WithColor);
  const bool ok = LVDIFVolumeBridge::CallCore(
    this,
    [&] {
      std::shared_ptr<lvdif::DictionaryVolume> volume = lvdif::loadVolume(this->FileName, options, interrupter);
      output->SetVolume(std::move(volume));
      if (kind == 1) output->SetOwnedChunks(owned);
    },
    "cannot read '" + this->FileName + "': ");
  if (!ok)
  {
    output->Initialize();
    return LVDIFVolumeBridge::FailReported(outInfo); // (a cancel: no error, no dump)
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkDictionaryVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
  const auto& d = this->Internal->Info.options.dims;
  os << indent << "Dimensions (after UpdateInformation): " << d[0] << " x " << d[1] << " x " << d[2] << "\n";
}
