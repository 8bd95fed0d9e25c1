#include "vtkOpenVDBLevelSetWriter.h"

#include "LVDIFOpenVDB.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkOpenVDBLevelSetWriter);

vtkOpenVDBLevelSetWriter::vtkOpenVDBLevelSetWriter() = default;
vtkOpenVDBLevelSetWriter::~vtkOpenVDBLevelSetWriter() = default;

lvdif::VolumeOptions vtkOpenVDBLevelSetWriter::ImageVolumeOptions()
{
  lvdif::VolumeOptions options;
  options.bandWidth = static_cast<float>(this->HalfWidth);
  return options;
}

void vtkOpenVDBLevelSetWriter::Save(
  const lvdif::DictionaryVolume& volume, const SaveSource& source, lvdif::Interrupter& interrupter)
{
  lvdif::vdb::ExportOptions exportOptions;
  exportOptions.halfWidth = this->HalfWidth;
  // an image without an `rgba` array has no colours to write
  exportOptions.withColor = source.fromImage ? source.imageColors != nullptr : this->WithColor;
  exportOptions.sdfName = this->GridName;
  lvdif::vdb::exportLevelSet(volume, this->FileName, exportOptions, interrupter);
}

void vtkOpenVDBLevelSetWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "HalfWidth: " << this->HalfWidth << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
}
