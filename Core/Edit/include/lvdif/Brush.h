// Brushes and CSG on the dictionary volume (paper Sect. 3.4, Fig. 7).
//
// A dab is one primitive (sphere, cube, or a capsule for stroke segments)
// placed in voxel coordinates; the primitive SDFs are Quilez's
// (https://iquilezles.org/articles/distfunctions/). Applying a dab combines
// the primitive's distance s with the stored distance d. With strength 1 and
// the Constant falloff (the defaults) the CSG operations are the paper's:
//
//   Add       d' = min(d, s)          (union; smooth: d' = smin(d, s, k))
//   Subtract  d' = max(d, -s)         (subtraction; smooth: d' = smax(d, -s, k))
//   Paint     d' = d, bit-identical   (colour only)
//
// smin is Quilez's polynomial smooth minimum: h = max(k - |a - b|, 0) / k,
// smin = min(a, b) - h*h*k/4; smax(a, b, k) = -smin(-a, -b, k). k = 0 is the
// paper's hard CSG. Every written distance goes through volume.encode(), so
// it saturates to +-band like every other write.
//
// Strength and falloff. Every dab has a weight w = strength * f(t), t the
// voxel's distance from the dab's core in units of its radius (sphere:
// |p - c| / r; cube: the largest |p_i - c_i| / h; capsule: distance to the
// segment / r) and f the falloff curve (Constant 1, Linear 1 - t, Smooth
// 1 - 3t^2 + 2t^3, Sharp (1 - t)^2; 0 beyond t = 1). Add and Subtract move
// the distance part of the way to the CSG result, d' = d + w (csg - d), with
// t clamped to 1 (the rim's weight holds in the band around the primitive);
// w = 1 is exactly the rule above. The other operations act inside the
// primitive (s <= 0) only, and only on distances inside the band (a
// saturated distance means "at least band", which no offset may turn into
// a surface):
//
//   Inflate   d' = d - w            (deflate with `invert`: d + w), voxels
//   Crease    d' = d + w^3 * 1.5    (a sharp dent; `invert`: a ridge)
//   Flatten   d' = d + w (e - d), e the signed distance to the plane tangent
//             to the surface nearest the dab centre (normal: the volume's
//             gradient there, by central differences of trilinear samples)
//   Smooth    d' = d + w (mean of the 6 neighbours - d)   (CPU only)
//   Grab      d'(p) = d(p - w(p) D), D the dab's `vec` (the drag since the
//             previous sample), d sampled trilinearly (CPU only)
//   Pinch     d'(p) = d(p + w(p) r(p)), r = p - c with c the dab's centre
//             (a capsule's: the nearest point of its segment), projected
//             perpendicular to the dab's `vec` (the stroke direction) when
//             that is not zero; d sampled trilinearly (CPU only). Surface
//             points move toward the centre (line): ridges and creases
//             sharpen. `invert`: d(p - w r), the surface spreads.
// Smooth, Grab and Pinch read neighbours, so each dab reads the volume as
// the previous dab left it (a Jacobi step per dab); they have no CUDA path
// (lvdif::applyDabs(Device::Auto, ...) runs them on the CPU).
//
// Colour (the exact rule):
//   Add       colour := brush colour where the new surface owns the voxel:
//             inside the primitive (s <= 0; a smaller add inside a body
//             recolours its interior, as the dice demo needs), or where the
//             distance was lowered to d' <= colorOffset. A voxel whose
//             distance the old surface keeps is never coloured (no halo).
//   Subtract and the shape brushes: colour unchanged (a cut exposes the
//             colour the interior already has).
//   Paint     where s <= 0 and |d| <= colorOffset (the skin of the surface
//             inside the brush, nothing deeper): colour := mix(old, brush,
//             q/8), q = round(8 w) (coverage in eighths; q = 8 is the brush
//             colour itself, q = 0 leaves the voxel). Mixed colours go into
//             the colour dictionary (Error DictionaryFull when it cannot).
//
// Symmetry mirrors every dab about the chosen planes (x = plane[0], ...);
// a dab and its mirror images act as one dab whose primitive is their union
// (s = min, t = min). An image is evaluated as the dab itself at the reflected
// voxel (exact for planes on whole or half voxels), so a symmetric volume stays
// exactly symmetric wherever the dabs are.
//
// Only chunks that intersect the dab's influence box are visited; a voxel is
// written only when its 4 bytes change, so exactly the chunks with a changed
// voxel are marked dirty (DictionaryVolume::set marks them), and chunks left
// all-equal by the edit are collapsed back to uniform. Chunks are processed
// in parallel (OpenMP), each by one thread; a list of dabs is applied per
// voxel in list order, which is bit-identical to applying them one by one.
// Without symmetry and with strength 1 and the Constant falloff the CPU works a
// row at a time, dab after dab (the voxels are independent, so the order per
// voxel is the same): a dab's distances over its part of the row in one
// vectorised loop, and for a hard add/subtract of a sphere the span below -band
// set at once (every key within the band goes to that of -band, or +band) and a
// row it cannot change skipped (the row's largest distance at most the dab's
// smallest, for add). Same bits as the per-voxel rule (TestBrush's
// RowPathEqualsThePerVoxelPathBitForBit, and the CUDA comparisons).
#pragma once

