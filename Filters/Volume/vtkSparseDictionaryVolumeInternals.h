// What vtkSparseDictionaryVolume.cxx (the object: its volume, copies and the
// composite API) and vtkSparseDictionaryVolumePartitions.cxx (which partitions
// there are; decoding, holding and handing them out) share. Not installed.
#ifndef vtkSparseDictionaryVolumeInternals_h
#define vtkSparseDictionaryVolumeInternals_h

#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <mutex>
#include <unordered_map>
#include <vector>

/// The decoded partitions held, by source (a chunk id, or a corner point's
/// code): shared by an object and its shallow copies, which view the same
/// partitions of the same Core volume.
struct vtkSparseDictionaryVolume::HeldPartitions
{
  std::mutex Lock;
  std::unordered_map<std::int64_t, vtkSmartPointer<vtkImageData>> Images;
  /// The images' own size (vtkImageData::GetActualMemorySize, in bytes): the
  /// one measure, checked against the memory limit and reported by
  /// GetHeldPartitionBytes (before decoding, the point arrays' size is the
  /// lower bound that refuses before allocating).
  std::uint64_t Bytes = 0;
  bool AllHeld = false;       // every partition is held (DecodePartitions succeeded)
  bool AllRefused = false;    // DecodePartitions was refused: not tried again until released or changed
  bool LimitReported = false; // held together over the limit: one error for the set
  bool DecodeReported = false; // a partition not decoded on its own (alone over the limit, or a decode error): one error
  /// What a partition that could not be decoded is handed out as: an image
  /// without points (a null leaf would break consumers that asked to skip
  /// empty nodes, e.g. vtkArrayCalculator, which calls NewInstance on it).
  vtkNew<vtkImageData> Undecoded;
};

/// The partitions' layout (vtkSparseDictionaryVolumePartitions.cxx): a
/// partition's source is a storage chunk (>= 0) or a corner point (-2 - its
/// linear index), see there.
namespace vtkSparseDictionaryVolumeLayout
{
/// The point box of a partition's source.
lvdif::VoxelBox sourceBox(const lvdif::DictionaryVolume& v, std::int64_t source);
/// The storage chunk a partition's points come from (a corner point's own chunk).
std::int64_t sourceChunk(const lvdif::DictionaryVolume& v, std::int64_t source);
/// The partitions' sources (owned: null for every chunk, else an inclusive box of chunk coordinates).
std::vector<std::int64_t> neededPartitions(const lvdif::DictionaryVolume& v, const int* owned);
/// Bytes of the partitions' point arrays (4 a point, 8 with colours).
std::uint64_t partitionBytes(const lvdif::DictionaryVolume& v, const std::vector<std::int64_t>& ids, bool colors);
}

#endif
