// A comma-decimal LC_NUMERIC for the tests of the C-text conversions
// (lvdif/CNumbers.h): de_DE.UTF-8, compiled with localedef into a temporary
// folder where the system has none (CI images carry only C and POSIX).
#pragma once

#include <clocale>
#include <cstdlib>
#include <string>
#include <unistd.h>

namespace lvdif::test
{

/// Sets LC_NUMERIC to a comma-decimal locale (de_DE.UTF-8, compiled with
/// localedef into a temporary folder where the system has none) and back
/// to "C" when it goes; `made` is false where no such locale can be made.
struct CommaLocale
{
  std::string dir;
  bool made = false;
  CommaLocale()
  {
    char tmpl[] = "/tmp/lvdif-locale-XXXXXX";
    if (!mkdtemp(tmpl)) return;
    dir = tmpl;
    if (!std::setlocale(LC_NUMERIC, "de_DE.UTF-8"))
    {
      const std::string cmd = "localedef -i de_DE -f UTF-8 " + dir + "/de_DE.UTF-8 > /dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0 && access((dir + "/de_DE.UTF-8/LC_NUMERIC").c_str(), F_OK) != 0) return;
      setenv("LOCPATH", dir.c_str(), 1);
      if (!std::setlocale(LC_NUMERIC, "de_DE.UTF-8")) return;
    }
    made = std::localeconv()->decimal_point[0] == ',';
  }
  ~CommaLocale()
  {
    std::setlocale(LC_NUMERIC, "C");
    unsetenv("LOCPATH");
    if (!dir.empty()) static_cast<void>(std::system(("rm -rf " + dir).c_str()));
  }
};

} // namespace lvdif::test
