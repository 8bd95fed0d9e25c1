#include "MeshOutput.h"
#include "VolumeFiles.h"

#include "lvdif/Error.h"

#include "vtkActor.h"
#include "LVDIFFiles.h"
#include "vtkCallbackCommand.h"
#include "vtkChunkedMarchingCubes.h"
#include "vtkCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOBJWriter.h"
#include "vtkPLYWriter.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"

#include <cstdlib>
#include "vtkRenderer.h"
#include "vtkSTLWriter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>

vtkSmartPointer<vtkPolyData> MeshVolume(const lvdif::DictionaryVolume& volume, lvdif::Interrupter& interrupter)
{
  // The one chunk mesh -> vtkPolyData route: vtkChunkedMarchingCubes on the
  // volume (merged, seam vertices shared), its progress and cancel bridged to
  // the CLI's interrupter. The filter only reads the volume: it is lent, not owned.
  std::shared_ptr<lvdif::DictionaryVolume> lent(const_cast<lvdif::DictionaryVolume*>(&volume), [](auto*) {});
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetVolume(lent);
  mc->SetOutputModeToMerged();
  mc->ComputeCornerColorsOff(); // per-triangle shader data: no file format takes it
  vtkNew<vtkCallbackCommand> forward;
  forward->SetClientData(&interrupter);
  forward->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
    auto* in = static_cast<lvdif::Interrupter*>(client);
    in->progress(*static_cast<double*>(call));
    if (in->wasInterrupted()) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  mc->AddObserver(vtkCommand::ProgressEvent, forward);
  interrupter.start("marching cubes");
  mc->Update();
  interrupter.end();
  interrupter.checkInterrupt();
  if (mc->GetErrorCode() != 0 || !mc->GetOutput())
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "marching cubes failed");
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(mc->GetOutput());
  return mesh;
}

void WriteMesh(vtkPolyData* mesh, const std::string& path)
{
  LVDIFFiles::SaveMesh(mesh, path); // by extension, through the one file registry
}

void RenderPng(vtkPolyData* mesh, const std::string& path, int width, int height)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(mesh);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("rgba");
  mapper->SetColorModeToDirectScalars();
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetSpecular(0.2);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.18, 0.2, 0.24);
  renderer->SetBackground2(0.05, 0.05, 0.08);
  renderer->GradientBackgroundOn();
  vtkNew<vtkRenderWindow> window;
  // Debian's VTK renders through X only: without a display it aborts the
  // process, so say so first (the mesh itself has been written already)
  if (window->IsA("vtkXOpenGLRenderWindow") && !std::getenv("DISPLAY"))
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "cannot render " + path + ": no X display (DISPLAY is not set); run under xvfb-run -a");
  }
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->Azimuth(35);
  camera->Elevation(25);
  camera->Zoom(1.05);
  renderer->ResetCameraClippingRange();
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(path.c_str());
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();
  if (png->GetErrorCode() != 0)
  {
    throw lvdif::Error(lvdif::ErrorCode::IoFailure, "could not write " + path);
  }
}
