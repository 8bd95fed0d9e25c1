#include "lvdif/StarterCanvas.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"

#include <algorithm>
#include <cmath>

namespace lvdif
{

CanvasFill canvasFillFromName(const std::string& name, const std::string& option)
{
  if (name == "empty") return CanvasFill::Empty;
  if (name == "full") return CanvasFill::Full;
  if (name == "sphere") return CanvasFill::Sphere;
  throw Error(ErrorCode::InvalidArgument, option + " must be empty, full or sphere, not '" + name + "'");
}

std::shared_ptr<DictionaryVolume> makeCanvas(const Index3& dims, CanvasFill fill)
{
  VolumeOptions o;
  o.dims = dims;
  o.chunkEdge = 32;
  std::shared_ptr<DictionaryVolume> v = DictionaryVolume::newCanvas(o); // the editors' one canvas rule
  if (fill == CanvasFill::Full)
    return std::make_shared<DictionaryVolume>(o, v->insideVoxel());
  if (fill == CanvasFill::Empty)
    return v;
  // a starter shape reaching at most 64 voxels from the centre: its mesh (and so the
  // first frame) stays small on large canvases; the rest of the canvas is uniform and
  // costs nothing. On a cubic canvas a sphere of radius 0.35 n; on another, a box of
  // half size 0.35 n on each axis (at most 64) rounded by the smallest of them, so
  // that it spans the canvas as the sphere does a cube (256 x 16 x 40 had a sphere
  // of 16 voxels across, a dot in the long view)
  double half[3], r = 64.0;
  for (int a = 0; a < 3; ++a)
    r = std::min(r, half[a] = std::min(64.0, 0.35 * static_cast<double>(dims[a])));
  const double cx = 0.5 * static_cast<double>(dims[0] - 1), cy = 0.5 * static_cast<double>(dims[1] - 1),
               cz = 0.5 * static_cast<double>(dims[2] - 1);
  if (fill == CanvasFill::Dot || (half[0] == r && half[1] == r && half[2] == r))
  {
    fillFromFunction(*v, sphereSdf(cx, cy, cz, r));
    return v;
  }
  const double hx = half[0] - r, hy = half[1] - r, hz = half[2] - r;
  fillFromFunction(*v, [=](double x, double y, double z) {
    const double qx = std::fabs(x - cx) - hx, qy = std::fabs(y - cy) - hy, qz = std::fabs(z - cz) - hz;
    const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0), oz = std::max(qz, 0.0);
    return static_cast<float>(std::sqrt(ox * ox + oy * oy + oz * oz) + std::min(std::max(qx, std::max(qy, qz)), 0.0) - r);
  });
  return v;
}

CanvasFill recordedStarter(const Recording& r, const Index3& d, const std::string& openHint)
{
  // A non-cubic canvas's starter is a rounded box since session 24 (a sphere, a dot on a long
  // canvas, before): a recording made on the old one played on the box, another model.
  if ((d[0] == d[1] && d[1] == d[2]) || r.version >= 3)
    return CanvasFill::Sphere;
  if (r.version == 2)
    throw Error(ErrorCode::InvalidArgument,
      "a version 2 recording of a non-cubic canvas does not say which starter shape it was made on (the sphere of "
      "builds before session 24 or the rounded box since), so it is not played on the starter canvas (nothing was "
      "played): play it on the volume it was recorded on (" + openHint + "), or say its starter on its version line: "
      "'LVDIF-RECORDING 4' for the rounded box of this build's new canvas, 'LVDIF-RECORDING 1' for the older "
      "sphere (and delete its last line, 'end records=N', which version 1 has not)");
  return CanvasFill::Dot;
}

} // namespace lvdif
