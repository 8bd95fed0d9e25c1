#include "VolumeFiles.h"

#include "LVDIFFiles.h"

std::string Extension(const std::string& path)
{
  return LVDIFFiles::Extension(path);
}

std::shared_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress)
{
  return LVDIFFiles::LoadVolume(path, progress);
}

void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress)
{
  // the writers only read the volume: it is lent, not owned
  std::shared_ptr<lvdif::DictionaryVolume> lent(const_cast<lvdif::DictionaryVolume*>(&volume), [](auto*) {});
  LVDIFFiles::SaveVolume(lent, path, metadata, progress);
}
