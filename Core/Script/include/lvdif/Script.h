// The LVDIF scripting language (paper Sect. 3.4.2, Fig. 9; docs/SCRIPTING.md):
// a small language with variables, arithmetic, loops, conditionals and math
// functions whose commands drive the same edit API as every other front end
// (lvdif::Editor). Programs build models procedurally, e.g.
//
//   canvas 128
//   brush cube
//   color 120 190 255
//   cube 64 64 64 40
//   op subtract
//   for i in 0..3 { sphere 30 + 20*i, 64, 104, 8 }
//
// Errors carry the line and column (1-based) of the offending token. Running
// counts steps (statements and loop iterations) and stops with an error past
// ScriptOptions::maxSteps, so no script can hang the application; an
// Interrupter reports progress and can cancel.
#pragma once

#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Interrupter.h"

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>

namespace lvdif
{

/// Nesting limit of blocks (if, else, for, while), and separately of an
/// expression's parentheses, unary operators and call arguments: parsing and
/// evaluation recurse once per level, so the bounds (at most 2 x 200 levels
/// in all) keep any script from exhausting the stack. Chains (1+1+1...,
/// else if ...) do not nest and have no limit of their own.
constexpr int ScriptMaxNesting = 200;

class ScriptError : public Error
{
public:
  ScriptError(ErrorCode code, int line, int column, const std::string& what);
  int line() const { return this->Line; }
  int column() const { return this->Column; }
  /// The message without the "line L, column C: " prefix.
  const std::string& detail() const { return this->Detail; }

private:
  int Line, Column;
  std::string Detail;
};

struct ScriptOptions
{
  std::uint64_t maxSteps = 50'000'000;
  /// How the caller lets a user raise maxSteps (e.g. "--max-steps N"), named in the
  /// step-limit error, or empty (the message then only asks about an endless loop).
  std::string maxStepsRaisedBy;
  /// Options of volumes made by `canvas` (its dims replace options.dims).
  VolumeOptions canvas;
  /// Output of `print` (default: standard output).
  std::function<void(const std::string&)> print;
  Interrupter* interrupter = nullptr;
  /// Largest voxel count `canvas` may ask for, for callers that want a
  /// bound of their own (a fuzzer); by default none but every volume's:
  /// 2..1048576 voxels per axis and a chunk table within the memory limit,
  /// checked before allocating. (It was 2^32, so `canvas 2048` was refused
  /// while the editors and `lvdif script --size 2048` made that canvas.)
  std::int64_t maxCanvasVoxels = std::numeric_limits<std::int64_t>::max();
  /// Where the caller fixed the start canvas's size (e.g. "--size 64"), or
  /// empty: a script with a `canvas N` statement anywhere (taken or not) is
  /// then refused before anything runs, at that statement, naming this (the
  /// script's canvas silently replaced the one of `lvdif script --size`).
  std::string canvasSizeGivenBy;
  /// The rule the volume the script leaves must meet (e.g. its output file's:
  /// a .bv is cubic, a .vdb has one spacing), given its dimensions and spacing,
  /// as "" or the reason it fails: checked on the attached volume before
  /// anything runs when the script has no `canvas N`, and by each `canvas N`
  /// before it makes its canvas (an error at that statement), so a script is
  /// not run to the end for a volume that cannot be saved.
  std::function<std::string(const Index3& dims, const std::array<double, 3>& spacing)> resultRule;
};

/// Parses only (syntax and command names/arity); throws ScriptError (ParseError).
void checkScript(const std::string& source);

/// The text of a script file, the one reader of every front end (lvdif script,
/// vtkLVDIFEditor::RunScriptFile, the Qt editor): FIFOs, directories and devices
/// are refused without blocking (Error naming the path), the size is checked
/// against the memory limit before reading.
std::string readScriptFile(const std::string& path);

class ScriptRunner
{
public:
  explicit ScriptRunner(const ScriptOptions& options = ScriptOptions());
  ~ScriptRunner();

  /// Scripts edit this volume until a `canvas` command makes a new one.
  void attach(DictionaryVolume& volume);
  /// Scripts drive this editor (its undo stack and recording, starting from its
  /// brush) until a `canvas` command makes a new volume. The editor must outlive the run.
  void attach(Editor& editor);
  /// Parses and runs; throws ScriptError (syntax: ParseError; run time:
  /// InvalidArgument) or Error(Cancelled).
  void run(const std::string& source);

  DictionaryVolume* volume();
  /// The volume made by `canvas` (nullptr if the script edits an attached one).
  std::unique_ptr<DictionaryVolume> takeVolume();
  Editor* editor();
  std::uint64_t steps() const { return this->Steps; }
  /// Edits applied (dabs, primitives, lines and strokes), for tests and the CLI.
  std::uint64_t edits() const { return this->Edits; }
  double variable(const std::string& name) const;

  struct Impl;

private:
  std::unique_ptr<Impl> P;
  std::uint64_t Steps = 0;
  std::uint64_t Edits = 0;
};

} // namespace lvdif
