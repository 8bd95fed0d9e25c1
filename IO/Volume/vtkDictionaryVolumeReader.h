/**
 * @class   vtkDictionaryVolumeReader
 * @brief   reads an LVDIF dictionary volume file (.lvdv) as vtkImageData
 *
 * Produces a float point array `sdf` (negative inside, voxel units) and, when
 * WithColor is on, a 4-component unsigned char array `rgba`. The header and
 * chunk table are read in RequestInformation; RequestData reads and
 * decompresses only the chunks that overlap the UPDATE_EXTENT
 * (CAN_PRODUCE_SUB_EXTENT), so pvbatch ranks and streaming read their part
 * only. Reports progress and honours AbortExecute. A corrupt file gives one
 * error naming the problem and an empty output.
 */
#ifndef vtkDictionaryVolumeReader_h
#define vtkDictionaryVolumeReader_h

#include "lvdifIOVolumeModule.h"
#include "vtkImageAlgorithm.h"

#include <string>

class LVDIFIOVOLUME_EXPORT vtkDictionaryVolumeReader : public vtkImageAlgorithm
{
public:
  static vtkDictionaryVolumeReader* New();
  vtkTypeMacro(vtkDictionaryVolumeReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Produce the `rgba` array as well (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  /// The metadata value of `key` after UpdateInformation ("" if absent), e.g. "name".
  std::string GetMetadata(const std::string& key) const;

  /// True if the file starts with the format's magic number.
  static bool CanReadFile(const char* fileName);

protected:
  vtkDictionaryVolumeReader();
  ~vtkDictionaryVolumeReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool WithColor = true;

private:
  struct Internals;
  Internals* Internal;
  vtkDictionaryVolumeReader(const vtkDictionaryVolumeReader&) = delete;
  void operator=(const vtkDictionaryVolumeReader&) = delete;
};

#endif
