// The edited volume and everything that follows it: the Core editor (brush
// settings, undo stack, recorder), the chunked marching cubes and its
// background worker. The UI thread edits (holding the worker's source
// mutex, so the worker never reads a half-written chunk) and polls finished
// chunk meshes; the meshing itself never runs on the UI thread.
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Editor.h"
#include "lvdif/MarchingCubesWorker.h"

#include <chrono>

#include <QString>

#include <array>
#include <memory>
#include <vector>

class VolumeDocument
{
public:
  enum class Fill
  {
    Empty,
    Full,
    Sphere
  };

  VolumeDocument();
  ~VolumeDocument();

  /// A new canvas of n^3 voxels (chunk edge 32). Throws lvdif::Error.
  void newCanvas(int nx, int ny, int nz, Fill fill);
  /// Opens a native volume file (.lvdv, docs/FORMAT.md) or a .vti image
  /// (float `sdf`, optional uchar `rgba`). Throws lvdif::Error.
  void open(const QString& path);
  /// Saves as .lvdv (exact) or .vti (decoded sdf + rgba) by extension; throws
  /// lvdif::Error. Clears the modified flag unless `asCopy` (autosave).
  void save(const QString& path, bool asCopy = false);
  /// Takes a volume made elsewhere (e.g. a converted mesh): no file yet, so
  /// the document counts as modified and Save asks for a name.
  void adopt(std::shared_ptr<lvdif::DictionaryVolume> volume);

  bool hasVolume() const { return this->Volume != nullptr; }
  lvdif::DictionaryVolume& volume() { return *this->Volume; }
  lvdif::Editor& editor() { return *this->Edit; }
  const QString& path() const { return this->Path; }
  /// Changes whenever the volume object is replaced (new, open, a script's canvas).
  int generation() const { return this->Generation; }
  bool modified() const { return this->Modified; }
  /// Edits since the last autosave.
  bool needsAutosave() const { return this->EditsSinceAutosave > 0; }
  void autosaved() { this->EditsSinceAutosave = 0; }

  // ---- edits (UI thread) ---------------------------------------------------
  void beginStroke();
  void addSample(const lvdif::BrushSample& s);
  void endStroke();
  bool undo();
  bool redo();
  void startRecording();
  lvdif::Recording stopRecording();
  void play(const lvdif::Recording& r);
  /// Runs an LVDIF script (docs/SCRIPTING.md) on the volume, or on the new
  /// volume its `canvas` command makes. The script's edits are not undoable
  /// one by one, so the undo history is cleared. Throws lvdif::ScriptError.
  void runScript(const std::string& source);

  // ---- meshing ---------------------------------------------------------------
  /// Meshes finished since the last call (never waits); with `gatheredAt`, when
  /// each mesh's input was read (MarchingCubesWorker::collect).
  std::vector<lvdif::ChunkMesh> collectMeshes(std::vector<std::chrono::steady_clock::time_point>* gatheredAt = nullptr);
  /// The chunks the last addSample()/endStroke() asked to re-mesh, and when
  /// (taken under the source mutex right after the edit): a mesh gathered later shows it.
  const std::vector<std::int64_t>& lastRequest() const { return this->LastRequest; }
  std::chrono::steady_clock::time_point lastRequestTime() const { return this->LastRequestAt; }
  bool meshingIdle() const;
  void waitMeshingIdle();

private:
  void resetPipeline();
  void afterEdit(const lvdif::EditResult& r);
  void requestDirty();
  /// Re-mesh request after an editor call: exact for what `r` changed.
  void requestChanged(const lvdif::EditResult& r);

  std::shared_ptr<lvdif::DictionaryVolume> Volume;
  std::unique_ptr<lvdif::Editor> Edit;
  std::unique_ptr<lvdif::ChunkedMarchingCubes> Mesher;
  std::unique_ptr<lvdif::MarchingCubesWorker> Worker;
  QString Path;
  bool Modified = false;
  int EditsSinceAutosave = 0;
  int Generation = 0;
  std::vector<std::int64_t> LastRequest;
  std::chrono::steady_clock::time_point LastRequestAt;
};
