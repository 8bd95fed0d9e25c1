#include "EditorRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLState.h"
#include "vtkRendererCollection.h"
#include "vtkPartialRedrawCuller.h"
#include "vtk_glew.h"

vtkStandardNewMacro(EditorRenderWindow);

void EditorRenderWindow::SetPartialRedraw(vtkPartialRedrawCuller* culler)
{
  this->Culler = culler;
}

void EditorRenderWindow::Frame()
{
  int damage[4];
  if (!this->Culler || !this->Culler->GetLastFramePartial(damage) || this->GetRenderers()->GetNumberOfItems() != 1 ||
    !this->GetSwapBuffers())
  {
    this->Superclass::Frame();
    return;
  }
  // vtkOpenGLRenderWindow::Frame sets a full-size scissor through the GL
  // state cache before it resolves and blits. With the cache already holding
  // that full size, the call changes nothing, so the GL scissor set here (the
  // damage rectangle, scissor test on) stays in force for the resolve and the
  // blit; afterwards GL is given back the cached scissor.
  vtkOpenGLState* state = this->GetState();
  const int* fb = this->GetDisplayFramebuffer()->GetLastSize();
  state->vtkglEnable(GL_SCISSOR_TEST);
  state->vtkglScissor(0, 0, fb[0], fb[1]);
  glScissor(damage[0], damage[1], damage[2], damage[3]);
  this->Superclass::Frame();
  int cached[4];
  state->vtkglGetIntegerv(GL_SCISSOR_BOX, cached); // the cache's value
  glScissor(cached[0], cached[1], cached[2], cached[3]);
}
