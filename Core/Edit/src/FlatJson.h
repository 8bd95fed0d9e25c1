// A minimal parser for ONE flat JSON object per line: string keys whose values
// are numbers, arrays of numbers, true/false/null, or strings (kept as text).
// Nested objects and arrays of non-numbers are refused. Hand-written so the
// core needs no JSON library; the socket input device is its only user.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace lvdif
{
namespace detail::edit
{

struct FlatJsonValue
{
  std::vector<double> numbers; // a number is a one-element list
  bool isArray = false;
  bool isString = false;
  std::string text;
};

/// Returns false with "column N: what" in *error on failure.
bool parseFlatJson(const std::string& line, std::map<std::string, FlatJsonValue>& out, std::string* error);

} // namespace detail::edit
} // namespace lvdif
