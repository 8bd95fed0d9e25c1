#include "vtkOpenVDBLevelSetWriter.h"

#include "LVDIFOpenVDB.h"

#include "lvdif/CNumbers.h"
#include "lvdif/DictionaryVolume.h"

#include "vtkObjectFactory.h"

#include <string>

vtkStandardNewMacro(vtkOpenVDBLevelSetWriter);

vtkOpenVDBLevelSetWriter::vtkOpenVDBLevelSetWriter() = default;
vtkOpenVDBLevelSetWriter::~vtkOpenVDBLevelSetWriter() = default;

void vtkOpenVDBLevelSetWriter::CheckSettings()
{
  lvdif::vdb::checkHalfWidth(this->HalfWidth, "HalfWidth");
}

void vtkOpenVDBLevelSetWriter::CheckGrid(const std::int64_t*, const double* spacing)
{
  if (spacing)
    lvdif::vdb::checkExportSpacing(spacing);
}

lvdif::VolumeOptions vtkOpenVDBLevelSetWriter::ImageVolumeOptions()
{
  lvdif::VolumeOptions options;
  options.bandWidth = static_cast<float>(this->HalfWidth > 0 ? this->HalfWidth : lvdif::vdb::DefaultHalfWidth);
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
  lvdif::vdb::checkExport(volume, exportOptions); // a refused volume gets no warning first
  // a band narrower than asked (0 asks for the volume's own), said once
  const double asked = this->HalfWidth > 0 ? this->HalfWidth : volume.bandWidth();
  const double written = lvdif::vdb::exportHalfWidth(volume, this->HalfWidth);
  if (written != asked)
  {
    const auto number = [](double v) {
      char text[40];
      lvdif::formatDoubleC(text, sizeof text, "%g", v);
      return std::string(text);
    };
    const std::string what =
      this->HalfWidth > 0 ? "HalfWidth " + number(asked) + " voxels" : std::string("the volume's band (unlimited)");
    vtkWarningMacro(<< "'" << this->FileName << "': " << what << " is written as a narrow band of "
                    << number(written) << " voxels ("
                    << (this->HalfWidth > 0 ? "the volume's band: distances beyond it are not stored"
                                            : "OpenVDB's default: a level set's background is finite; set HalfWidth for another")
                    << ")");
  }
  if (lvdif::vdb::exportLevelSet(volume, this->FileName, exportOptions, interrupter) == 0)
  {
    // valid OpenVDB, but probably not what was wanted: it was written without a word,
    // and reading it back failed ("no active voxels"); an all-inside volume reads as empty
    vtkWarningMacro(<< "'" << this->FileName << "': the volume has no voxel within the narrow band (no surface), "
                    << "so the level set holds no active voxel: it reads back as nothing (vtkOpenVDBLevelSetReader "
                    << "refuses it, and an inside is lost); .lvdv keeps such a volume");
  }
}

void vtkOpenVDBLevelSetWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "HalfWidth: " << this->HalfWidth << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
}
