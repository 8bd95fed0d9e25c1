// The action recorder's format (paper Sect. 3.4.2: "recorded input actions can
// be used to reconstruct a CSG-based volume model"). A recording is a list of
// edits, each with every parameter needed to redo it, plus undo/redo events.
// Text format (docs/RECORDING.md):
//
//   LVDIF-RECORDING 2
//   canvas 64 64 64
//   edit time=0.25 op=add shape=sphere kind=basic spacing=1.6 blend=0 coloroffset=1.5 color=255,0,0,255 dabs=2
//   d 10 20 30 3
//   d 11.6 20 30 3
//   undo time=1.5
//   end records=2
//
// A recording with a `fill time=T sdf=D color=r,g,b,a` record (every voxel set:
// a script's `canvas fill|clear`) is written as version 3, one of a non-cubic
// canvas as version 4.
//
// Numbers are written with 17 significant digits, so reading a recording gives
// the same doubles and playing it back (Editor::play) on the same start volume
// reproduces the volume bit for bit. The player applies the recorded dabs as
// they are (as the original's player does): strokes are not re-interpolated.
//
// importOriginalCsv() reads the original LVDIF recorder's CSV
// (original-code-spec.md section 6.2): positions are in kernel order (z, y, x)
// in voxels of the original N^3 volume, so they are swapped to (x, y, z) and
// scaled by targetSize / originalSize; radii are scaled the same way.
#pragma once

#include "lvdif/Stroke.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace lvdif
{

struct EditRecord
{
  enum class Type
  {
    Edit,
    Undo,
    Redo,
    /// Every voxel set to one value (a script's `canvas fill|clear`,
    /// Editor::fillVolume): `sdf` and the colour brush.color. Not undoable.
    Fill
  };
  Type type = Type::Edit;
  double time = 0;
  BrushSettings brush;
  double sdf = 0; // a Fill record's distance (decoded, so another dictionary encodes it again)
  BrushKind kind = BrushKind::Single;
  double spacing = 1.6;
  std::vector<Dab> dabs;
};

struct Recording
{
  /// The newest version. Version 2 ends with `end records=N`, so that a file
  /// cut short (at a line or inside a number) is refused; version 3 adds the
  /// `fill` record and is written only for a recording that has one (others are
  /// written as version 2, which older builds read). Version 4 is written for a
  /// recording of a non-cubic canvas (and may hold fill records): it was made
  /// where the editors' starter shape on such a canvas is the rounded box that
  /// spans it (since session 24; a sphere of the smallest axis's size before), so
  /// that a player can start from the canvas it was recorded on (docs/RECORDING.md).
  /// Version 1 files (no end record) are still read, with `warning` set.
  static constexpr int Version = 4;
  /// The version line of the file read (readRecording); writeRecording writes
  /// the lowest version that holds the recording, whatever this says.
  int version = Version;
  /// Dimensions of the volume it was recorded on (the `canvas` line; {0, 0, 0}:
  /// not known, as in recordings written before it and imported CSVs).
  /// Editor::play refuses a volume of other dimensions before applying anything.
  Index3 canvas{ 0, 0, 0 };
  std::vector<EditRecord> records;
  /// Set by readRecording for a version 1 file: it has no end record, so a cut
  /// one cannot be told from a whole one. Front ends print it as one warning.
  std::string warning;
};

void writeRecording(std::ostream& out, const Recording& recording);
/// Throws Error(ParseError) naming the line for any malformed input.
/// Errors name the source: "<name>:<line>:<column>: what".
Recording readRecording(std::istream& in, const std::string& name = "recording");
void saveRecording(const std::string& path, const Recording& recording);
Recording loadRecording(const std::string& path);

struct CsvImportOptions
{
  /// Edge N of the volume the CSV was recorded on (its file name says it:
  /// Recording_<N>_<date>.csv).
  double originalSize = 128;
  /// Edge of the volume it will be played on; coordinates scale by target/original.
  double targetSize = 128;
  /// The colour of each palette index (the original does not store its palette);
  /// empty means defaultCsvPalette().
  std::vector<Rgba> palette;
};

struct CsvImportResult
{
  Recording recording;
  std::size_t skippedRows = 0; // rows that were not 10 valid fields ("Broken frame")
  std::string firstProblem;    // "line N: what" for the first skipped row
};

/// Ten distinct colours used for palette indices when none is given (our choice,
/// not the original Unity palette, which its files do not record); index i wraps mod 10.
const std::vector<Rgba>& defaultCsvPalette();

CsvImportResult importOriginalCsv(std::istream& in, const CsvImportOptions& options);

} // namespace lvdif
