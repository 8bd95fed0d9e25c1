#include "MeshOutput.h"
#include "VolumeFiles.h"

#include "lvdif/Error.h"

#include "vtkActor.h"
#include "LVDIFFiles.h"
#include "LVDIFVolumeBridge.h"
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
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSTLWriter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLPolyDataWriter.h"

#include "lvdif/ByteStream.h"

#include <algorithm>
#include <string>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <dlfcn.h>

vtkSmartPointer<vtkPolyData> MeshVolume(const lvdif::DictionaryVolume& volume, lvdif::Interrupter& interrupter)
{
  // The one chunk mesh -> vtkPolyData route: vtkChunkedMarchingCubes on the
  // volume (merged, seam vertices shared), its progress and cancel bridged to
  // the CLI's interrupter. The filter only reads the volume: it is lent, not owned.
  // A volume one point thick (a slice) has no cells: the filter refuses it
  // (VTK's rule); here, as any volume without a surface, the empty mesh is
  // written and named in one warning (it blamed the distances: "never change
  // sign at 0")
  const lvdif::Index3& dims = volume.dims();
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    std::fprintf(stderr,
      "warning: the volume is %lld x %lld x %lld points and marching cubes needs at least 2 points along every axis "
      "(a volume one point thick has no cells), so the mesh has no triangles\n",
      static_cast<long long>(dims[0]), static_cast<long long>(dims[1]), static_cast<long long>(dims[2]));
    auto empty = vtkSmartPointer<vtkPolyData>::New();
    empty->SetPoints(vtkSmartPointer<vtkPoints>::New());
    return empty;
  }
  std::shared_ptr<lvdif::DictionaryVolume> lent(const_cast<lvdif::DictionaryVolume*>(&volume), [](auto*) {});
  vtkNew<vtkChunkedMarchingCubes> mc;
  mc->SetVolume(lent);
  mc->SetOutputModeToMerged();
  mc->ComputeCornerColorsOff(); // per-triangle shader data: no file format takes it
  vtkNew<vtkCallbackCommand> forward;
  forward->SetClientData(&interrupter);
  forward->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
    auto* in = static_cast<lvdif::Interrupter*>(client);
    in->progress(*static_cast<double*>(call)); // "done" only by end(), below
    if (in->wasInterrupted()) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  mc->AddObserver(vtkCommand::ProgressEvent, forward);
  // the filter's own error is the command's one line (it said only "marching cubes failed")
  std::string failure;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&failure);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    *static_cast<std::string*>(client) = LVDIFVolumeBridge::MessageText(static_cast<const char*>(call));
  });
  mc->AddObserver(vtkCommand::ErrorEvent, onError);
  interrupter.start("marching cubes");
  mc->Update();
  interrupter.checkInterrupt();
  if (mc->GetErrorCode() != 0 || !failure.empty() || !mc->GetOutput())
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, failure.empty() ? "marching cubes failed" : failure);
  }
  interrupter.end(); // only a stage that succeeded is "done"
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(mc->GetOutput());
  // an empty mesh is still written (a valid file), but never silently; with
  // no points object at all (a volume of one voxel or one chunk-less row)
  // VTK's writers refused it ("cannot write 'x.ply.tmp-...': No data to write!")
  if (mesh->GetNumberOfPolys() == 0)
    std::fprintf(stderr, "warning: the volume has no surface (its distances never change sign at 0), so the mesh has "
                         "no triangles\n");
  if (!mesh->GetPoints())
    mesh->SetPoints(vtkSmartPointer<vtkPoints>::New());
  return mesh;
}

void CheckMeshOutput(const std::string& path)
{
  // the registry's words (a Qt dialog filter, "Meshes (*.ply ...);;PLY mesh (*.ply);;...", was the list)
  LVDIFFiles::RequireFormat(path, LVDIFFiles::Kind::Mesh, true);
  lvdif::requireWritable(path);
}

void CheckPngOutput(const std::string& path)
{
  if (Extension(path) != "png")
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "a picture must be a .png file, not " + path);
  lvdif::requireWritable(path);
}

void RequireDisplay(const std::string& path)
{
  // Debian's VTK renders through X only and aborts the process when the display
  // cannot be opened: try opening it first (libX11 is loaded by VTK anyway)
  vtkNew<vtkRenderWindow> window;
  if (!window->IsA("vtkXOpenGLRenderWindow"))
    return;
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "cannot render " + path + ": no X display (DISPLAY is not set); run under xvfb-run -a");
  // The connection stays open until the process exits: Xvfb (xvfb-run without
  // -noreset) resets when its last client leaves, and VTK's own connection
  // made during that reset failed with "bad X server connection" and an abort
  // (6 runs in 8 of `xvfb-run -a lvdif mesh v.lvdv m.ply --png m.png`).
  static void* held = nullptr;
  if (held)
    return;
  void* x11 = ::dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  using Open = void* (*)(const char*);
  Open open = x11 ? reinterpret_cast<Open>(::dlsym(x11, "XOpenDisplay")) : nullptr;
  if (open)
  {
    held = open(display);
    if (!held)
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "cannot render " + path + ": cannot open the X display '" +
          display + "'; run under xvfb-run -a");
  }
}

void WriteMesh(vtkPolyData* mesh, const std::string& path)
{
  CheckMeshOutput(path);
  LVDIFFiles::SaveMesh(mesh, path); // the registry's writer, saved safely (a temporary file renamed over the old)
}

void RenderPng(vtkPolyData* mesh, const std::string& path, int width, int height)
{
  CheckPngOutput(path);
  RequireDisplay(path);
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
  lvdif::saveAtomicallyByName(path, [&](const std::string& tmp) {
    vtkNew<vtkPNGWriter> png;
    png->SetFileName(tmp.c_str());
    png->SetInputConnection(grab->GetOutputPort());
    png->Write();
    if (png->GetErrorCode() != 0)
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, "could not write " + path);
  });
}
