#include "MeshOutput.h"
#include "VolumeFiles.h"

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Error.h"

#include "vtkActor.h"
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

#include "lvdif/ByteStream.h"

#include <algorithm>
#include <cctype>
#include <dlfcn.h>

vtkSmartPointer<vtkPolyData> MeshVolume(const lvdif::DictionaryVolume& volume, lvdif::Interrupter& interrupter)
{
  lvdif::MarchingCubesOptions options;
  options.cornerColors = false;
  lvdif::ChunkedMarchingCubes mc(volume, options);
  const std::vector<lvdif::ChunkMesh> chunks = mc.extractAll(interrupter);
  std::size_t nPoints = 0, nTriangles = 0;
  for (const auto& c : chunks)
  {
    nPoints += c.points.size();
    nTriangles += c.triangles.size();
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(nPoints));
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(static_cast<vtkIdType>(nPoints));
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(nPoints));
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(nTriangles), static_cast<vtkIdType>(3 * nTriangles));
  vtkIdType base = 0;
  for (const auto& c : chunks)
  {
    for (std::size_t i = 0; i < c.points.size(); ++i)
    {
      const vtkIdType id = base + static_cast<vtkIdType>(i);
      points->SetPoint(id, c.points[i].data());
      if (!c.normals.empty()) normals->SetTypedTuple(id, c.normals[i].data());
      const lvdif::Rgba col = c.colors.empty() ? lvdif::Rgba{ 200, 200, 200, 255 } : c.colors[i];
      const unsigned char t[4] = { col.r, col.g, col.b, col.a };
      rgba->SetTypedTuple(id, t);
    }
    for (const auto& t : c.triangles)
    {
      const vtkIdType ids[3] = { base + t[0], base + t[1], base + t[2] };
      polys->InsertNextCell(3, ids);
    }
    base += static_cast<vtkIdType>(c.points.size());
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  mesh->GetPointData()->SetNormals(normals);
  mesh->GetPointData()->AddArray(rgba);
  return mesh;
}

void CheckMeshOutput(const std::string& path)
{
  const std::string ext = Extension(path);
  if (ext != "ply" && ext != "obj" && ext != "stl" && ext != "vtp")
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "unknown mesh extension '." + ext + "' of " + path + " (use .ply, .obj, .stl or .vtp)");
  lvdif::requireWritable(path);
}

void CheckPngOutput(const std::string& path)
{
  if (Extension(path) != "png")
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "a picture must be a .png file, not " + path);
  lvdif::requireWritable(path);
  // Debian's VTK renders through X only and aborts the process when the display
  // cannot be opened: try opening it first (libX11 is loaded by VTK anyway)
  vtkNew<vtkRenderWindow> window;
  if (!window->IsA("vtkXOpenGLRenderWindow"))
    return;
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "cannot render " + path + ": no X display (DISPLAY is not set); run under xvfb-run -a");
  void* x11 = ::dlopen("libX11.so.6", RTLD_LAZY | RTLD_LOCAL);
  using Open = void* (*)(const char*);
  using Close = int (*)(void*);
  Open open = x11 ? reinterpret_cast<Open>(::dlsym(x11, "XOpenDisplay")) : nullptr;
  Close close = x11 ? reinterpret_cast<Close>(::dlsym(x11, "XCloseDisplay")) : nullptr;
  if (open && close)
  {
    void* d = open(display);
    if (!d)
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "cannot render " + path + ": cannot open the X display '" +
          display + "'; run under xvfb-run -a");
    close(d);
  }
}

void WriteMesh(vtkPolyData* mesh, const std::string& path)
{
  CheckMeshOutput(path);
  const std::string ext = Extension(path);
  // VTK's writers write by name: into the safe save's temporary file
  lvdif::saveAtomicallyByName(path, [&](const std::string& tmp) {
    int ok = 0;
    unsigned long error = 0;
    if (ext == "ply")
    {
      vtkNew<vtkPLYWriter> w;
      w->SetFileName(tmp.c_str());
      w->SetInputData(mesh);
      w->SetFileTypeToBinary();
      w->SetArrayName("rgba");
      w->SetEnableAlpha(true);
      ok = w->Write();
      error = w->GetErrorCode();
    }
    else if (ext == "obj")
    {
      vtkNew<vtkOBJWriter> w;
      w->SetFileName(tmp.c_str());
      w->SetInputData(mesh);
      ok = w->Write();
      error = w->GetErrorCode();
    }
    else if (ext == "stl")
    {
      vtkNew<vtkSTLWriter> w;
      w->SetFileName(tmp.c_str());
      w->SetInputData(mesh);
      w->SetFileTypeToBinary();
      ok = w->Write();
      error = w->GetErrorCode();
    }
    else
    {
      vtkNew<vtkXMLPolyDataWriter> w;
      w->SetFileName(tmp.c_str());
      w->SetInputData(mesh);
      ok = w->Write();
      error = w->GetErrorCode();
    }
    if (!ok || error != 0)
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, "could not write " + path);
  });
}

void RenderPng(vtkPolyData* mesh, const std::string& path, int width, int height)
{
  CheckPngOutput(path);
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
