#include "VolumeFiles.h"

#include "vtkLVDIFFiles.h"

std::string Extension(const std::string& path)
{
  return vtkLVDIFFiles::Extension(path);
}

std::shared_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress)
{
  return vtkLVDIFFiles::LoadVolume(path, progress);
}

void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress)
{
  // the writers only read the volume: it is lent, not owned
  std::shared_ptr<lvdif::DictionaryVolume> lent(const_cast<lvdif::DictionaryVolume*>(&volume), [](auto*) {});
  vtkLVDIFFiles::SaveVolume(lent, path, metadata, progress);
}
