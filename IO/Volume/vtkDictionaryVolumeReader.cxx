#include "vtkDictionaryVolumeReader.h"

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
  std::ifstream f(fileName ? fileName : "", std::ios::binary);
  char magic[8] = {};
  return f.read(magic, 8) && std::memcmp(magic, "LVDIFVOL", 8) == 0;
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
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return 0;
  }
  try
  {
    this->Internal->Info = lvdif::readVolumeInfo(this->FileName);
  }
  catch (const lvdif::Error& e)
  {
    this->Internal->Info = lvdif::VolumeFileInfo();
    vtkErrorMacro(<< "cannot read '" << this->FileName << "': " << e.what());
    return 0;
  }
  const lvdif::VolumeOptions& o = this->Internal->Info.options;
  for (int a = 0; a < 3; ++a)
  {
    if (o.dims[a] > VTK_INT_MAX)
    {
      vtkErrorMacro("volume dimension " << o.dims[a] << " exceeds VTK's extent range");
      return 0;
    }
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  LVDIFVolumeBridge::SetSparseInformation(outInfo, o);
  return 1;
}

int vtkDictionaryVolumeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outInfo);
  lvdif::VolumeFileReadOptions options;
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
  const int piece = outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
  int owned[6] = { 0, -1, 0, -1, 0, -1 };
  if (pieces > 1)
  {
    // A piece is a block of storage chunks (see the header); it reads them and
    // the one layer of points their partitions share with the next chunks.
    if (!LVDIFVolumeBridge::PieceChunks(piece, pieces, this->Internal->Info.options, owned, options.region))
    {
      output->Initialize(); // a piece without chunks: empty
      return 1;
    }
    options.wholeVolume = false;
  }
  else if (outInfo->Has(SDDP::UPDATE_EXTENT()) && outInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    int ext[6], whole[6];
    outInfo->Get(SDDP::UPDATE_EXTENT(), ext);
    outInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    if (!std::equal(ext, ext + 6, whole))
    {
      // a consumer asked for part of the volume: read only its chunks
      options.wholeVolume = false;
      options.region.lo = { ext[0], ext[2], ext[4] };
      options.region.hi = { ext[1], ext[3], ext[5] };
    }
  }
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  output->SetPartitionColors(this->WithColor);
  const bool ok = LVDIFVolumeBridge::CallCore(
    this,
    [&] {
      std::shared_ptr<lvdif::DictionaryVolume> volume = lvdif::loadVolume(this->FileName, options, interrupter);
      output->SetVolume(std::move(volume));
      if (pieces > 1) output->SetOwnedChunks(owned);
    },
    "cannot read '" + this->FileName + "': ");
  if (!ok)
  {
    output->Initialize();
    return 0;
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
