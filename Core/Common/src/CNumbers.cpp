#include "lvdif/CNumbers.h"

#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <locale.h> // newlocale, uselocale, strtod_l (POSIX 2008, glibc)

namespace lvdif
{
namespace
{
/// The "C" locale as an object, made once (never freed: it lives as long as
/// the process).
locale_t cLocale()
{
  static const locale_t c = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
  return c;
}
} // namespace

double strtodC(const char* text, char** end)
{
  return strtod_l(text, end, cLocale());
}

int formatDoubleC(char* buffer, std::size_t size, const char* format, double value)
{
  // uselocale changes this thread's locale only, and only until it is set back
  const locale_t previous = uselocale(cLocale());
  const int n = std::snprintf(buffer, size, format, value);
  uselocale(previous);
  return n;
}

} // namespace lvdif
