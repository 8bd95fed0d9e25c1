#include "LVDIFXmlNesting.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace LVDIFFiles
{

void RequireXmlNestingBelow(const std::string& path, int limit, const std::string& what)
{
  lvdif::FileSource file(path);
  const std::uint64_t size = file.size();
  std::vector<char> block(std::size_t(1) << 20);
  std::uint64_t at = 0; // file offset of block[0]
  std::size_t have = 0, i = 0;
  auto refill = [&] {
    at += have;
    have = at < size ? static_cast<std::size_t>(std::min<std::uint64_t>(block.size(), size - at)) : 0;
    if (have)
      file.read(at, block.data(), have);
    i = 0;
    return have > 0;
  };
  // the next byte; false at the end of the file
  auto next = [&](char& c) {
    if (i == have && !refill())
      return false;
    c = block[i++];
    return true;
  };
  // skips past `close` (a comment's "-->", a processing instruction's "?>")
  auto skipPast = [&](const char* close) {
    const std::size_t n = std::strlen(close);
    std::size_t matched = 0;
    char c;
    while (matched < n && next(c))
      matched = c == close[matched] ? matched + 1 : (c == close[0] ? 1 : 0);
  };
  int depth = 0;
  for (;;)
  {
    // the text up to the next tag
    for (;;)
    {
      if (i == have && !refill())
        return;
      const void* lt = std::memchr(block.data() + i, '<', have - i);
      if (lt)
      {
        i = static_cast<std::size_t>(static_cast<const char*>(lt) - block.data()) + 1;
        break;
      }
      i = have;
    }
    char c;
    if (!next(c))
      return;
    if (c == '?')
    {
      skipPast("?>");
      continue;
    }
    if (c == '!')
    {
      char d = 0;
      if (next(d) && d == '-')
        skipPast("-->");
      else if (d == '[')
        skipPast("]]>");
      else
        skipPast(">");
      continue;
    }
    // the tag: its name (AppendedData is followed by raw bytes) and its end, a '>'
    // outside quoted attribute values; "<x/>" opens and closes
    const bool closing = c == '/';
    std::string name(closing ? "" : std::string(1, c));
    bool inName = !closing, ended = false;
    char quote = 0, last = c;
    while (next(c))
    {
      if (quote)
        quote = c == quote ? 0 : quote;
      else if (c == '"' || c == '\'')
        quote = c;
      else if (c == '>')
      {
        ended = true;
        break;
      }
      inName = inName && !(c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '/');
      if (inName && name.size() < 32)
        name.push_back(c);
      last = c;
    }
    if (!ended)
      return; // a tag cut off: VTK's parser says so
    if (closing)
      depth = std::max(0, depth - 1);
    else if (last != '/')
    {
      if (++depth > limit)
        throw lvdif::Error(lvdif::ErrorCode::CorruptData,
          what + ": XML elements nested more than " + std::to_string(limit) + " deep (a VTK file nests a few)");
      if (name == "AppendedData")
        return;
    }
  }
}

} // namespace LVDIFFiles
