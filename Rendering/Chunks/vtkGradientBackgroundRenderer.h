/**
 * @class   vtkGradientBackgroundRenderer
 * @brief   an OpenGL renderer whose gradient background keeps its actor
 *          between frames
 *
 * vtkOpenGLRenderer (VTK 9.1) draws a gradient background in Clear() with a
 * textured 2D actor, a 2D mapper, a poly data and a trivial producer it makes
 * for the frame and deletes after it: each frame builds the quad's vertex
 * buffers and vertex array again, and the mapper's release walks the window's
 * whole vertex buffer cache (a buffer per array of every chunk actor in the
 * editor). Under software OpenGL that was about a fifth of a partial frame
 * that draws a few chunks (docs/BENCHMARKS.md, "Stroke-to-frame latency").
 *
 * This renderer makes the same objects once, fills them as VTK does (the
 * viewport's size, Background and Background2 as colours times 255 through
 * float tuples) and refills them only when one of those changes; each frame
 * clears as VTK does (vtkOpenGLRenderer::Clear with the gradient turned off
 * for the call) and then draws the kept quad with the depth test off, as VTK
 * draws its new one. The picture equals the stock renderer's, pixel for pixel
 * (TestGradientBackground), in full frames and in frames drawn in part under
 * the camera's scissor (vtkPartialRedrawCuller).
 *
 * Only the plain gradient: a textured background, a transparent renderer
 * (layers, or the background alpha below 1 with preserved colour) or
 * KeepBackgroundActor off take VTK's own Clear().
 */
#ifndef vtkGradientBackgroundRenderer_h
#define vtkGradientBackgroundRenderer_h

#include "lvdifRenderingChunksModule.h" // for export macro
#include "vtkOpenGLRenderer.h"

#include <memory> // for unique_ptr

class LVDIFRENDERINGCHUNKS_EXPORT vtkGradientBackgroundRenderer : public vtkOpenGLRenderer
{
public:
  static vtkGradientBackgroundRenderer* New();
  vtkTypeMacro(vtkGradientBackgroundRenderer, vtkOpenGLRenderer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Keep the gradient background's actor between frames (default on; off:
  /// VTK's Clear, a new actor per frame).
  vtkSetMacro(KeepBackgroundActor, bool);
  vtkGetMacro(KeepBackgroundActor, bool);
  vtkBooleanMacro(KeepBackgroundActor, bool);
  ///@}

  /// How many times the kept quad was filled (its size or colours changed).
  vtkGetMacro(NumberOfBackgroundUpdates, int);

  void Clear() override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

protected:
  vtkGradientBackgroundRenderer();
  ~vtkGradientBackgroundRenderer() override;

  bool KeepBackgroundActor = true;
  int NumberOfBackgroundUpdates = 0;

private:
  vtkGradientBackgroundRenderer(const vtkGradientBackgroundRenderer&) = delete;
  void operator=(const vtkGradientBackgroundRenderer&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
