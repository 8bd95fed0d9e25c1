// Minimal command-line parsing: positional arguments and `--key value` (or `--key=value`) /
// `--flag` options, with errors that name the bad option.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

/// The one guard of a number's text before it is read (strtol, strtod, or the editor's Qt
/// conversions): not empty, no white space around it (strtol and strtod skip it: --size " 32" was
/// taken as 32, and so was the editor's --new " 32") and no hexadecimal (strtod reads --padding
/// 0x10 as 16).
bool plainNumberText(const std::string& v);
/// " (no spaces around the number)" when `v` has white space at either end, else "": what a
/// refusal of such a text adds, since a quoted " 32" reads like 32 in a terminal.
std::string numberTextHint(const std::string& v);

class Arguments
{
public:
  /// argv[first..argc) are parsed: `valued` lists the options that take a
  /// value, `flags` those that take none; any other option is refused with
  /// Error(InvalidArgument) "unknown option --x" where it stands.
  Arguments(int argc, char** argv, int first, const std::vector<std::string>& valued,
    const std::vector<std::string>& flags = {});
  const std::vector<std::string>& positional() const { return this->Positional; }
  bool has(const std::string& key) const { return this->Options.count(key) != 0; }
  std::string get(const std::string& key, const std::string& fallback) const;
  /// The one number guard of every option: the whole text must be a number
  /// inside [lo, hi] (NaN never is; an integer beyond long's range is not
  /// clamped), else Error(InvalidArgument) quoting the text and the range.
  long getInt(const std::string& key, long fallback, long lo, long hi) const;
  /// Any number but NaN unless a range is given; infinity only where hi (lo) is.
  double getDouble(const std::string& key, double fallback, double lo = -HUGE_VAL, double hi = HUGE_VAL) const;
  /// An integer edge length N for a new N x N x N canvas, refused (naming the
  /// option) unless the editors' one canvas rule accepts it.
  long getCanvasSize(const std::string& key, long fallback) const;
  /// A canvas of N^3 or NXxNYxNZ voxels (fallback: a cube), by the same canvas rule.
  std::array<std::int64_t, 3> getCanvasDims(const std::string& key, long fallback) const;

private:
  std::vector<std::string> Positional;
  std::map<std::string, std::string> Options;
};
