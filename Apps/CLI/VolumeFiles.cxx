#include "VolumeFiles.h"

#include "LVDIFFiles.h"

#include "lvdif/Error.h"

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
  const LVDIFFiles::Format* f = LVDIFFiles::Find(path, LVDIFFiles::Kind::Volume);
  if (!f || f->writerClass.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "cannot write '" + path + "': not a volume format (" + LVDIFFiles::DialogFilter(LVDIFFiles::Kind::Volume, true) + ")");
  LVDIFFiles::RequireWritable(path);
}

void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress)
{
  // the writers only read the volume: it is lent, not owned
  std::shared_ptr<lvdif::DictionaryVolume> lent(const_cast<lvdif::DictionaryVolume*>(&volume), [](auto*) {});
  LVDIFFiles::SaveVolume(lent, path, metadata, progress);
}
