#include "vtkDictionaryVolumeWriter.h"

#include "LVDIFVolumeBridge.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/VolumeFile.h"

#include "vtkObjectFactory.h"

#include <limits>

vtkStandardNewMacro(vtkDictionaryVolumeWriter);

vtkDictionaryVolumeWriter::vtkDictionaryVolumeWriter()
  : CompressionLevel(lvdif::VolumeFileWriteOptions().compressionLevel)
{
}

vtkDictionaryVolumeWriter::~vtkDictionaryVolumeWriter() = default;

lvdif::VolumeOptions vtkDictionaryVolumeWriter::ImageVolumeOptions()
{
  lvdif::VolumeOptions options;
  options.chunkEdge = this->ChunkEdge;
  options.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
  return options;
}

void vtkDictionaryVolumeWriter::CheckSettings()
{
  lvdif::checkCompressionLevel(this->CompressionLevel, "CompressionLevel");
}

void vtkDictionaryVolumeWriter::Save(
  const lvdif::DictionaryVolume& volume, const SaveSource& source, lvdif::Interrupter& interrupter)
{
  lvdif::VolumeFileWriteOptions writeOptions;
  writeOptions.compressionLevel = this->CompressionLevel;
  writeOptions.metadata = this->Metadata;
  if (!this->VolumeName.empty())
  {
    writeOptions.metadata["name"] = this->VolumeName;
  }
  if (source.fromImage)
  {
    writeOptions.metadata["creation parameters"] =
      "vtkDictionaryVolumeWriter band " + std::to_string(this->BandWidth) + " chunk " + std::to_string(this->ChunkEdge);
  }
  lvdif::saveVolume(volume, this->FileName, writeOptions, interrupter);
}

void vtkDictionaryVolumeWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeName: " << this->VolumeName << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "CompressionLevel: " << this->CompressionLevel << "\n";
}
