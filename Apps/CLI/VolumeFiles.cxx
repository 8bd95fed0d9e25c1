#include "VolumeFiles.h"

#include "LVDIFFiles.h"

#include "lvdif/Error.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

std::string Extension(const std::string& path)
{
  return LVDIFFiles::Extension(path);
}

std::shared_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress)
{
  return LVDIFFiles::LoadVolume(path, progress);
}

void CheckVolumeOutput(const std::string& path)
{
  // the registry's words (a Qt dialog filter, "Volumes (*.lvdv ...);;LVDIF ...", was the list)
  LVDIFFiles::RequireFormat(path, LVDIFFiles::Kind::Volume, true);
  LVDIFFiles::RequireWritable(path);
}

std::string VolumeOutputDimsProblem(const std::string& path, const lvdif::Index3& dims, const double* spacing)
{
  // the writers' own rules (a .bv's cube, an OpenVDB level set's one spacing), from the one registry
  const std::string problem = LVDIFFiles::GridProblem(path, dims, spacing);
  return problem.empty() ? problem : "cannot write '" + path + "': " + problem;
}

std::string VolumeOutputProblemForInput(const std::string& path, const std::string& input)
{
  // the input's grid from its header (a .lvdv's, a .vti's): a .lvdv or .vti of unequal
  // spacing to .vdb was read whole, then refused
  lvdif::VolumeOptions grid;
  if (!LVDIFFiles::ReadGrid(input, grid))
    return std::string(); // the load names what is wrong with the file
  return VolumeOutputDimsProblem(path, grid.dims, grid.spacing.data());
}

void RequireChunkTable(const lvdif::Index3& dims, const std::string& what, const std::string& advice)
{
  lvdif::VolumeOptions o;
  o.dims = dims;
  try
  {
    lvdif::requireMemory(lvdif::DictionaryVolume::tableBytes(o), what + " of " + std::to_string(dims[0]) + " x " +
        std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " voxels, whose chunk table alone");
  }
  catch (const lvdif::Error& e)
  {
    throw lvdif::Error(e.code(), std::string(e.what()) + ": " + advice);
  }
}

bool VolumeOutputIsCubicOnly(const std::string& path)
{
  return Extension(path) == "bv";
}

void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress)
{
  // the writers only read the volume: it is lent, not owned
  std::shared_ptr<lvdif::DictionaryVolume> lent(const_cast<lvdif::DictionaryVolume*>(&volume), [](auto*) {});
  LVDIFFiles::SaveVolume(lent, path, metadata, progress);
}
