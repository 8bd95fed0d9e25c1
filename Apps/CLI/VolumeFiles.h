// Loading and saving volumes for the CLI: by extension through the one file
// registry (IO/Files/LVDIFFiles.h), shared with the editor and checked
// against the ParaView plugin.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <map>
#include <memory>
#include <string>

std::shared_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress);
/// A volume extension the file registry can write, and a writable place, checked before the work.
void CheckVolumeOutput(const std::string& path);
/// "" when a volume of these dimensions (and spacing, when given) can be saved to `path`, else
/// "cannot write 'PATH': " and its format's rule (LVDIFFiles::GridProblem: .bv cubic, the edge its
/// SDF_<N>_ name says; .vdb one spacing), for the commands that know the grid before their work:
/// checked before it, not when saving after it.
std::string VolumeOutputDimsProblem(const std::string& path, const lvdif::Index3& dims, const double* spacing = nullptr);
/// VolumeOutputDimsProblem for the volume in `input` where its header tells the grid (a
/// .lvdv, header only: dimensions and spacing), so that a command refuses before reading the whole
/// volume; "" otherwise (the check after loading it then speaks).
std::string VolumeOutputProblemForInput(const std::string& path, const std::string& input);
/// The chunk table of a volume of `dims` (the least it needs) against the memory limit, for a size
/// the command line gives, before the work: "WHAT of NX x NY x NZ voxels, whose chunk table alone
/// needs ..., more than the limit of ... (set LVDIF_MEMORY_LIMIT to change it): ADVICE" (it was the
/// volume's own words after the work began, naming no option).
void RequireChunkTable(const lvdif::Index3& dims, const std::string& what, const std::string& advice);
/// True when `path`'s format holds cubic volumes only (.bv, the original's N^3).
bool VolumeOutputIsCubicOnly(const std::string& path);
void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress);
std::string Extension(const std::string& path);
