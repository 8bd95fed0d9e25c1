// The editor's brush cursor: vtkBrushRepresentation (a cursor on the surface
// under the mouse) with what a volume of the editor needs besides a surface:
//
// - Where the ray under the mouse hits no surface it may still hit the solid:
//   a volume that is inside everywhere (a Full canvas, a solid block) has no
//   surface to pick, yet the user sees a block to carve. The ray is met with
//   the volume's box; where the solid reaches the box there (no surface along
//   the ray, so the whole ray in the box is inside), the cursor sits on the
//   box's face, its normal the face's. A volume that shows no surface at all
//   (an Empty canvas) takes the brush at the middle of the ray's way through
//   the box, facing the camera, so that the first stroke can be drawn in the
//   air. Elsewhere a press off the surface turns the camera, as before.
// - The cursor is the brush's true shape on an anisotropic grid: a dab of r
//   voxels reaches r * spacing[a] along axis a (it was a sphere of r times the
//   x spacing).
// - The cursor takes no part in the camera's clipping range: a large brush
//   (the wheel or --radius up to 1e7 voxels) pushed the near plane past the
//   model, and then nothing could be picked.
#pragma once

#include "vtkBrushRepresentation.h"

#include <functional>

class EditorBrushRepresentation : public vtkBrushRepresentation
{
public:
  static EditorBrushRepresentation* New();
  vtkTypeMacro(EditorBrushRepresentation, vtkBrushRepresentation);

  /// The volume's box in world coordinates, whether a world point is inside
  /// the solid, and whether the view shows any surface; no box: off.
  void SetVolume(const double bounds[6], std::function<bool(const double world[3])> inside,
    std::function<bool()> showsSurface);
  void ClearVolume();
  /// The cursor's scale per axis (spacing[a] / spacing[0]): the Radius is in
  /// world units of the x axis.
  void SetAxisScale(double sx, double sy, double sz);

  /// Where the cursor stands after the last ComputeInteractionState: on the
  /// picked surface, on the volume's box, in the middle of an empty volume, nowhere.
  enum Hit
  {
    NoHit,
    SurfaceHit,
    BoxHit,
    EmptyVolumeHit
  };
  Hit GetLastHit() const { return this->LastHit; }

  int ComputeInteractionState(int X, int Y, int modify = 0) override;
  void BuildRepresentation() override;

protected:
  EditorBrushRepresentation();
  ~EditorBrushRepresentation() override = default;

private:
  /// The ray through display (X, Y) met with the box: true with the entry and
  /// exit points and the entry face's outward normal.
  bool RayThroughBox(int X, int Y, double entry[3], double exit[3], double normal[3]);

  bool HaveVolume = false;
  double Box[6] = { 0, 0, 0, 0, 0, 0 };
  std::function<bool(const double*)> Inside;
  std::function<bool()> ShowsSurface;
  double AxisScale[3] = { 1, 1, 1 };
  Hit LastHit = NoHit;

  EditorBrushRepresentation(const EditorBrushRepresentation&) = delete;
  void operator=(const EditorBrushRepresentation&) = delete;
};
