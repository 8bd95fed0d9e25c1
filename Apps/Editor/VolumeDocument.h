// The edited document: a holder of one lvdif::EditSession (the volume, on the
// host or resident on the GPU, its editor, marching cubes and remesh rule) plus
// what only the app needs: the file name and the modified/autosave state. The
// UI thread edits and polls finished chunk meshes; the session decides where
// the meshing runs (a worker thread on the CPU, one batched launch per frame on
// the GPU), never on the UI thread's time on the CPU.
#pragma once

#include "lvdif/EditSession.h"
#include "lvdif/StarterCanvas.h"

#include <chrono>

#include <QString>

#include <array>
#include <memory>
#include <vector>

class VolumeDocument
{
public:
  /// Core's canvas fills (lvdif/StarterCanvas.h: Empty, Full, Sphere, the old starter Dot)
  using Fill = lvdif::CanvasFill;

  VolumeDocument();
  ~VolumeDocument();

  /// A new canvas of n^3 voxels (chunk edge 32). Throws lvdif::Error.
  void newCanvas(int nx, int ny, int nz, Fill fill);
  /// Opens a volume file of any format the file registry reads (LVDIFFiles).
  /// Throws lvdif::Error. `untitled` (a recovered autosave): the volume is
  /// not that file's document: no file name, modified, Save asks for a name.
  void open(const QString& path, bool untitled = false);
  /// Saves by extension through the file registry (.lvdv exact); throws
  /// lvdif::Error. Clears the modified flag unless `asCopy` (autosave).
  void save(const QString& path, bool asCopy = false);
  /// Takes a volume made elsewhere (e.g. a converted mesh): no file yet, so
  /// the document counts as modified and Save asks for a name.
  void adopt(std::shared_ptr<lvdif::DictionaryVolume> volume);

  bool hasVolume() const { return this->Session != nullptr; }
  /// Whether the voxel nearest a world point (clamped into the volume) is
  /// inside the solid (on the GPU the host copy is synced first).
  bool insideAt(const double world[3]);
  /// The volume's geometry, options and dictionaries (on the GPU its voxels are
  /// synced only for saving: lvdif::EditSession::hostVolume).
  const lvdif::DictionaryVolume& volume() const { return this->Session->hostVolume(); }
  lvdif::Editor& editor() { return this->Session->editor(); }
  lvdif::EditSession& session() { return *this->Session; }
  const QString& path() const { return this->Path; }
  /// Changes whenever the volume object is replaced (new, open, a script's canvas).
  int generation() const { return this->Session ? this->Session->generation() : 0; }
  bool modified() const { return this->Modified; }
  /// Edits since the last autosave.
  bool needsAutosave() const { return this->EditsSinceAutosave > 0; }
  void autosaved() { this->EditsSinceAutosave = 0; }

  // ---- edits (UI thread) ---------------------------------------------------
  void beginStroke();
  void addSample(const lvdif::BrushSample& s);
  void endStroke();
  /// Undo and redo by the script policy (docs/SCRIPTING.md, docs/EDITING.md):
  /// every stroke is one step, also one that changed no voxel (a carve in empty
  /// space), which the session's history does not hold: its undo and redo
  /// change nothing, and a new stroke drops what was undone. False when there
  /// is nothing to undo (redo).
  bool undo();
  bool redo();
  void startRecording();
  lvdif::Recording stopRecording();
  /// Plays a recording as one undo step a record. On a non-cubic starter canvas
  /// (newCanvas Sphere, untouched) it starts from the starter the recording was
  /// made on: a version 1 recording (before session 24) on the Dot; a version 2
  /// one, which cannot say which, is refused (lvdif::Error) before anything plays.
  void play(const lvdif::Recording& r);
  /// Runs an LVDIF script (docs/SCRIPTING.md) through the session: its edits
  /// are undoable; a `canvas` command makes a new volume (`options`: its rules,
  /// lvdif::ScriptOptions). Throws lvdif::ScriptError.
  void runScript(const std::string& source, const lvdif::ScriptOptions& options = lvdif::ScriptOptions());

  // ---- meshing ---------------------------------------------------------------
  /// Meshes ready now (never waits for the CPU worker); with `gatheredAt`, when
  /// each mesh's input was read (lvdif::EditSession::collectMeshes).
  std::vector<lvdif::ChunkMesh> collectMeshes(std::vector<std::chrono::steady_clock::time_point>* gatheredAt = nullptr);
  /// The mesh chunks the last addSample()/endStroke() asked to re-mesh, and when
  /// (right after the edit): a mesh gathered later shows it.
  const std::vector<std::int64_t>& lastRequest() const;
  std::chrono::steady_clock::time_point lastRequestTime() const;
  bool meshingIdle() const;
  void waitMeshingIdle();

private:
  /// Holds `volume` in the session (a new session the first time), meshes everything.
  void hold(std::shared_ptr<lvdif::DictionaryVolume> volume);
  /// Counts a change when the session's count moved.
  void noteChanges();
  /// The strokes' own history starts again from the session's (a new volume,
  /// a script or a recording played: their steps are the session's).
  void resetHistory();

  std::unique_ptr<lvdif::EditSession> Session;
  // the untouched starter canvas of newCanvas (Sphere): its volume's generation
  // and the session's change count then (-1: the volume is no starter)
  int StarterGeneration = -1;
  std::uint64_t StarterChanges = 0;
  QString Path;
  bool Modified = false;
  int EditsSinceAutosave = 0;
  std::uint64_t SeenChanges = 0;
  bool CapsPending = false; // all meshes were requested: the box caps of chunks the device skips come with the next collect
  // The strokes' history, as the script runner keeps a script's: Done/Undone
  // hold the steps since resetHistory(), true where the session holds the step
  // (a stroke that changed no voxel is false: the session keeps no step for
  // it, so Ctrl+Z after it undid the stroke before). Before them (empty), the
  // session's own history. RedoDropped: a stroke since, so the session's redo
  // steps from before it are not to be redone (the session drops them only on
  // a stroke that changes something).
  std::vector<bool> Done, Undone;
  bool RedoDropped = false;
  std::size_t StrokeUndoCount = 0;   // the session's undo count at beginStroke
  std::uint64_t StrokeChanges = 0;   // its change count there
};
