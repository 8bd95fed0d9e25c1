// Lexer of the scripting language: numbers, identifiers, operators, newlines
// (statement ends); '#' starts a comment to the end of the line.
#include "ScriptAst.h"
#include "lvdif/CNumbers.h"

#include "lvdif/Memory.h"
#include "lvdif/Script.h"
#include "lvdif/QuotedText.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace lvdif
{
namespace detail::script
{

std::vector<Token> lex(const std::string& src)
{
  // Every token takes at least one byte of the source and becomes at most one
  // syntax node and one chain operator, so the source's size bounds what
  // lexing and parsing hold (tokens with the vector's growth, then the tree):
  // checked before either starts. A 10 MiB chain of "1+" took 1.5 GiB, and a
  // script of a few hundred MiB ended in the out-of-memory killer.
  constexpr std::uint64_t perByte = 2 * sizeof(Token) + sizeof(Expr) + sizeof(Expr::Op);
  requireMemory(checkedMultiply(src.size() + 1, perByte, "script"),
    "lexing and parsing a script of " + formatBytes(src.size()));
  std::vector<Token> out;
  int line = 1, col = 1;
  // a UTF-8 byte order mark before the text (Windows editors write one) is not
  // part of it: it was "line 1, column 1: unexpected character byte 239"
  std::size_t i = src.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  auto push = [&](Tok k, const std::string& text, int l, int c) {
    Token t;
    t.kind = k;
    t.text = text;
    t.line = l;
    t.column = c;
    out.push_back(t);
  };
  while (i < src.size())
  {
    const char ch = src[i];
    const int l = line, c = col;
    // a line ends at LF, CRLF or a lone CR (classic Mac files: one long line before)
    if (ch == '\n' || (ch == '\r' && !(i + 1 < src.size() && src[i + 1] == '\n')))
    {
      push(Tok::Newline, "\\n", l, c);
      ++i;
      ++line;
      col = 1;
      continue;
    }
    if (ch == ' ' || ch == '\t' || ch == '\r')
    {
      ++i;
      ++col;
      continue;
    }
    if (ch == '#')
    {
      while (i < src.size() && src[i] != '\n' && src[i] != '\r')
        ++i;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(ch)) ||
      (ch == '.' && i + 1 < src.size() && std::isdigit(static_cast<unsigned char>(src[i + 1]))))
    {
      std::size_t j = i;
      while (j < src.size() && std::isdigit(static_cast<unsigned char>(src[j])))
        ++j;
      // a '.' followed by '.' is the range operator, not a decimal point
      if (j < src.size() && src[j] == '.' && !(j + 1 < src.size() && src[j + 1] == '.'))
      {
        ++j;
        while (j < src.size() && std::isdigit(static_cast<unsigned char>(src[j])))
          ++j;
      }
      if (j < src.size() && (src[j] == 'e' || src[j] == 'E'))
      {
        std::size_t k = j + 1;
        if (k < src.size() && (src[k] == '+' || src[k] == '-'))
          ++k;
        if (k < src.size() && std::isdigit(static_cast<unsigned char>(src[k])))
        {
          j = k;
          while (j < src.size() && std::isdigit(static_cast<unsigned char>(src[j])))
            ++j;
        }
      }
      const std::string text = src.substr(i, j - i);
      Token t;
      t.kind = Tok::Number;
      t.text = text;
      t.number = strtodC(text.c_str(), nullptr);
      t.line = l;
      t.column = c;
      if (!std::isfinite(t.number))
        throw ScriptError(ErrorCode::ParseError, l, c, "number " + quotedText(text) + " is out of range");
      if (j < src.size() && (std::isalpha(static_cast<unsigned char>(src[j])) || src[j] == '_'))
        throw ScriptError(ErrorCode::ParseError, l, c + static_cast<int>(j - i),
          std::string("unexpected '") + src[j] + "' after a number");
      out.push_back(t);
      col += static_cast<int>(j - i);
      i = j;
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(ch)) || ch == '_')
    {
      std::size_t j = i;
      while (j < src.size() && (std::isalnum(static_cast<unsigned char>(src[j])) || src[j] == '_'))
        ++j;
      push(Tok::Ident, src.substr(i, j - i), l, c);
      col += static_cast<int>(j - i);
      i = j;
      continue;
    }
    const char next = i + 1 < src.size() ? src[i + 1] : '\0';
    auto two = [&](Tok k, const char* text) {
      push(k, text, l, c);
      i += 2;
      col += 2;
    };
    auto one = [&](Tok k) {
      push(k, std::string(1, ch), l, c);
      ++i;
      ++col;
    };
    switch (ch)
    {
      case '.':
        if (next == '.')
        {
          two(Tok::DotDot, "..");
          continue;
        }
        break;
      case '=':
        if (next == '=')
          two(Tok::Eq, "==");
        else
          one(Tok::Assign);
        continue;
      case '!':
        if (next == '=')
        {
          two(Tok::Ne, "!=");
          continue;
        }
        break;
      case '<':
        if (next == '=')
          two(Tok::Le, "<=");
        else
          one(Tok::Lt);
        continue;
      case '>':
        if (next == '=')
          two(Tok::Ge, ">=");
        else
          one(Tok::Gt);
        continue;
      case '(': one(Tok::LParen); continue;
      case ')': one(Tok::RParen); continue;
      case '{': one(Tok::LBrace); continue;
      case '}': one(Tok::RBrace); continue;
      case ',': one(Tok::Comma); continue;
      case ';': one(Tok::Semicolon); continue;
      case '+': one(Tok::Plus); continue;
      case '-': one(Tok::Minus); continue;
      case '*': one(Tok::Star); continue;
      case '/': one(Tok::Slash); continue;
      case '%': one(Tok::Percent); continue;
      default: break;
    }
    const unsigned char u = static_cast<unsigned char>(ch);
    std::string shown = std::isprint(u) ? std::string("'") + ch + "'" : "byte " + std::to_string(int(u));
    // a UTF-8 character (text copied from a web page or a word processor): shown whole, with its
    // code point and, for the look-alikes of a space or a minus, what to type (it was "byte 194")
    const int more = (u & 0xE0) == 0xC0 ? 1 : (u & 0xF0) == 0xE0 ? 2 : (u & 0xF8) == 0xF0 ? 3 : -1;
    if (more > 0)
    {
      std::uint32_t cp = u & (0x3F >> more);
      bool valid = i + static_cast<std::size_t>(more) < src.size();
      for (int k = 1; valid && k <= more; ++k)
      {
        const unsigned char b = static_cast<unsigned char>(src[i + static_cast<std::size_t>(k)]);
        valid = (b & 0xC0) == 0x80;
        cp = (cp << 6) | (b & 0x3F);
      }
      if (valid && cp >= 0x80)
      {
        char hex[16];
        std::snprintf(hex, sizeof hex, "U+%04X", static_cast<unsigned>(cp));
        const bool space = cp == 0xA0 || (cp >= 0x2000 && cp <= 0x200B) || cp == 0x202F || cp == 0x3000;
        const bool minus = cp == 0x2212 || (cp >= 0x2010 && cp <= 0x2015);
        shown = space ? std::string(hex) + " (a no-break or other wide space: type a plain space)"
          : "'" + src.substr(i, static_cast<std::size_t>(more) + 1) + "' " + hex +
            (minus ? " (a dash or minus sign: type '-')" : " (scripts are ASCII outside comments)");
      }
    }
    throw ScriptError(ErrorCode::ParseError, l, c, "unexpected character " + shown);
  }
  push(Tok::End, "end of script", line, col);
  return out;
}

} // namespace detail::script
} // namespace lvdif