#include "lvdif/Interrupter.h"
#include "lvdif/HostDevice.h"

#include "lvdif/DictionaryVolume.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

// The primitive functions below also compile as CUDA device code (Brush.cu).

namespace lvdif
{

enum class BrushShape : int
{
  Sphere = 0,
  Cube = 1,
  Capsule = 2
};

enum class BrushOp : int
{
  Add = 0,
  Subtract = 1,
  Paint = 2,
  Smooth = 3,
  Inflate = 4,
  Grab = 5,
  Flatten = 6,
  Crease = 7,
  Pinch = 8
};

/// How a dab's weight falls from its core (t = 0) to its rim (t = 1); see above.
enum class Falloff : int
{
  Constant = 0,
  Linear = 1,
  Smooth = 2,
  Sharp = 3
};

/// Mirror planes: axis a is mirrored about a = plane[a] where mirror[a].
struct Symmetry
{
  std::array<bool, 3> mirror{ false, false, false };
  std::array<double, 3> plane{ 0, 0, 0 };
  bool any() const { return this->mirror[0] || this->mirror[1] || this->mirror[2]; }
};

const char* toString(BrushShape s);
const char* toString(BrushOp op);
const char* toString(Falloff f);
/// True for the operations that read neighbouring voxels (Smooth, Grab, Pinch): CPU only.
inline bool readsNeighbours(BrushOp op)
{
  return op == BrushOp::Smooth || op == BrushOp::Grab || op == BrushOp::Pinch;
}

/// One placed primitive, in voxel coordinates.
struct Dab
{
  BrushShape shape = BrushShape::Sphere;
  std::array<double, 3> center{ 0, 0, 0 };
  /// Sphere radius, cube HALF edge, capsule radius (voxels, > 0; <= 0 is skipped).
  double radius = 1.0;
  /// Second end point of a capsule (ignored otherwise).
  std::array<double, 3> end{ 0, 0, 0 };
  /// Grab: the displacement this dab applies (voxels); Pinch: the stroke's
  /// direction at the dab (any length; zero: none, the pinch is radial);
  /// Flatten: set by the brush (the plane's unit normal), ignored on input.
  std::array<double, 3> vec{ 0, 0, 0 };
  /// Flatten: set by the brush (the plane's offset n . p0), ignored on input.
  double value = 0;
};

/// The brush colour of every front end until one is chosen (the editor's colour
/// button, a script's `color`, vtkLVDIFEditor::SetColor, a recording's records
/// carry their own): the editor's, which a user sees first, and one that shows
/// on the unpainted light grey. Scripts, `lvdif script` and vtkLVDIFEditor had
/// white (255, 255, 255) where the editor had this: a script run in the editor
/// and by the CLI gave other colours.
inline constexpr Rgba DefaultBrushColor{ 230, 90, 60, 255 };

struct BrushSettings
{
  BrushOp op = BrushOp::Add;
  Rgba color = DefaultBrushColor;
  /// Smooth blend radius k in voxels (0 = hard CSG).
  double blend = 0.0;
  /// Skin thickness (voxels) that gets the colour; the original uses 1.5.
  double colorOffset = 1.5;
  /// Edge rounding of cube dabs (Quilez's round box: box(h - r) - r), 0..half edge.
  double rounding = 0.0;
  /// Weight of every dab, (0, 1].
  double strength = 1.0;
  Falloff falloff = Falloff::Constant;
  /// Inflate deflates, Crease raises a ridge, Pinch spreads (the UI's Ctrl).
  bool invert = false;
  Symmetry symmetry;
};

// ---- primitive SDFs (voxel units, negative inside) ---------------------------

LVDIF_HD double sphereDistance(double px, double py, double pz, double r)
{
  return std::sqrt(px * px + py * py + pz * pz) - r;
}

/// Quilez's box with half extent h on every axis.
LVDIF_HD double cubeDistance(double px, double py, double pz, double h)
{
  const double ux = std::fabs(px) - h, uy = std::fabs(py) - h, uz = std::fabs(pz) - h;
  const double mx = ux > 0 ? ux : 0, my = uy > 0 ? uy : 0, mz = uz > 0 ? uz : 0;
  const double outside = std::sqrt(mx * mx + my * my + mz * mz);
  double m = ux > uy ? ux : uy;
  m = m > uz ? m : uz;
  return outside + (m < 0 ? m : 0);
}

/// Quilez's box with half extents (hx, hy, hz).
LVDIF_HD double cubeDistanceBox(double px, double py, double pz, double hx, double hy, double hz)
{
  const double ux = std::fabs(px) - hx, uy = std::fabs(py) - hy, uz = std::fabs(pz) - hz;
  const double mx = ux > 0 ? ux : 0, my = uy > 0 ? uy : 0, mz = uz > 0 ? uz : 0;
  double m = ux > uy ? ux : uy;
  m = m > uz ? m : uz;
  return std::sqrt(mx * mx + my * my + mz * mz) + (m < 0 ? m : 0);
}

/// Quilez's capsule from a to b (p relative to a, ba = b - a).
LVDIF_HD double capsuleDistance(double px, double py, double pz, double bax, double bay, double baz, double r)
{
  const double bb = bax * bax + bay * bay + baz * baz;
  double t = bb > 0 ? (px * bax + py * bay + pz * baz) / bb : 0.0;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  const double qx = px - t * bax, qy = py - t * bay, qz = pz - t * baz;
  return std::sqrt(qx * qx + qy * qy + qz * qz) - r;
}

/// The dab's signed distance at voxel (x, y, z); `rounding` rounds cube edges.
LVDIF_HD double dabDistance(const Dab& d, double x, double y, double z, double rounding = 0.0)
{
  const double px = x - d.center[0], py = y - d.center[1], pz = z - d.center[2];
  switch (d.shape)
  {
    case BrushShape::Cube:
    {
      const double r = rounding < d.radius ? rounding : d.radius;
      return r > 0 ? cubeDistance(px, py, pz, d.radius - r) - r : cubeDistance(px, py, pz, d.radius);
    }
    case BrushShape::Capsule:
      return capsuleDistance(px, py, pz, d.end[0] - d.center[0], d.end[1] - d.center[1], d.end[2] - d.center[2], d.radius);
    default:
      return sphereDistance(px, py, pz, d.radius);
  }
}

/// The voxel's distance from the dab's core in units of its radius (t above).
LVDIF_HD double dabRadialFraction(const Dab& d, double x, double y, double z)
{
  const double px = x - d.center[0], py = y - d.center[1], pz = z - d.center[2];
  if (d.shape == BrushShape::Cube)
  {
    double m = std::fabs(px);
    m = std::fabs(py) > m ? std::fabs(py) : m;
    m = std::fabs(pz) > m ? std::fabs(pz) : m;
    return m / d.radius;
  }
  if (d.shape == BrushShape::Capsule)
    return (capsuleDistance(px, py, pz, d.end[0] - d.center[0], d.end[1] - d.center[1], d.end[2] - d.center[2], 0.0)) /
      d.radius;
  return std::sqrt(px * px + py * py + pz * pz) / d.radius;
}

/// The falloff curve f(t) (0 for t >= 1 except Constant at t = 1).
LVDIF_HD double falloffCurve(int falloff, double t)
{
  if (t > 1)
    return 0;
  if (t < 0)
    t = 0;
  switch (falloff)
  {
    case static_cast<int>(Falloff::Linear): return 1 - t;
    case static_cast<int>(Falloff::Smooth): return 1 - t * t * (3 - 2 * t);
    case static_cast<int>(Falloff::Sharp): return (1 - t) * (1 - t);
    default: return 1;
  }
}

/// Quilez's polynomial smooth minimum (k > 0).
LVDIF_HD double smoothMin(double a, double b, double k)
{
  const double diff = a > b ? a - b : b - a;
  const double h = (k - diff > 0 ? k - diff : 0) / k;
  return (a < b ? a : b) - h * h * k * 0.25;
}

/// The voxels whose value or colour this dab may change (not clipped to the volume):
/// the primitive's bounding box grown by the band (Add/Subtract) or by nothing (Paint),
/// plus the colour skin and the blend radius.
VoxelBox dabInfluenceBox(const DictionaryVolume& volume, const Dab& dab, const BrushSettings& settings);

/// Throws Error(InvalidArgument) when the dabs (with their mirror images) would visit
/// more chunks in all than EditLimits::maxChunkVisitsPerEdit. Every apply call checks
/// it before writing; an editor that applies a long edit in batches checks the whole
/// edit once, so batching cannot lift the budget.
void requireChunkVisitBudget(const DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings);

/// Told before the first write into a chunk during one apply call (from the thread that
/// owns the chunk; different chunks may call concurrently). The undo stack uses it to
/// snapshot the chunk (copy-on-write).
class ChunkWriteObserver
{
public:
  virtual ~ChunkWriteObserver() = default;
  virtual void beforeChunkWrite(const DictionaryVolume& volume, std::int64_t chunkId) = 0;
};

struct EditResult
{
  std::int64_t changedVoxels = 0;
  /// Chunks with at least one changed voxel, increasing ids.
  std::vector<std::int64_t> changedChunks;
  /// A box holding every changed voxel (empty when none changed): exact per row
  /// of the brush loop, the whole chunk box where a chunk was filled in one go.
  /// Feed it to ChunkedMarchingCubes::chunksAffectedBy for the exact set of
  /// marching cubes chunks to re-mesh.
  VoxelBox changedBox;
  /// Per changed chunk (parallel to changedChunks): the box of its changed voxels,
  /// each inside its chunk and inside changedBox. Finer than changedBox for the
  /// re-mesh (a stroke's crescent of changed voxels meets far fewer mesh chunks
  /// than its bounding box). Empty when not known (then changedBox stands).
  std::vector<VoxelBox> changedChunkBoxes;
  /// True when an interrupter stopped the edit part way: what was written is
  /// reported above (an undo step that observed the writes restores it).
  bool interrupted = false;
  /// True when changedChunkBoxes holds one box per changed chunk.
  bool hasChunkBoxes() const { return !this->changedChunks.empty() && this->changedChunkBoxes.size() == this->changedChunks.size(); }
};

/// Applies the dabs in order (see the header comment). Adds the brush colour to the
/// volume's colour dictionary first (Error DictionaryFull if it cannot). Invalid dabs
/// (non-finite position or radius) are refused with Error(InvalidArgument) before any write.
/// `interrupter`, when given, is checked between chunks (and between groups of the
/// brushes that read neighbours): once it reports true the rest is left as it was
/// and the result says `interrupted` (no exception: the caller decides).
EditResult applyDabs(DictionaryVolume& volume, const std::vector<Dab>& dabs, const BrushSettings& settings,
  ChunkWriteObserver* observer = nullptr, const Interrupter* interrupter = nullptr);

/// The dabs with their mirror images (`symmetry`), in groups of 2^(mirrored axes):
/// dab i's group is [i * g, (i + 1) * g), its first member the dab itself.
std::vector<Dab> mirrorDabs(const std::vector<Dab>& dabs, const Symmetry& symmetry);

inline EditResult applyDab(DictionaryVolume& volume, const Dab& dab, const BrushSettings& settings,
  ChunkWriteObserver* observer = nullptr)
{
  return applyDabs(volume, std::vector<Dab>{ dab }, settings, observer);
}

} // namespace lvdif
