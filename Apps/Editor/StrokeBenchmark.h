// lvdif-editor --benchmark-stroke FILE: replays a recorded stroke
// through the editor's real UI event loop at the speed it was recorded and
// prints the stroke-to-frame latency (p50, p95, max) and the frames per
// second, then quits.
//
// Each sample is delivered by a Qt timer at its recorded time to the window's
// brush input, the slots the brush widget calls (MainWindow::beginStroke,
// addBrushSample, endStroke): the Core editor applies it, the worker re-meshes
// the chunks it changed, the sample's settle / the 15 ms mesh timer install
// the finished meshes as chunk actors, and the next frame (one for every
// sample applied by then) renders them. Reported per frame: the render alone
// (Render + glFinish) and install + render (from the first install since the
// previous frame, so it includes the samples applied meanwhile); before the
// stroke, the still scene's frame drawn whole and unchanged; after it, how far
// the picture is from the scene drawn whole. Latency of a sample = from
// its recorded time until the end of the render (glFinish) of the frame at
// which every chunk it changed shows a mesh gathered after the edit (the
// window's meshesShown signal says when each mesh's input was read). Qt's
// compositing of the widget afterwards is not included. Under Xvfb the frames
// are drawn by software OpenGL: not representative of a GPU. Only the window's
// public interface is used (EditorDriver starts it).
//
// FILE: one sample per line in the socket protocol (InputDevice.h:
// {"position":[x,y,z],"time":t}, voxel coordinates, seconds; '#' lines and
// blank lines skipped; without times, 50 Hz), or a recording (.lvr/.lvrec):
// the centres of its dabs as samples at 50 Hz (recordings keep no sample
// times). The brush is the tool panel's (--radius, --op, --color, --brush).
//
// Level of detail (--stroke-lod): the latency counts the first mesh that
// shows the sample, coarse or not (the report says how many were coarse);
// "refine" is the time from the stroke's end until the frame at which every
// chunk the stroke changed shows its full-resolution mesh of its last edit.
#pragma once

#include "lvdif/Stroke.h"

#include "vtkSmartPointer.h"

#include <QObject>
#include <QString>

#include <chrono>
#include <cstdint>
#include <map>
#include <vector>

class MainWindow;
class vtkPartialRedrawCuller;
class vtkUnsignedCharArray;
struct ShownMeshes;

class StrokeBenchmark : public QObject
{
  Q_OBJECT
public:
  using TimePoint = std::chrono::steady_clock::time_point;

  /// Reads the samples (positions in voxels, times in seconds from 0); throws
  /// lvdif::Error naming the file and line on bad input. A recording's samples
  /// are voxels of its canvas: with `dims` (the volume's), one made on a canvas
  /// of other dimensions is refused, as its playback is (the stroke went
  /// elsewhere or outside without a word).
  static std::vector<lvdif::BrushSample> loadSamples(const QString& path, const lvdif::Index3* dims = nullptr);

  StrokeBenchmark(MainWindow& window, std::vector<lvdif::BrushSample> samples, const QString& name);

  /// Schedules the stroke (the surface should be shown); when done, prints the
  /// report and calls QApplication::exit (0, or 1 if a requested chunk never showed).
  void start();

private:
  /// The view's partial-redraw culler if it is on, else nullptr.
  vtkPartialRedrawCuller* redrawCuller();
  /// Prints the still scene's frame time drawn whole and unchanged.
  void measureStillFrames();
  /// Pixels of the picture shown that differ from the scene drawn whole (-1:
  /// sizes differ); with `earlier`, also those of that earlier grab (*earlierDiffer).
  long pixelsDifferingFromFullRedraw(vtkUnsignedCharArray* earlier = nullptr, long* earlierDiffer = nullptr);
  /// The picture shown now (the display framebuffer, as Qt presents it).
  vtkSmartPointer<vtkUnsignedCharArray> grabShown();
  /// After the window applied a sample: the chunks it asked to re-mesh.
  void sampleApplied();
  /// MainWindow::meshesShown: waits for the frame to be drawn, notes when.
  void frameRendered(const ShownMeshes& shown);
  void deliver(std::size_t i);
  void finishWhenIdle();
  void report();

  struct Request
  {
    double sampleTime = 0; // seconds after the start
    TimePoint editedAt;
    std::vector<std::int64_t> chunks;
  };
  MainWindow& Window;
  std::vector<lvdif::BrushSample> Samples;
  QString Name;
  TimePoint Start;
  double CurrentSampleTime = 0;
  bool Ended = false;
  std::vector<Request> Requests;
  struct Shown
  {
    TimePoint gathered, rendered;
    int level = 0; // 1: a coarse mesh of the stroke's level of detail
  };
  // per chunk: every mesh installed, in order
  std::map<std::int64_t, std::vector<Shown>> Delivered;
  TimePoint EndAt; // the stroke ended (MainWindow::endStroke returned)
  std::vector<double> RenderMs; // from the first install of a frame's meshes to its end
  std::vector<double> DrawMs;   // the frame's Render() and glFinish
  TimePoint LastFrame;
  int Frames = 0;
  int UndrawnFrames = 0; // frames whose meshes all equalled the shown ones (not rendered)
  std::vector<double> TrianglesDrawn; // per frame, by the chunk actors
  std::vector<double> DrawCalls;      // per frame, the chunk actors' triangle draw calls
  int FullBefore = 0, PartialBefore = 0; // the culler's counts at the stroke's start
  int SingleSampledBefore = 0;           // the window's single-sampled frames at the stroke's start
  vtkSmartPointer<vtkUnsignedCharArray> StrokePicture; // the picture the stroke's frames left, before the still frame
};
