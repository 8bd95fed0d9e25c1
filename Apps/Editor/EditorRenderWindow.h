// The editor's render window: after a frame that vtkPartialRedrawCuller drew
// in part, the multisample resolve into the display framebuffer (Frame) covers
// only the damage rectangle. The resolve reads each pixel's own samples, so
// the pixels outside keep the values the last resolve gave them, which are
// still right; at 8 samples the full-size resolve was most of the fixed cost
// of a frame under software OpenGL.
#pragma once

#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkPartialRedrawCuller.h"
#include "vtkWeakPointer.h"

class EditorRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static EditorRenderWindow* New();
  vtkTypeMacro(EditorRenderWindow, vtkGenericOpenGLRenderWindow);

  /// The culler of the window's one renderer.
  void SetPartialRedraw(vtkPartialRedrawCuller* culler);

  void Frame() override;

protected:
  EditorRenderWindow() = default;
  ~EditorRenderWindow() override = default;

private:
  EditorRenderWindow(const EditorRenderWindow&) = delete;
  void operator=(const EditorRenderWindow&) = delete;

  vtkWeakPointer<vtkPartialRedrawCuller> Culler;
};
