// Image to volume (the original's experimental feature, original-code-spec.md
// section 7): an RGBA image becomes a coloured slab, optionally a relief whose
// height follows a depth map (the original loads a depth map and ignores it).
//
// Geometry: pixel (column u, row r) becomes the column of voxels centred at
// x = origin.x + u, y = origin.y + (height - 1 - r) (row 0 is the top of the
// picture, so the image stands upright with y up), spanning
// z in [origin.z, origin.z + thickness + depth(u, r) * depthScale] and
// +-0.5 voxel in x and y: the solid is the union of these pixel boxes.
// Fully transparent pixels (alpha 0) make no material unless keepTransparent.
// Distances: the minimum of the exact box distances over the pixels within
// `window` pixels of the voxel. This is the exact SDF of the union outside the
// solid up to `window` voxels away (farther voxels store +window or more, a
// lower bound) and has the exact sign everywhere; inside, its magnitude is
// a lower bound. Marching cubes needs only the sign and |d| < 1 exactly.
// Colour: the colour of the pixel whose box gives the minimum.
// The slab is united with the volume's content (d = min(d, slab), colour from
// the image where the slab wins); only voxels of the slab's bounding box
// (grown by `window`) can change.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <array>
#include <cstdint>

namespace lvdif
{

struct ImageView
{
  int width = 0, height = 0;
  const std::uint8_t* rgba = nullptr; // width * height * 4 bytes, row-major, row 0 at the top
  const float* depth = nullptr;       // optional, width * height values in [0, 1]
};

struct ImageToVolumeOptions
{
  Index3 origin{ 0, 0, 0 };
  double thickness = 1.0;  // voxels of slab under every pixel (> 0)
  double depthScale = 0.0; // voxels of extra height for depth 1
  int window = 2;          // pixels searched around each voxel (1..8)
  bool keepTransparent = false;
};

/// Unites the slab with the volume; returns the number of solid voxels in the slab's box.
/// Error(InvalidArgument) for an empty/inconsistent image or bad options (nothing written).
std::int64_t imageToVolume(DictionaryVolume& volume, const ImageView& image, const ImageToVolumeOptions& options,
  Interrupter& interrupter = nullInterrupter());

} // namespace lvdif
