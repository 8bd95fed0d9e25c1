// The edit API every front end drives (scripts, recordings, input devices, the
// VTK layer and the Qt app): it owns the current brush settings, wraps every
// edit in one undo step, and appends it to the recording when recording.
//
// Interactive strokes: beginStroke(), addSample() for each device sample
// (Drill strokes, and Basic ones with applyAsItGoes, are applied as they go),
// endStroke(). pump() does this from an
// InputDevice: button bit 0 pressed starts a stroke, held adds samples, released
// ends it. A Grab stroke is applied as it goes, one dab per sample: centred on
// the previous sample, displacing by the move since it (Brush.h).
//
// With a device-resident volume attached (attachDevice), the same calls apply
// the dabs on the GPU and keep the history there (DeviceVolume's copy-on-write
// steps); Smooth, Grab and Pinch run on the synced host copy and hand their chunks to
// the device. Front ends do not drive an Editor directly: lvdif::EditSession holds one.
#pragma once

#include "lvdif/DeviceVolume.h"
#include "lvdif/EditLimits.h"
#include "lvdif/InputDevice.h"
#include "lvdif/Interrupter.h"
#include "lvdif/Recording.h"
#include "lvdif/UndoStack.h"

#include <memory>

namespace lvdif
{

class Editor
{
public:
  explicit Editor(DictionaryVolume& volume, const UndoStack::Options& undo = UndoStack::Options());

  /// The host volume (with a device attached: synced only by DeviceVolume::sync).
  DictionaryVolume& volume() { return this->Volume; }
  /// The host history (unused while a device is attached: see canUndo()).
  UndoStack& undoStack() { return this->Undo; }

  /// Edits, undo and redo go to this device-resident copy of volume() from now
  /// on (nullptr: back to the host). Either way the history starts empty.
  /// Refused while a stroke is open.
  void attachDevice(cuda::DeviceVolume* device);
  cuda::DeviceVolume* device() { return this->Device; }

  /// The history in use (host or device).
  bool canUndo() const;
  bool canRedo() const;
  std::size_t undoCount() const;
  void clearHistory();
  /// Sets every voxel to `fill` (a script's `canvas fill|clear`): not undoable,
  /// so the history is cleared; every storage chunk is touched. Recorded (when
  /// recording) as a fill record of the distance and colour, which play() repeats.
  void fillVolume(Voxel fill);

  BrushSettings brush;
  StrokeSettings stroke;
  /// Budgets of every edit (checked before the work; Error InvalidArgument).
  EditLimits limits;
  /// Checked between batches of dabs (at most 4096 dabs or ~2^23 voxels of their boxes)
  /// inside long edits, strokes and playback
  /// (Error Cancelled; what was applied stays, as one undo step).
  Interrupter* interrupter = nullptr;
  /// Dabs applied by this editor so far (counts against limits.maxTotalDabs).
  std::uint64_t dabsApplied() const { return this->DabsApplied; }

  /// One dab (with the current brush) as one undo step.
  EditResult dab(const Dab& d);
  /// A whole stroke through these samples (current stroke settings) as one undo step.
  EditResult strokeThrough(const std::vector<BrushSample>& samples);
  /// Applies dabs as they are (one undo step) and records them with `kind`.
  EditResult applyDabs(const std::vector<Dab>& dabs, BrushKind kind);

  void beginStroke();
  EditResult addSample(const BrushSample& s);
  /// Returns the whole stroke's merged result; lastWrite() has only what this call wrote.
  EditResult endStroke();
  /// What the most recent dab(), strokeThrough(), applyDabs(), addSample() or
  /// endStroke() wrote by itself (for endStroke: only the stroke's remaining
  /// dabs). A live (Drill) front end re-meshes chunksAffectedBy(lastWrite().changedBox)
  /// after each call instead of the whole stroke's box.
  const EditResult& lastWrite() const { return this->LastWrite; }
  bool strokeOpen() const { return this->Builder != nullptr; }

  /// Reads up to maxSamples samples from the device, and when maxMillis >= 0 for at
  /// most that long (checked after each sample; an interactive front end passes its
  /// frame budget); returns how many were read.
  std::size_t pump(InputDevice& device, std::size_t maxSamples = 1024, int timeoutMs = 0, int maxMillis = -1);

  bool undo();
  bool redo();

  /// Starts appending every edit (and undo/redo) to a recording; time is the
  /// number of recorded events unless setTime() gives one (seconds, >= 0).
  void startRecording();
  Recording stopRecording();
  bool recording() const { return this->Rec != nullptr; }
  void setTime(double t) { this->Time = t; }

  /// Plays a recording back (edits, undo and redo in order). An undo or redo
  /// with nothing to act on is Error(InvalidArgument) (the recording started
  /// from another volume or history); the records before it stay applied.
  /// `played`, when given, counts the records applied, also when it throws
  /// (0: nothing changed, e.g. a recording of another canvas is refused).
  void play(const Recording& r, Interrupter& interrupter = nullInterrupter(), std::size_t* played = nullptr);

  /// The chunks changed by edits, undo and redo since the last call (increasing ids),
  /// independent of the volume's dirty flags (front ends report them in events).
  std::vector<std::int64_t> takeTouchedStorageChunks();
  /// Adds chunks changed outside the editor's edits (e.g. a script's `canvas fill`).
  void touchStorageChunks(const std::vector<std::int64_t>& ids);

private:
  void record(const EditRecord& e);
  EditResult applyNow(const std::vector<Dab>& dabs);
  void beginStep(const char* label);
  void endStep();
  /// The budgets, then the dabs in batches with a cancellation check between them.
  EditResult applyChecked(const std::vector<Dab>& dabs);
  void throwIfInterrupted(const EditResult& r);
  /// Dabs the next stroke may make: the per-edit limit or what is left of the total.
  std::uint64_t strokeBudget() const;

  DictionaryVolume& Volume;
  UndoStack Undo;
  cuda::DeviceVolume* Device = nullptr;
  std::unique_ptr<StrokeBuilder> Builder;
  std::vector<Dab> StrokeDabs; // every dab of the open stroke, for the record
  EditResult StrokeResult;
  EditResult LastWrite;
  std::unique_ptr<Recording> Rec;
  std::vector<std::int64_t> Touched; // storage chunks, since the last takeTouchedStorageChunks()
  double Time = -1;
  std::uint64_t DabsApplied = 0;
  std::array<double, 3> GrabFrom{ 0, 0, 0 }; // the previous sample of a Grab stroke
  bool GrabStarted = false;
};

} // namespace lvdif
