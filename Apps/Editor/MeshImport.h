// "Open mesh...": a mesh file (vtkLVDIFMeshReader) converted to a volume by
// vtkMeshToSDF (the one mesh-to-volume route: Core's sparse meshToSdf, writing
// straight into the dictionary volume with the CLI's defaults) on a worker thread, with a progress dialog whose Cancel
// button sets the filter's AbortExecute. The UI thread keeps running its
// event loop meanwhile (the chunk view and the dialog stay responsive).
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <QString>

#include <cmath>
#include <memory>

class QWidget;

struct MeshImportSettings
{
  /// The range of `resolution` (the dialog's and --mesh-resolution's) is every fitted grid's, `lvdif
  /// mesh-to-sdf --dims`' and vtkMeshToSDF's MaxDimension's: DictionaryVolume::MinCanvasDimension to
  /// MaxDimension, as memory allows, and at least 2 x padding + 2 (leastResolution); it was 8 to 4096 here.
  int resolution = 128; // points along the mesh's longest axis
  /// The least resolution that leaves one cell for the mesh inside the padding (2 x padding + 2), as
  /// fitGridToMesh and `lvdif mesh-to-sdf` require.
  int leastResolution() const { return static_cast<int>(std::ceil(2 * this->padding + 2)); }
  int signMode = 2;     // vtkMeshToSDF::NORMAL / PSEUDO_NORMAL / WINDING_NUMBER (default)
  double padding = 2.0; // voxels of margin around the mesh
  bool reorientFaces = false; // winding sign: of the consistently re-oriented mesh (vtkMeshToSDF::ReorientFaces)
  bool cubic = false; // the fitted grid made cubic, `resolution` points on every axis (a .bv output, as lvdif mesh-to-sdf)
};

/// Asks for the resolution, the sign mode and (winding sign) whether to
/// re-orient the faces; false if cancelled.
bool askMeshImportSettings(QWidget* parent, MeshImportSettings& settings);

/// "winding", "pseudo" or "normal" to a vtkMeshToSDF sign mode, through the
/// CLI's parser (lvdif::signModeFromName): lvdif::Error naming --mesh-sign otherwise.
int meshSignModeFromName(const QString& name);

/// Converts the mesh, showing progress under `parent`. Returns the volume, or
/// nullptr with `error` set (empty when the user cancelled). `warning`
/// (optional): what the conversion warned about (e.g. no voxel inside), or empty.
/// `console` (a batch run, which has nobody to watch a dialog): the progress
/// goes to it too, as the CLI's (the CLI's ProgressBar), and it may cancel (Ctrl-C).
std::shared_ptr<lvdif::DictionaryVolume> importMesh(QWidget* parent, const QString& path,
  const MeshImportSettings& settings, QString& error, QString* warning = nullptr,
  lvdif::Interrupter* console = nullptr);
