/**
 * @class   vtkPartialRedrawCuller
 * @brief   redraws only the part of the view that changed since the last
 *          frame (the damage rectangle), with only the props that cover it
 *
 * A sculpting stroke changes a few chunk meshes and the brush cursor per
 * frame while the camera stands still; drawing the whole surface again each
 * frame costs time in proportion to the whole model (with software OpenGL,
 * seconds per frame for a million triangles). Sculpting tools redraw only the
 * damaged screen region instead (e.g. Blender's sculpt mode: partial redraw of
 * the region the stroke touched, drawing only the mesh nodes inside it). This
 * culler does that for a vtkRenderer:
 *
 * - It remembers, for every prop drawn in the last frame, its screen
 *   rectangle (the projected corners of its bounds, grown by 3 pixels for
 *   lines and points, by 1 for a prop that draws only filled polygons: its
 *   fragments lie within its projection) and a signature (the
 *   modification times of the prop, its actors, their mappers' inputs,
 *   properties and textures, and their visibility; for an actor whose owner
 *   announces its input's changes, SetInputChangesAnnounced, the input's
 *   modification time as of the last announcement).
 * - The damage is the union of the old and new rectangles of every prop that
 *   was added, removed, hidden, shown, moved or modified since.
 * - If the view is unchanged (camera matrices, viewport, window size,
 *   renderer and lights) and the damage is small, the frame clears and draws
 *   only inside the damage rectangle (the camera's one-shot scissor), and
 *   only the props whose rectangles meet it; outside, the render framebuffer
 *   keeps the last frame. Every pixel inside is computed from exactly the
 *   fragments a full frame would draw there, so the picture equals a full
 *   redraw's (tested: TestPartialRedraw).
 * - Otherwise (first frame, a view change, a large damage, translucent props
 *   in the damage, a hardware selection, a frame this culler did not see, or
 *   RequestFullRedraw) the frame is drawn whole, as without the culler.
 *
 * Requirements: the renderer is the only one drawing into its viewport and the
 * render window keeps its framebuffer between frames (vtkOpenGLRenderWindow
 * renders into its own framebuffer object: it does). Add it after the
 * renderer's default frustum culler (AddCuller appends). Off by default.
 */
#ifndef vtkPartialRedrawCuller_h
#define vtkPartialRedrawCuller_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkCuller.h"

#include <memory> // for unique_ptr

class vtkActor;

class LVDIFRENDERINGCHUNKS_EXPORT vtkPartialRedrawCuller : public vtkCuller
{
public:
  static vtkPartialRedrawCuller* New();
  vtkTypeMacro(vtkPartialRedrawCuller, vtkCuller);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Partial redraws on or off (off: every frame is drawn whole and nothing is remembered).
  void SetEnabled(bool enabled);
  vtkGetMacro(Enabled, bool);
  vtkBooleanMacro(Enabled, bool);
  ///@}

  ///@{
  /// A damage rectangle larger than this fraction of the viewport's area is
  /// drawn whole (default 0.5).
  vtkSetClampMacro(MaximumDamageFraction, double, 0.0, 1.0);
  vtkGetMacro(MaximumDamageFraction, double);
  ///@}

  ///@{
  /// Pixels added around the screen rectangle of a prop that draws only
  /// filled polygons (default 1; lines and points get 3). For tests: a
  /// negative margin makes damages too small (a wrong picture).
  vtkSetMacro(SurfaceMargin, int);
  vtkGetMacro(SurfaceMargin, int);
  ///@}

  /// The next frame is drawn whole.
  void RequestFullRedraw() { this->FullRedrawRequested = true; }

  ///@{
  /// A declared change: call BeginChange(prop) before changing a prop and
  /// EndChange(prop, bounds) after, with the world box outside which the prop
  /// draws the same as before (e.g. a chunk's mesh replaced by one whose
  /// changed triangles lie in that box; an uninitialized box: nothing
  /// differs). If the prop was drawn in the last frame and nothing else about
  /// it changed between that frame and the next (its signature before the
  /// first BeginChange equals the last frame's, after each EndChange equals
  /// the next BeginChange's, after the last EndChange equals the next
  /// frame's), its damage is the boxes' screen rectangle instead of its old
  /// and new rectangles; otherwise the declaration is ignored.
  void BeginChange(vtkProp* prop);
  void EndChange(vtkProp* prop, const double bounds[6]);
  /// EndChange with the points of what changed (e.g. the changed triangles'
  /// vertices, world x, y, z each): the damage is the screen rectangle of
  /// their projections (tighter than that of their box), when each point is
  /// in front of the eye; `bounds` should hold them.
  void EndChange(vtkProp* prop, const double bounds[6], const double* points, vtkIdType numberOfPoints);
  ///@}

  ///@{
  /// Announced data changes, for an actor with a static mapper whose owner
  /// changes the mapper's input (its arrays and cells, in place or not) only
  /// between BeginChange and EndChange or right before calling
  /// InputDataChanged(actor). The signature of such an actor then takes its
  /// input's modification time as recorded at the last announcement instead
  /// of asking the input each frame (vtkPolyData::GetMTime visits every array
  /// and cell array: with hundreds of chunk actors that was most of the
  /// culler's time in a frame that changes a few), and the input object as
  /// looked up when the mapper last changed (SetInputData modifies it). The
  /// rest of the signature (actor, mapper, property, texture, visibility) is
  /// still read each frame. An unannounced change of such an input may leave
  /// stale pixels: the owner promises to announce.
  void SetInputChangesAnnounced(vtkActor* actor, bool announced);
  void InputDataChanged(vtkActor* actor);
  ///@}

  ///@{
  /// Statistics since construction: frames drawn whole, frames drawn in part
  /// (an empty damage counts as partial, drawing nothing), and of the last
  /// frame the props drawn and the damage rectangle (x, y, width, height in
  /// window pixels; the whole viewport for a full frame).
  vtkGetMacro(NumberOfFullRedraws, int);
  vtkGetMacro(NumberOfPartialRedraws, int);
  vtkGetMacro(LastNumberOfPropsDrawn, int);
  vtkGetVector4Macro(LastDamage, int);
  ///@}

  /// Whether the renderer's latest frame (the one started last) was culled
  /// here and drawn in part; if so, `damage` gets its rectangle (x, y,
  /// width, height in window pixels): outside it the frame left the
  /// framebuffer as it was (a render window may then present only that part).
  bool GetLastFramePartial(int damage[4]);

  double Cull(vtkRenderer* ren, vtkProp** propList, int& listLength, int& initialized) override;

protected:
  vtkPartialRedrawCuller();
  ~vtkPartialRedrawCuller() override;

  bool Enabled = false;
  double MaximumDamageFraction = 0.5;
  int SurfaceMargin = 1;
  bool FullRedrawRequested = true;
  int NumberOfFullRedraws = 0;
  int NumberOfPartialRedraws = 0;
  int LastNumberOfPropsDrawn = 0;
  int LastDamage[4] = { 0, 0, 0, 0 };
  bool LastPartial = false;

private:
  vtkPartialRedrawCuller(const vtkPartialRedrawCuller&) = delete;
  void operator=(const vtkPartialRedrawCuller&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
