// The editor's render window: after a frame that vtkPartialRedrawCuller drew
// in part, the multisample resolve into the display framebuffer (Frame) covers
// only the damage rectangle. The resolve reads each pixel's own samples, so
// the pixels outside keep the values the last resolve gave them, which are
// still right; at 8 samples the full-size resolve was most of the fixed cost
// of a frame under software OpenGL.
//
// Single-sampled interactive frames (SetSingleSampleFrames): while a stroke
// is drawn, a multisampled window renders its frames into a framebuffer of one
// sample per pixel of its own (colour and depth, the render framebuffer's
// size) and copies the frame's rectangle (the damage, or the whole view) into
// the display framebuffer as it would copy a resolved one. Under software
// OpenGL a multisampled frame takes about twice as long. These are interactive
// frames: the window's owner turns them off and draws the view whole, with
// its multisampling, once the stroke is still (MainWindow's still frame), so
// the still picture is the one a multisampled full redraw gives, as before.
// Outside the rectangles these frames drew, the display keeps the last
// multisampled resolve; within them the scissored clear and draw leave
// nothing of the framebuffer's older contents, so which framebuffer drew the
// frames before does not matter (as for the partial resolve above).
#pragma once

#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkWeakPointer.h"

class vtkOpenGLFramebufferObject;

class EditorRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static EditorRenderWindow* New();
  vtkTypeMacro(EditorRenderWindow, vtkGenericOpenGLRenderWindow);

  /// The culler of the window's one renderer.
  void SetPartialRedraw(vtkPartialRedrawCuller* culler);

  /// Frames drawn with one sample per pixel while on (when the window is
  /// multisampled); off again, the next frame is drawn multisampled (the
  /// owner requests it drawn whole).
  void SetSingleSampleFrames(bool on) { this->SingleSampleFrames = on; }
  bool GetSingleSampleFrames() const { return this->SingleSampleFrames; }
  /// Whether the last frame was drawn with one sample per pixel in place of
  /// the window's multisampling (and so needs a multisampled redraw).
  bool GetLastFrameSingleSampled() const { return this->LastSingleSampled; }
  /// Frames drawn single-sampled since the window was made.
  int GetNumberOfSingleSampledFrames() const { return this->SingleSampledFrames; }

  void Start() override;
  void Frame() override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

protected:
  EditorRenderWindow();
  ~EditorRenderWindow() override;

private:
  EditorRenderWindow(const EditorRenderWindow&) = delete;
  void operator=(const EditorRenderWindow&) = delete;

  /// Swaps the single-sample framebuffer (and its sample counts) with the
  /// window's render framebuffer: in Start, and back at the end of Frame.
  void SwapFramebuffers();

  vtkWeakPointer<vtkPartialRedrawCuller> Culler;
  bool SingleSampleFrames = false;
  bool Swapped = false;
  bool LastSingleSampled = false;
  int SingleSampledFrames = 0;
  vtkOpenGLFramebufferObject* SingleFramebuffer = nullptr;
  int SingleMultiSamples = 0;     // the window's MultiSamples while swapped (0)
  int SingleLastMultiSamples = 0; // its LastMultiSamples while swapped
};
