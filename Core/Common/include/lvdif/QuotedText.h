// Text from an input (a file's token, a script's name or number) quoted for a
// one-line message: the one rule of the mesh readers, the script language and
// recordings.
#pragma once

#include <algorithm>
#include <string>

namespace lvdif
{

/// `text` in single quotes, at most 40 bytes of it then "...", every byte that
/// is not printable ASCII as \xHH. A token of 100,000 characters was quoted whole
/// (a script's "number '1111...' is out of range" was a 100 kB line), and raw
/// bytes ended a message at their first NUL.
inline std::string quotedText(const std::string& text)
{
  std::string q = "'";
  const std::size_t n = std::min<std::size_t>(text.size(), 40);
  for (std::size_t i = 0; i < n; ++i)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f)
    {
      q += static_cast<char>(c);
      continue;
    }
    static const char hex[] = "0123456789abcdef";
    q += "\\x";
    q += hex[c >> 4];
    q += hex[c & 15];
  }
  return q + (text.size() > n ? "...'" : "'");
}

} // namespace lvdif
