/**
 * @class   vtkDictionaryVolumeWriter
 * @brief   writes a vtkSparseDictionaryVolume (or vtkImageData) as an LVDIF dictionary volume file (.lvdv)
 *
 * A vtkSparseDictionaryVolume input is written as it is: its chunks, uniform
 * chunks and dictionaries, without decoding (BandWidth and ChunkEdge are the
 * volume's own then; the properties below apply to image input only).
 * An image input must have a point array `sdf` (any real type; negative inside,
 * in voxel units) and may have an unsigned char array `rgba` (1 to 4
 * components). Distances are encoded with the SDF dictionary and saturated to
 * +-BandWidth; chunks beyond the band are stored as one value. The file is
 * written crash-safely (temporary file, fsync, rename): a failed write leaves
 * any previous file intact. Reports progress and honours AbortExecute.
 */
#ifndef vtkDictionaryVolumeWriter_h
#define vtkDictionaryVolumeWriter_h

#include "lvdifIOVolumeModule.h"
#include "vtkLVDIFVolumeWriter.h"

#include <map>
#include <string>

class LVDIFIOVOLUME_EXPORT vtkDictionaryVolumeWriter : public vtkLVDIFVolumeWriter
{
public:
  static vtkDictionaryVolumeWriter* New();
  vtkTypeMacro(vtkDictionaryVolumeWriter, vtkLVDIFVolumeWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Distances saturate to +-BandWidth voxels (default 8; 0, or VTK_FLOAT_MAX
  /// and more: no band; negative or NaN is an error: LVDIFVolumeBridge::BandOption).
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  ///@}

  ///@{
  /// Chunk edge in voxels, a power of two in [4, 256] (default 32).
  vtkSetMacro(ChunkEdge, int);
  vtkGetMacro(ChunkEdge, int);
  ///@}

  ///@{
  /// zstd level 1..19 (default: the format's default, see docs/FORMAT.md);
  /// anything else is an error at write (lvdif::checkCompressionLevel; no clamp).
  vtkSetMacro(CompressionLevel, int);
  vtkGetMacro(CompressionLevel, int);
  ///@}

  ///@{
  /// Stored as the `name` metadata entry when not empty.
  vtkSetStdStringFromCharMacro(VolumeName);
  vtkGetCharFromStdStringMacro(VolumeName);

  /// Adds a metadata entry to the file ("source mesh", "creation parameters", ...).
  void AddMetadata(const std::string& key, const std::string& value) { this->Metadata[key] = value; }
  void ClearMetadata() { this->Metadata.clear(); }
  ///@}

protected:
  vtkDictionaryVolumeWriter();
  ~vtkDictionaryVolumeWriter() override;

  void Save(const lvdif::DictionaryVolume& volume, const SaveSource& source, lvdif::Interrupter& interrupter) override;
  lvdif::VolumeOptions ImageVolumeOptions() override;
  void CheckSettings() override;

  std::string VolumeName;
  std::map<std::string, std::string> Metadata;
  double BandWidth = 8.0;
  int ChunkEdge = 32;
  int CompressionLevel;

private:
  vtkDictionaryVolumeWriter(const vtkDictionaryVolumeWriter&) = delete;
  void operator=(const vtkDictionaryVolumeWriter&) = delete;
};

#endif
