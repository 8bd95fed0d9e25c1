#include "VolumeFiles.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/VolumeFile.h"

#include <algorithm>
#include <cctype>

std::string Extension(const std::string& path)
{
  const auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::unique_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress)
{
  const std::string ext = Extension(path);
  if (ext == "lvdv")
  {
    return lvdif::loadVolume(path, lvdif::VolumeFileReadOptions(), progress);
  }
  if (ext == "bv")
  {
    return lvdif::loadLegacyBv(path, lvdif::LegacyBvOptions(), progress);
  }
  throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
    "cannot read '" + path + "': volumes are .lvdv (or legacy .bv) files");
}

void CheckVolumeOutput(const std::string& path)
{
  const std::string ext = Extension(path);
  if (ext != "lvdv" && ext != "bv")
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "cannot write '" + path + "': volumes are .lvdv (or legacy .bv) files");
  lvdif::requireWritable(path);
}

void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress)
{
  const std::string ext = Extension(path);
  if (ext == "lvdv")
  {
    lvdif::VolumeFileWriteOptions options;
    options.metadata = metadata;
    lvdif::saveVolume(volume, path, options, progress);
    return;
  }
  if (ext == "bv")
  {
    lvdif::saveLegacyBv(volume, path, lvdif::LegacyBvOptions(), progress);
    return;
  }
  throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
    "cannot write '" + path + "': volumes are .lvdv (or legacy .bv) files");
}
