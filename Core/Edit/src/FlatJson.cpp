#include "FlatJson.h"
#include "lvdif/CNumbers.h"

#include <cmath>
#include <cstdlib>

namespace lvdif
{
namespace detail::edit
{
namespace
{
struct Cursor
{
  const std::string& s;
  std::size_t i = 0;
  std::string err;

  void ws()
  {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == '\n'))
      ++i;
  }
  bool fail(const std::string& what)
  {
    if (err.empty())
      err = "column " + std::to_string(i + 1) + ": " + what;
    return false;
  }
  bool expect(char c)
  {
    ws();
    if (i < s.size() && s[i] == c)
    {
      ++i;
      return true;
    }
    return fail(std::string("expected '") + c + "'");
  }
  bool string(std::string& out)
  {
    ws();
    if (i >= s.size() || s[i] != '"')
      return fail("expected a string");
    ++i;
    out.clear();
    while (i < s.size() && s[i] != '"')
    {
      if (s[i] == '\\')
      {
        if (i + 1 >= s.size())
          return fail("unterminated escape");
        const char e = s[i + 1];
        if (e == 'u')
          return fail("\\u escapes are not supported");
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e;
        i += 2;
        continue;
      }
      if (static_cast<unsigned char>(s[i]) < 0x20)
        return fail("control character in string");
      out += s[i++];
    }
    if (i >= s.size())
      return fail("unterminated string");
    ++i;
    return true;
  }
  bool number(double& out)
  {
    ws();
    // JSON grammar: -?digits(.digits)?([eE][+-]?digits)?
    const std::size_t start = i;
    if (i < s.size() && s[i] == '-')
      ++i;
    const std::size_t digits = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9')
      ++i;
    if (i == digits)
      return fail("expected a number");
    if (i < s.size() && s[i] == '.')
    {
      ++i;
      const std::size_t f = i;
      while (i < s.size() && s[i] >= '0' && s[i] <= '9')
        ++i;
      if (i == f)
        return fail("expected digits after '.'");
    }
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E'))
    {
      ++i;
      if (i < s.size() && (s[i] == '+' || s[i] == '-'))
        ++i;
      const std::size_t e = i;
      while (i < s.size() && s[i] >= '0' && s[i] <= '9')
        ++i;
      if (i == e)
        return fail("expected an exponent");
    }
    out = strtodC(s.substr(start, i - start).c_str(), nullptr);
    if (!std::isfinite(out))
      return fail("number out of range");
    return true;
  }
  bool literal(const char* word, double value, FlatJsonValue& v)
  {
    const std::string w(word);
    if (s.compare(i, w.size(), w) != 0)
      return fail("unexpected character");
    i += w.size();
    v.numbers.push_back(value);
    return true;
  }
  bool value(FlatJsonValue& v)
  {
    ws();
    if (i >= s.size())
      return fail("expected a value");
    const char c = s[i];
    if (c == '[')
    {
      ++i;
      v.isArray = true;
      ws();
      if (i < s.size() && s[i] == ']')
      {
        ++i;
        return true;
      }
      for (;;)
      {
        double x;
        if (!number(x))
          return false;
        if (v.numbers.size() > 64)
          return fail("array too long");
        v.numbers.push_back(x);
        ws();
        if (i < s.size() && s[i] == ',')
        {
          ++i;
          continue;
        }
        return expect(']');
      }
    }
    if (c == '"')
    {
      v.isString = true;
      return string(v.text);
    }
    if (c == 't')
      return literal("true", 1, v);
    if (c == 'f')
      return literal("false", 0, v);
    if (c == 'n')
      return literal("null", NAN, v);
    if (c == '{')
      return fail("nested objects are not supported");
    double x;
    if (!number(x))
      return false;
    v.numbers.push_back(x);
    return true;
  }
};
} // namespace

bool parseFlatJson(const std::string& line, std::map<std::string, FlatJsonValue>& out, std::string* error)
{
  out.clear();
  Cursor c{ line, 0, std::string() };
  bool ok = c.expect('{');
  c.ws();
  if (ok && c.i < line.size() && line[c.i] == '}')
  {
    ++c.i;
  }
  else
  {
    while (ok)
    {
      std::string key;
      FlatJsonValue v;
      ok = c.string(key) && c.expect(':') && c.value(v);
      if (!ok)
        break;
      out[key] = v;
      c.ws();
      if (c.i < line.size() && line[c.i] == ',')
      {
        ++c.i;
        continue;
      }
      ok = c.expect('}');
      break;
    }
  }
  if (ok)
  {
    c.ws();
    if (c.i != line.size())
      ok = c.fail("text after the object");
  }
  if (!ok && error)
    *error = c.err;
  return ok;
}

} // namespace detail::edit
} // namespace lvdif
