/**
 * @class   vtkLVDIFVolumeWriter
 * @brief   base of the writers of LVDIF volumes (.lvdv, .bv, .vdb)
 *
 * Takes a vtkSparseDictionaryVolume (written as it is, without decoding) or a
 * vtkImageData with a point array `sdf` (negative inside, voxel units) and
 * optionally `rgba` (made into a dictionary volume first). WriteData checks the
 * file name and the input, makes the volume of an image input, calls Save, and
 * reports a failure once (vtkErrorMacro and the writer's error code); a cancel
 * (AbortExecute) is not an error. Write() returns 0 whenever nothing was
 * written, also when the input failed upstream (its own error says why) and
 * after a cancel (no message, error code NoError; the old file is kept). Subclasses say how an image becomes a volume
 * and how a volume is saved. Every save is crash-safe (lvdif::saveAtomically).
 */
#ifndef vtkLVDIFVolumeWriter_h
#define vtkLVDIFVolumeWriter_h

#include "lvdifIOVolumeModule.h"
#include "vtkWriter.h"

#include <cstdint>
#include <memory>
#include <string>

class vtkDataArray;
class vtkImageData;

namespace lvdif
{
class DictionaryVolume;
class Interrupter;
struct VolumeOptions;
}

class LVDIFIOVOLUME_EXPORT vtkLVDIFVolumeWriter : public vtkWriter
{
public:
  vtkTypeMacro(vtkLVDIFVolumeWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

  /// The input when it is an image (nullptr for a sparse volume).
  vtkImageData* GetInput();

  /// vtkWriter::Write, but 0 when the input failed upstream (vtkWriter's
  /// answered 1, nothing written, and ran a failed reader a second time);
  /// the file name, its folder and the writer's settings are checked first
  /// (CheckTarget), before the input is brought up to date.
  int Write() override;

  /// What Write() runs, for every LVDIF writer (vtkPDictionaryVolumeWriter
  /// too): the pipeline for the whole input, stopping when its information
  /// fails; false when it did not run to the end.
  static bool UpdateWholeInput(vtkWriter* writer);

protected:
  vtkLVDIFVolumeWriter();
  ~vtkLVDIFVolumeWriter() override;

  void WriteData() final;
  /// The file name, the place (lvdif::requireWritable) and CheckSettings: false
  /// after one error (and the writer's error code) when one fails.
  bool CheckTarget();
  /// CheckGrid on the input's information (its whole extent and spacing):
  /// false after one error naming the file (and the writer's error code).
  bool CheckInputGrid();
  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// What a save is given besides the volume.
  struct SaveSource
  {
    /// The volume was just made from an image input (false: a sparse input).
    bool fromImage = false;
    /// The image's `rgba` array when it had one and the writer asked for it.
    vtkDataArray* imageColors = nullptr;
  };
  /// Writes `volume` to FileName; throws lvdif::Error on failure.
  virtual void Save(const lvdif::DictionaryVolume& volume, const SaveSource& source, lvdif::Interrupter& interrupter) = 0;
  /// The writer's own settings that apply to every input (a sparse one too),
  /// checked after the folder and before any work; throws lvdif::Error (default: none).
  virtual void CheckSettings() {}
  /// The input's grid as its pipeline information announces it (points on
  /// each axis; spacing, nullptr when not announced), checked by Write() after
  /// the input's information pass and before any of its work: what the format
  /// cannot hold (a .bv's cube, an OpenVDB level set's one spacing); throws
  /// lvdif::Error (default: none). The save checks the volume itself again.
  virtual void CheckGrid(const std::int64_t dims[3], const double* spacing) { (void)dims; (void)spacing; }
  /// Whether an image input's `rgba` array is read (default true).
  virtual bool ReadsImageColors() { return true; }
  /// The volume of an image input (default: its `sdf` and `rgba` encoded with
  /// ImageVolumeOptions()); throws lvdif::Error.
  virtual std::unique_ptr<lvdif::DictionaryVolume> ImageToVolume(
    vtkImageData* image, vtkDataArray* sdf, vtkDataArray* rgba);
  /// Chunk edge and band of the volume made from an image input.
  virtual lvdif::VolumeOptions ImageVolumeOptions() = 0;

  std::string FileName;

private:
  bool Cancelled = false; // the last WriteData was cancelled (AbortExecute)
  vtkLVDIFVolumeWriter(const vtkLVDIFVolumeWriter&) = delete;
  void operator=(const vtkLVDIFVolumeWriter&) = delete;
};

#endif
