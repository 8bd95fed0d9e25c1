/**
 * @class   vtkDictionaryVolumeToImage
 * @brief   exposes an lvdif::DictionaryVolume as a VTK image source
 *
 * Produces vtkImageData with a float point array `sdf` (decoded from the
 * 16-bit dictionary keys, negative inside, voxel units) and, when WithColor
 * is on, a 4-component unsigned char array `rgba`. It can produce any
 * sub-extent (CAN_PRODUCE_SUB_EXTENT), so downstream pieces (pvbatch ranks,
 * streaming) decode only their part. The volume is shared, not copied: call
 * Modified() after editing it.
 */
#ifndef vtkDictionaryVolumeToImage_h
#define vtkDictionaryVolumeToImage_h

#include "lvdifFiltersVolumeModule.h"
#include "vtkImageAlgorithm.h"

#include <memory>

namespace lvdif
{
class DictionaryVolume;
}

class LVDIFFILTERSVOLUME_EXPORT vtkDictionaryVolumeToImage : public vtkImageAlgorithm
{
public:
  static vtkDictionaryVolumeToImage* New();
  vtkTypeMacro(vtkDictionaryVolumeToImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  void SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume);
  std::shared_ptr<lvdif::DictionaryVolume> GetVolume() const { return this->Volume; }
#endif

  ///@{
  /// Produce the `rgba` array as well (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

protected:
  vtkDictionaryVolumeToImage();
  ~vtkDictionaryVolumeToImage() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::shared_ptr<lvdif::DictionaryVolume> Volume;
  bool WithColor = true;

private:
  vtkDictionaryVolumeToImage(const vtkDictionaryVolumeToImage&) = delete;
  void operator=(const vtkDictionaryVolumeToImage&) = delete;
};

#endif
