#include "EditorRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLState.h"
#include "vtkRendererCollection.h"
#include "vtkPartialRedrawCuller.h"
#include "vtk_glew.h"

#include <utility>

vtkStandardNewMacro(EditorRenderWindow);

EditorRenderWindow::EditorRenderWindow()
  : SingleFramebuffer(vtkOpenGLFramebufferObject::New())
{
}

EditorRenderWindow::~EditorRenderWindow()
{
  if (this->Swapped)
  {
    this->SwapFramebuffers();
  }
  this->SingleFramebuffer->Delete();
}

void EditorRenderWindow::SetPartialRedraw(vtkPartialRedrawCuller* culler)
{
  this->Culler = culler;
}

void EditorRenderWindow::SwapFramebuffers()
{
  std::swap(this->RenderFramebuffer, this->SingleFramebuffer);
  std::swap(this->MultiSamples, this->SingleMultiSamples);
  std::swap(this->LastMultiSamples, this->SingleLastMultiSamples);
  this->Swapped = !this->Swapped;
}

void EditorRenderWindow::Start()
{
  if (this->Swapped)
  {
    this->SwapFramebuffers(); // a frame that did not reach Frame
  }
  this->LastSingleSampled = false;
  if (this->SingleSampleFrames && this->MultiSamples > 1)
  {
    // vtkOpenGLRenderWindow::Start creates (or resizes) and binds the render
    // framebuffer for the window's sample count: for this frame, ours of one
    // sample. Direct member writes: no Modified, as for a frame's state.
    this->SingleMultiSamples = 0;
    this->SingleLastMultiSamples = 0; // as last created: unchanged, kept
    this->SingleFramebuffer->SetContext(this);
    this->SwapFramebuffers();
    this->LastSingleSampled = true;
    ++this->SingleSampledFrames;
  }
  this->Superclass::Start();
}

void EditorRenderWindow::Frame()
{
  int damage[4];
  const bool partial = this->Culler && this->Culler->GetLastFramePartial(damage) &&
    this->GetRenderers()->GetNumberOfItems() == 1 && this->GetSwapBuffers();
  // A single-sampled frame: the window's own framebuffer and sample count
  // again, and VTK's Frame without its copy to the display (SwapBuffers off
  // for the call: its copy of a single-sampled framebuffer ignores the
  // scissor, it would copy everything); the copy after it puts this frame's
  // rectangle there.
  const bool single = this->Swapped;
  const vtkTypeBool swapBuffers = this->SwapBuffers;
  if (single)
  {
    this->SwapFramebuffers();
    this->SwapBuffers = 0; // direct: no Modified
    this->Superclass::Frame(); // the generic window's frame event
    this->SwapBuffers = swapBuffers;
  }
  else if (!partial)
  {
    this->Superclass::Frame();
  }
  else
  {
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
  if (single && this->GetSwapBuffers())
  {
    // the frame's rectangle (the damage, or the whole framebuffer) from the
    // single-sampled framebuffer into the display framebuffer
    const int* fb = this->GetDisplayFramebuffer()->GetLastSize();
    int r[4] = { 0, 0, fb[0], fb[1] }; // x0, y0, x1, y1
    if (partial)
    {
      r[0] = damage[0];
      r[1] = damage[1];
      r[2] = damage[0] + damage[2];
      r[3] = damage[1] + damage[3];
    }
    vtkOpenGLState* state = this->GetState();
    state->PushFramebufferBindings();
    this->SingleFramebuffer->Bind(GL_READ_FRAMEBUFFER);
    this->SingleFramebuffer->ActivateReadBuffer(0);
    this->GetDisplayFramebuffer()->Bind(GL_DRAW_FRAMEBUFFER);
    this->GetDisplayFramebuffer()->ActivateDrawBuffer(0);
    {
      vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
      state->vtkglDisable(GL_SCISSOR_TEST);
      if (r[2] > r[0] && r[3] > r[1])
      {
        state->vtkglBlitFramebuffer(r[0], r[1], r[2], r[3], r[0], r[1], r[2], r[3], GL_COLOR_BUFFER_BIT, GL_NEAREST);
      }
    }
    state->PopFramebufferBindings();
    if (!this->UseOffScreenBuffers && this->FrameBlitMode != NoBlit)
    {
      // as VTK's Frame copies the display framebuffer on
      if (this->FrameBlitMode == BlitToHardware)
        this->BlitDisplayFramebuffersToHardware();
      else
        this->BlitDisplayFramebuffer();
    }
  }
}

void EditorRenderWindow::ReleaseGraphicsResources(vtkWindow* w)
{
  if (this->Swapped)
  {
    this->SwapFramebuffers();
  }
  this->SingleFramebuffer->ReleaseGraphicsResources(w);
  this->Superclass::ReleaseGraphicsResources(w);
}
