// MainWindow: a stroke from the brush widget's press to its release (its
// samples applied to the volume, the Grab tool's view-plane drag, the level of
// detail while dragging) and the frames that show the re-meshed chunks (the
// finished meshes installed in the chunk actors, the bounded wait for them
// before a stroke's frame, the frame drawn).
#include "MainWindow.h"

#include "LVDIFChunkedMarchingCubesOutput.h"
#include "vtkBrushRepresentation.h"
#include "vtkCamera.h"
#include "vtkChunkActorManager.h"
#include "vtkGenericOpenGLRenderWindow.h"
#include "vtkPolyData.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"

#include <QActionGroup>
#include <QApplication>
#include <QLabel>
#include <QThread>
#include <QTimer>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <vector>

namespace
{
double msSince(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

bool MainWindow::beginStroke()
{
  if (!this->Doc.hasVolume())
    return false;
  this->applyBrushState();
  // Ctrl inverts, Shift smooths (effectiveOp), for this stroke only
  const int op = this->effectiveOp();
  lvdif::Editor& e = this->Doc.editor();
  e.brush.op = static_cast<lvdif::BrushOp>(op);
  const bool ctrl = this->viewInteractor()->GetControlKey() ||
    (QApplication::queryKeyboardModifiers() & Qt::ControlModifier);
  e.brush.invert = ctrl && (op == 4 || op == 7 || op == 8);
  this->Grabbing = op == 5;
  updatePreview(nullptr, true);
  // The stroke's frames with one sample per pixel (a multisampled view is
  // drawn whole again, multisampled, once still: the still timer).
  this->RenderWindow->SetSingleSampleFrames(!this->Options.multisampledDrag);
  try
  {
    this->Doc.beginStroke();
    // a level of detail for the stroke's frames (finishStrokeMeshing refines)
    this->Doc.session().setCoarseMeshing(strokeLodMinChunks(this->Options.strokeLod));
    this->Painting = true;
  }
  catch (const std::exception& e)
  {
    this->showError("Cannot start the stroke", e);
  }
  return this->Painting;
}

void MainWindow::addBrushSample(const double* sample)
{
  if (!this->Painting)
    return;
  if (this->Grabbing)
  {
    if (!this->PreviewPoints.empty())
      return; // after the press, the grab follows the view plane (onGrabMove)
    double w[4] = { sample[0], sample[1], sample[2], 1.0 };
    this->Renderer->SetWorldPoint(w);
    this->Renderer->WorldToDisplay();
    this->GrabDepth = this->Renderer->GetDisplayPoint()[2];
    this->PreviewPoints.push_back({ sample[0], sample[1], sample[2] });
  }
  else if (this->Tools->state().kind == 2)
    this->updatePreview(sample);
  const auto& o = this->Doc.volume().options();
  lvdif::BrushSample s;
  double p[3] = { sample[0], sample[1], sample[2] };
  if (this->Tools->state().kind == 3)
  {
    // Drill: the tool goes below the surface, half a radius along the inward normal.
    const double* n = this->BrushRep->GetPickedNormal();
    const double depth = 0.5 * sample[3];
    for (int a = 0; a < 3; ++a)
      p[a] -= depth * n[a];
  }
  for (int a = 0; a < 3; ++a)
    s.position[a] = (p[a] - o.origin[a]) / o.spacing[a];
  s.buttons = 1;
  s.pressure = this->Pressure; // < 0 without a tablet: the radius stays as set
  s.time = this->Clock.elapsed() * 1e-3;
  try
  {
    const auto t0 = std::chrono::steady_clock::now();
    // The chunks this sample invalidates go to the worker with those of every
    // sample applied before the next frame (frameAfterSamples): a backlog of
    // samples is meshed once, not once per sample.
    this->Doc.session().holdMeshing();
    this->Doc.addSample(s);
    this->Profile.brushMs += msSince(t0);
    ++this->Profile.samples;
  }
  catch (const std::exception& e)
  {
    this->Painting = false;
    this->finishStrokeMeshing(); // what the stroke changed before the failure
    this->showError("The brush failed", e);
    return;
  }
  this->LastEdit = QDateTime::currentDateTime();
  // The frame comes when the event loop is next free: samples that arrived
  // while the last frame was drawn are all applied first and shown in one
  // frame, so a slow frame delays the view by one frame, not by a queue of
  // frames (one per sample).
  if (!this->FrameTimer->isActive())
    this->FrameTimer->start();
}

void MainWindow::onGrabMove()
{
  if (!this->Painting || !this->Grabbing || this->PreviewPoints.empty())
    return;
  // the point under the cursor on the view plane through the grab's start
  const int* pos = this->viewInteractor()->GetEventPosition();
  this->Renderer->SetDisplayPoint(pos[0], pos[1], this->GrabDepth);
  this->Renderer->DisplayToWorld();
  const double* w = this->Renderer->GetWorldPoint();
  const double p[4] = { w[0] / w[3], w[1] / w[3], w[2] / w[3], 0 };
  this->Grabbing = false; // let addBrushSample take this one
  this->addBrushSample(p);
  this->Grabbing = true;
}

void MainWindow::frameAfterSamples()
{
  if (!this->Doc.hasVolume())
    return;
  this->Doc.session().releaseMeshing();
  // Re-meshing a frame's chunks usually takes a few ms. Waiting for it shows
  // the edits in this frame; what is not done by then needs another frame, so
  // the wait is bounded by the last frame's render time (at least SettleMs,
  // at most MaxSettleMs): never longer than the frame it may save.
  constexpr double SettleMs = 6, MaxSettleMs = 100;
  const double bound = std::min(MaxSettleMs, std::max(SettleMs, this->LastRenderMs));
  const auto t0 = std::chrono::steady_clock::now();
  while (!this->Doc.meshingIdle() && msSince(t0) < bound)
  {
    QThread::usleep(250);
  }
  this->Profile.settleMs += msSince(t0);
  this->Profile.settleTimeouts += this->Doc.meshingIdle() ? 0 : 1;
  this->installFinishedMeshes();
  this->drawFrame();
}

void MainWindow::endStroke()
{
  if (!this->Painting)
    return;
  this->Painting = false;
  this->Grabbing = false;
  try
  {
    this->Doc.endStroke();
  }
  catch (const std::exception& e)
  {
    this->showError("The brush failed", e);
  }
  this->finishStrokeMeshing(); // the stroke's last dabs too; the frame timer or the mesh timer shows them
  this->updatePreview(nullptr, true);
  this->LastEdit = QDateTime::currentDateTime();
  this->updateTitle();
}

void MainWindow::finishStrokeMeshing()
{
  lvdif::EditSession& s = this->Doc.session();
  s.releaseMeshing(); // at the stroke's level
  s.setCoarseMeshing(0);
  // every chunk shown coarsely gets its full-resolution mesh (the worker meshes
  // a chunk still queued at the latest level asked): the picture at rest is the
  // one without a level of detail
  this->Refined = s.refineMeshes();
  this->RefineAt = std::chrono::steady_clock::now();
}

void MainWindow::setStrokeLod(const QString& mode)
{
  this->Options.strokeLod = mode;
  if (this->StrokeLodActions)
    for (QAction* a : this->StrokeLodActions->actions())
      if (a->data().toString() == mode)
        a->setChecked(true);
}

void MainWindow::showFinishedMeshes()
{
  this->installFinishedMeshes();
  this->drawFrame();
}

void MainWindow::installFinishedMeshes()
{
  if (!this->Doc.hasVolume())
    return;
  std::vector<ShownMeshes::TimePoint> gatheredAt;
  std::vector<lvdif::ChunkMesh> meshes = this->Doc.collectMeshes(&gatheredAt);
  if (meshes.empty())
    return;
  ShownMeshes& shown = this->Pending;
  if (shown.chunks.empty())
    shown.installStart = std::chrono::steady_clock::now();
  for (const lvdif::ChunkMesh& mesh : meshes)
  {
    shown.chunks.push_back(mesh.chunkId);
    shown.levels.push_back(mesh.level);
  }
  shown.gatheredAt.insert(shown.gatheredAt.end(), gatheredAt.begin(), gatheredAt.end());
  // In completion order; a later mesh of a chunk supersedes an earlier one.
  std::map<std::int64_t, const lvdif::ChunkMesh*> newest;
  for (const lvdif::ChunkMesh& mesh : meshes)
    newest[mesh.chunkId] = &mesh;
  // the actors of a frame's chunks in one call: SetChunks prepares them in
  // parallel, and leaves a chunk whose new mesh equals its shown one as it is
  const vtkMTimeType managerTime = this->Chunks->GetMTime();
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<vtkIdType> ids;
  std::vector<vtkSmartPointer<vtkPolyData>> polys;
  for (const auto& kv : newest)
  {
    if (kv.second->empty())
      this->Chunks->RemoveChunk(kv.first);
    else
    {
      ids.push_back(kv.first);
      polys.push_back(LVDIFChunkedMarchingCubesOutput::VolumeChunkToPolyData(*kv.second, this->Doc.volume()));
    }
  }
  const auto t1 = std::chrono::steady_clock::now();
  const vtkIdType unchanged = this->Chunks->GetNumberOfUnchangedMeshes();
  this->Chunks->SetChunks(ids, std::vector<vtkPolyData*>(polys.begin(), polys.end()));
  this->Profile.convertMs += std::chrono::duration<double, std::milli>(t1 - t0).count();
  this->Profile.setChunkMs += msSince(t1);
  this->Profile.meshes += static_cast<int>(newest.size());
  this->Profile.unchangedMeshes += static_cast<int>(this->Chunks->GetNumberOfUnchangedMeshes() - unchanged);
  // a chunk replaced or removed (the manager is modified only then), or the camera moved below
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  const vtkMTimeType cameraTime = camera->GetMTime();
  this->PendingChanged = this->PendingChanged || this->Chunks->GetMTime() > managerTime;
  if (!this->ViewInitialized && this->Chunks->GetNumberOfChunks() > 0)
  {
    this->resetView();
    this->ViewInitialized = true;
    if (this->Options.timing)
      std::fprintf(stderr, "lvdif-editor: first surface shown %lld ms after the window was made\n",
        static_cast<long long>(this->Clock.elapsed()));
  }
  else
    this->settleHome();
  this->PendingChanged = this->PendingChanged || camera->GetMTime() != cameraTime;
  this->Status->setText(QString("%1 chunks, %2 triangles")
                          .arg(this->Chunks->GetNumberOfChunks())
                          .arg(this->Chunks->GetNumberOfTriangles()));
}

void MainWindow::drawFrame()
{
  if (this->Pending.chunks.empty())
    return;
  ShownMeshes shown;
  std::swap(shown, this->Pending);
  shown.drawn = this->PendingChanged;
  this->PendingChanged = false;
  shown.renderStart = std::chrono::steady_clock::now();
  if (!shown.drawn)
  {
    // every new mesh equalled its chunk's shown one: the view shows them already
    ++this->Profile.undrawnFrames;
    emit this->meshesShown(shown);
    return;
  }
  this->RenderWindow->Render();
  this->LastRenderMs = msSince(shown.renderStart);
  this->Profile.renderMs += this->LastRenderMs;
  ++this->Profile.frames;
  emit this->meshesShown(shown);
  this->updateView();
}
