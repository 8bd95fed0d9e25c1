// strtodC / formatDoubleC: strtod's syntax, and C text whatever LC_NUMERIC is.
#include "lvdif/CNumbers.h"

#include "CommaLocale.h"

#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <cstdlib>
#include <string>

namespace
{
std::string formatted(const char* format, double v)
{
  char buf[64];
  lvdif::formatDoubleC(buf, sizeof(buf), format, v);
  return buf;
}

} // namespace

TEST(CNumbers, ReadsWhatStrtodReads)
{
  // the same value and the same end as strtod in the C locale (the tests run in it)
  for (const char* t : { "0.5", "  -2.5x", "+1e3", "0x1p-2", "inf", "-INFINITY", "1e400", ".25e-1", "abc", "" })
  {
    char* endC = nullptr;
    char* endStd = nullptr;
    const double c = lvdif::strtodC(t, &endC), s = std::strtod(t, &endStd);
    EXPECT_TRUE(c == s || (std::isnan(c) && std::isnan(s))) << t;
    EXPECT_EQ(endC - t, endStd - t) << t;
  }
  char* end = nullptr;
  EXPECT_TRUE(std::isnan(lvdif::strtodC("nan", &end)));
  EXPECT_EQ(lvdif::strtodC("0x1p-2", nullptr), 0.25);
  EXPECT_EQ(formatted("%.17g", 0.1), "0.10000000000000001");
  EXPECT_EQ(formatted("%.6g", 1234567.0), "1.23457e+06");
}

TEST(CNumbers, CTextUnderACommaLocale)
{
  lvdif::test::CommaLocale comma;
  if (!comma.made) GTEST_SKIP() << "no comma-decimal locale could be made (localedef)";
  // the premise: under this locale the C library's own conversions differ
  char* end = nullptr;
  EXPECT_EQ(std::strtod("0.5", &end), 0.0);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", 0.5);
  EXPECT_STREQ(buf, "0,5");
  // ours do not
  const char* t = "0.5 ";
  EXPECT_EQ(lvdif::strtodC(t, &end), 0.5);
  EXPECT_EQ(end, t + 3);
  EXPECT_EQ(lvdif::strtodC("-1.25e-2", nullptr), -0.0125);
  EXPECT_EQ(formatted("%.17g", 0.5), "0.5");
  EXPECT_EQ(formatted("%.6g", 2.75), "2.75");
  // and the thread's locale is the process's again afterwards
  std::snprintf(buf, sizeof(buf), "%.1f", 0.5);
  EXPECT_STREQ(buf, "0,5");
}
