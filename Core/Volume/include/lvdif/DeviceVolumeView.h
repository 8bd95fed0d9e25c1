// What device code needs to read a dictionary volume that lives on the GPU
// (lvdif::cuda::DeviceVolume::view()): plain device pointers and the chunk
// geometry, so that other subsystems (marching cubes) read the resident volume
// without depending on the editing code. All pointers are device memory and
// stay valid until the next edit, undo/redo or sync of the DeviceVolume.
//
// Voxel (x, y, z) lives in storage chunk id = (x >> shift) + chunkCounts[0] *
// ((y >> shift) + chunkCounts[1] * (z >> shift)); its 4 bytes (SDF key | colour
// key << 16) are uniform[id] when slotOf[id] < 0, else
// pool[slotOf[id] * chunkEdge^3 + localIndex] (DictionaryVolume::localIndex).
#pragma once

#include <cstdint>

namespace lvdif
{

struct DeviceVolumeView
{
  const std::uint32_t* pool = nullptr;
  const int* slotOf = nullptr;
  const std::uint32_t* uniform = nullptr;
  /// The SDF dictionary's decode table (SdfDictionary::KeyCount floats).
  const float* sdfTable = nullptr;
  /// The colour dictionary (Rgba, 4 bytes each), at least as many as the volume's colour keys.
  const std::uint32_t* palette = nullptr;
  std::int64_t dims[3] = { 0, 0, 0 };
  std::int64_t chunkCounts[3] = { 0, 0, 0 };
  int chunkEdge = 0;
  int shift = 0;
  bool valid() const { return pool != nullptr; }
};

} // namespace lvdif
