// Numbers as text in the "C" locale, whatever the process's: the numbers in
// meshes, scripts, recordings and settings are C text ("0.5"), but a host may
// have set LC_NUMERIC to a comma-decimal locale (Qt applications take it from
// the environment; so may a Python or ParaView session), and strtod and
// printf follow it: "0.5" was then read as 0 or refused, and recordings were
// written with "0,5". Every text-to-number and number-to-text conversion of
// the core that meets files goes through these two.
#pragma once

#include <cstddef>

namespace lvdif
{

/// std::strtod in the "C" locale: the same syntax (leading blanks, a sign,
/// decimal and hexadecimal forms, inf and nan) and the same `end`.
double strtodC(const char* text, char** end);

/// std::snprintf of one double in the "C" locale (format: one conversion,
/// e.g. "%.17g").
int formatDoubleC(char* buffer, std::size_t size, const char* format, double value);

} // namespace lvdif
