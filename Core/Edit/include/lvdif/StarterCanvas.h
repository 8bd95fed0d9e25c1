// The editors' new canvas: its fills, the starter shape, and which starter a
// recording was made on. One implementation for the Qt editor (--new, --fill,
// File > New canvas) and `lvdif play` without --in (the recording's own
// canvas), so that a recording made on the editor's starter canvas replays
// voxel for voxel on the command line (the CLI could not make that canvas).
#pragma once

#include "lvdif/DictionaryVolume.h"

#include <memory>
#include <string>

namespace lvdif
{

struct Recording;

enum class CanvasFill
{
  Empty, ///< every voxel outside
  Full,  ///< every voxel inside
  /// The starter shape: on a cubic canvas a sphere of radius min(0.35 n, 64) at
  /// the centre; on another, a box of half size min(0.35 n, 64) on each axis
  /// rounded by the smallest of them, so that it spans the canvas as the sphere
  /// does a cube (since session 24)
  Sphere,
  /// The starter of builds before session 24 on every canvas: the sphere of
  /// Sphere's radius, a dot on a long canvas (recordings of version 1 start on it)
  Dot
};

/// "empty", "full" or "sphere" (the editor's and `lvdif play`'s --fill words) to
/// a fill; Error(InvalidArgument) naming `option` otherwise.
CanvasFill canvasFillFromName(const std::string& name, const std::string& option);

/// A new canvas of `dims` voxels (chunk edge 32), filled. The editors' one
/// canvas rule first (DictionaryVolume::newCanvas): Error(InvalidArgument).
std::shared_ptr<DictionaryVolume> makeCanvas(const Index3& dims, CanvasFill fill);

/// The starter (Sphere or Dot) that `recording`, played on an untouched starter
/// canvas of `dims` (its own), was made on: Dot for a version 1 recording of a
/// non-cubic canvas (made before session 24), else Sphere. A version 2
/// recording of a non-cubic canvas cannot say which (version 2 was written both
/// before and since): Error(InvalidArgument), nothing played, naming how to
/// play it on the volume it was recorded on (`openHint`, e.g. "File > Open" or
/// "--in VOLUME") or the version line that says its starter.
CanvasFill recordedStarter(const Recording& recording, const Index3& dims, const std::string& openHint);

} // namespace lvdif
