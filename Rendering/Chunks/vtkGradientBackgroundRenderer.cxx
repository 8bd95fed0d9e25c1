#include "vtkGradientBackgroundRenderer.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper2D.h"
#include "vtkTexturedActor2D.h"
#include "vtkTrivialProducer.h"
#include "vtkUnsignedCharArray.h"
#include "vtk_glew.h"

#include <algorithm>

vtkStandardNewMacro(vtkGradientBackgroundRenderer);

struct vtkGradientBackgroundRenderer::Internals
{
  vtkNew<vtkTexturedActor2D> Actor;
  vtkNew<vtkPolyDataMapper2D> Mapper;
  vtkNew<vtkPolyData> Quad;
  vtkNew<vtkPoints> Points;
  vtkNew<vtkUnsignedCharArray> Colors;
  vtkNew<vtkTrivialProducer> Producer;
  bool Filled = false;
  int Size[2] = { 0, 0 };
  double Background[3] = { 0, 0, 0 }, Background2[3] = { 0, 0, 0 };

  Internals()
  {
    // as vtkOpenGLRenderer::Clear builds its quad
    this->Points->SetNumberOfPoints(4);
    this->Quad->SetPoints(this->Points);
    vtkNew<vtkCellArray> tris;
    tris->InsertNextCell(3);
    tris->InsertCellPoint(0);
    tris->InsertCellPoint(1);
    tris->InsertCellPoint(2);
    tris->InsertNextCell(3);
    tris->InsertCellPoint(0);
    tris->InsertCellPoint(2);
    tris->InsertCellPoint(3);
    this->Quad->SetPolys(tris);
    this->Colors->SetNumberOfComponents(4);
    this->Colors->SetNumberOfTuples(4);
    this->Quad->GetPointData()->SetScalars(this->Colors);
    this->Producer->SetOutput(this->Quad);
    this->Mapper->SetInputConnection(this->Producer->GetOutputPort());
    this->Actor->SetMapper(this->Mapper);
  }

  /// Refills the quad if the viewport's size or the colours changed; true if it did.
  bool Update(const int size[2], const double* bg, const double* bg2)
  {
    if (this->Filled && size[0] == this->Size[0] && size[1] == this->Size[1] &&
      std::equal(bg, bg + 3, this->Background) && std::equal(bg2, bg2 + 3, this->Background2))
    {
      return false;
    }
    this->Filled = true;
    std::copy(size, size + 2, this->Size);
    std::copy(bg, bg + 3, this->Background);
    std::copy(bg2, bg2 + 3, this->Background2);
    this->Points->SetPoint(0, 0, 0, 0);
    this->Points->SetPoint(1, size[0], 0, 0);
    this->Points->SetPoint(2, size[0], size[1], 0);
    this->Points->SetPoint(3, 0, size[1], 0);
    this->Points->Modified();
    float tmp[4];
    tmp[0] = bg[0] * 255;
    tmp[1] = bg[1] * 255;
    tmp[2] = bg[2] * 255;
    tmp[3] = 255;
    this->Colors->SetTuple(0, tmp);
    this->Colors->SetTuple(1, tmp);
    tmp[0] = bg2[0] * 255;
    tmp[1] = bg2[1] * 255;
    tmp[2] = bg2[2] * 255;
    this->Colors->SetTuple(2, tmp);
    this->Colors->SetTuple(3, tmp);
    this->Colors->Modified();
    this->Quad->Modified();
    return true;
  }
};

vtkGradientBackgroundRenderer::vtkGradientBackgroundRenderer()
  : Internal(new Internals)
{
}

vtkGradientBackgroundRenderer::~vtkGradientBackgroundRenderer() = default;

void vtkGradientBackgroundRenderer::Clear()
{
  if (!this->KeepBackgroundActor || !this->GradientBackground || this->TexturedBackground || this->Transparent())
  {
    this->Superclass::Clear();
    return;
  }
  // VTK's clear of colour and depth, without its background quad; the flag
  // is set directly (no Modified: the renderer's time is part of what the
  // partial-redraw culler compares).
  this->GradientBackground = false;
  this->Superclass::Clear();
  this->GradientBackground = true;

  const int* size = this->GetSize();
  const int sz[2] = { size[0], size[1] };
  if (this->Internal->Update(sz, this->Background, this->Background2))
  {
    ++this->NumberOfBackgroundUpdates;
  }
  vtkOpenGLState* ostate = this->GetState();
  ostate->vtkglDisable(GL_DEPTH_TEST);
  this->Internal->Actor->RenderOverlay(this);
  ostate->vtkglEnable(GL_DEPTH_TEST);
}

void vtkGradientBackgroundRenderer::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internal->Actor->ReleaseGraphicsResources(w);
  this->Superclass::ReleaseGraphicsResources(w);
}

void vtkGradientBackgroundRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KeepBackgroundActor: " << this->KeepBackgroundActor << "\n";
  os << indent << "NumberOfBackgroundUpdates: " << this->NumberOfBackgroundUpdates << "\n";
}
