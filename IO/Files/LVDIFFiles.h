/**
 * @file   LVDIFFiles.h
 * @brief  the one file registry by extension: which formats exist, who reads and writes them
 *
 * Every front end reads and writes the same formats through this table: the
 * CLI (`lvdif`), the Qt editor (open/save volume, export mesh, file dialog
 * filters) and the ParaView plugin, whose reader/writer XML hints
 * (ReaderFactory / WriterFactory extensions) a test checks against it.
 * Volumes are loaded and saved through the VTK reader and writer classes named
 * here (so a format behaves the same everywhere); meshes through
 * vtkLVDIFMeshReader and VTK's writers.
 */
#ifndef LVDIFFiles_h
#define LVDIFFiles_h

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdifIOFilesModule.h"

#include "vtkSmartPointer.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

class vtkPolyData;

namespace LVDIFFiles
{
enum class Kind
{
  Volume,
  Mesh
};

struct Format
{
  std::string extension;   // lower case, no dot
  std::string description; // for dialogs
  Kind kind;
  std::string readerClass; // the VTK class that reads it ("" if none)
  std::string writerClass; // the VTK class that writes it ("" if none)
};

/// Every format this build handles (.vdb only with the OpenVDB module).
LVDIFIOFILES_EXPORT const std::vector<Format>& Formats();

/// The lower-case extension of a path without the dot ("" if none).
LVDIFIOFILES_EXPORT std::string Extension(const std::string& path);

/// The format of this kind for the path's extension, or nullptr.
LVDIFIOFILES_EXPORT const Format* Find(const std::string& path, Kind kind);

/// The format that reads (forSaving false) or writes (true) the path, or
/// lvdif::Error(InvalidArgument) naming the path and the extensions that do
/// (the words LoadVolume and SaveVolume use: one message for every front end).
LVDIFIOFILES_EXPORT const Format& RequireFormat(const std::string& path, Kind kind, bool forSaving);

/// "LVDIF volume (*.lvdv);;..." for Qt file dialogs: the formats of a kind
/// that can be read (forSaving false) or written (true), an "all" entry first.
LVDIFIOFILES_EXPORT std::string DialogFilter(Kind kind, bool forSaving);

/// Throws lvdif::Error (lvdif::requireWritable's words) unless every file a
/// save to `path` writes can be written: the path, and for a distributed volume
/// (.lvdvp) also its piece beside it (a piece that is a folder was found after
/// the work). Front ends call it before any work.
LVDIFIOFILES_EXPORT void RequireWritable(const std::string& path);

/// What a volume of this grid cannot be saved to `path` as, in its writer's
/// words ("" when it can): a .bv's cube of the edge its SDF_<N>_ name says
/// (lvdif::checkLegacyBvDims), an OpenVDB level set's one spacing
/// (lvdif::vdb::checkExportSpacing; not checked when `spacing` is nullptr).
/// For front ends that know the grid before their work (a .lvdv's header, a
/// size on the command line), so that they refuse before it.
LVDIFIOFILES_EXPORT std::string GridProblem(
  const std::string& path, const lvdif::Index3& dims, const double* spacing = nullptr);

/// The grid (dims, spacing, origin) of a volume file from its header alone,
/// without reading its data: a .lvdv's header, a .vti's (VTK's reader's
/// information pass). False for other formats and for a file whose header
/// cannot be read (nothing is printed: the load names what is wrong). For
/// GridProblem before a conversion reads the whole input.
LVDIFIOFILES_EXPORT bool ReadGrid(const std::string& path, lvdif::VolumeOptions& grid);

/// Reads a volume by extension. Throws lvdif::Error naming the file and the
/// problem (unknown extension, the reader's own error), Cancelled when the
/// interrupter says so.
LVDIFIOFILES_EXPORT std::shared_ptr<lvdif::DictionaryVolume> LoadVolume(
  const std::string& path, lvdif::Interrupter& interrupter = lvdif::nullInterrupter());

/// Writes a volume by extension (metadata where the format has a place for it).
LVDIFIOFILES_EXPORT void SaveVolume(const std::shared_ptr<lvdif::DictionaryVolume>& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata = {},
  lvdif::Interrupter& interrupter = lvdif::nullInterrupter());

/// Reads a triangle mesh (vtkLVDIFMeshReader: validated, polygons fanned).
LVDIFIOFILES_EXPORT vtkSmartPointer<vtkPolyData> LoadMesh(const std::string& path);

/// Writes a mesh by extension (binary where the format allows; `rgba` as
/// colours in .ply), crash-safely: a temporary file renamed over the old one, so
/// a failed write (a full disk too) leaves the old file as it was. Throws
/// lvdif::Error on an unknown extension or failure.
LVDIFIOFILES_EXPORT void SaveMesh(vtkPolyData* mesh, const std::string& path);
}

#endif
