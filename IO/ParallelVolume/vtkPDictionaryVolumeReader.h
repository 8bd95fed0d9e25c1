/**
 * @class   vtkPDictionaryVolumeReader
 * @brief   reads a distributed dictionary volume (.lvdvp index + one .lvdv per piece)
 *
 * Reads the index written by vtkPDictionaryVolumeWriter (docs/FORMAT.md,
 * "Distributed volumes") and produces the whole image (sdf, and rgba with
 * WithColor): it advertises the whole extent and CAN_PRODUCE_SUB_EXTENT, and
 * for an update extent opens only the pieces overlapping it, each of which
 * decodes only its chunks overlapping the request (vtkDictionaryVolumeReader).
 * So under MPI every rank reads only its part, whatever the number of ranks
 * that wrote the files. Points on a plane shared by two pieces are taken from
 * the first piece listed (both hold the same values).
 */
#ifndef vtkPDictionaryVolumeReader_h
#define vtkPDictionaryVolumeReader_h

#include "lvdifIOParallelVolumeModule.h"
#include "vtkImageAlgorithm.h"

#include <string>

class LVDIFIOPARALLELVOLUME_EXPORT vtkPDictionaryVolumeReader : public vtkImageAlgorithm
{
public:
  static vtkPDictionaryVolumeReader* New();
  vtkTypeMacro(vtkPDictionaryVolumeReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

  ///@{
  /// Also produce `rgba` (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  /// True if the file starts with the index's magic line.
  static bool CanReadFile(const char* fileName);

  /// Pieces opened by the last update (for tests and diagnostics).
  vtkGetMacro(PiecesRead, int);

protected:
  vtkPDictionaryVolumeReader();
  ~vtkPDictionaryVolumeReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool WithColor = true;
  int PiecesRead = 0;

private:
  vtkPDictionaryVolumeReader(const vtkPDictionaryVolumeReader&) = delete;
  void operator=(const vtkPDictionaryVolumeReader&) = delete;
};

#endif
