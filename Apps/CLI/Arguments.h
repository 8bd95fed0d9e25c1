// Minimal command-line parsing: positional arguments and `--key value` /
// `--flag` options, with errors that name the bad option.
#pragma once

#include <map>
#include <string>
#include <vector>

class Arguments
{
public:
  /// argv[first..argc) are parsed; `flags` lists options that take no value.
  Arguments(int argc, char** argv, int first, const std::vector<std::string>& flags = {});
  const std::vector<std::string>& positional() const { return this->Positional; }
  bool has(const std::string& key) const { return this->Options.count(key) != 0; }
  std::string get(const std::string& key, const std::string& fallback) const;
  long getInt(const std::string& key, long fallback) const;
  double getDouble(const std::string& key, double fallback) const;
  /// An integer edge length N for a new N x N x N canvas, refused (naming the
  /// option) unless the editors' one canvas rule accepts it.
  long getCanvasSize(const std::string& key, long fallback) const;
  /// Throws lvdif::Error(InvalidArgument) naming any option not in `known`.
  void allowOnly(const std::vector<std::string>& known) const;

private:
  std::vector<std::string> Positional;
  std::map<std::string, std::string> Options;
};
