#include "lvdif/ColorDictionary.h"

#include "lvdif/Error.h"

#include <limits>
#include <sstream>

namespace lvdif
{

// The index (Index, colour -> key) is built when add() first needs it, not
// by assign(): readers assign up to 65,535 colours per file, most volumes
// read are never given a new colour, and a map node per colour dominated
// imports under the sanitizers' allocator. Index is empty or complete;
// find() scans the colours while it is empty, so it never writes.

namespace
{
/// The first key whose colour appeared at a lower key, or colors.size():
/// one open-addressing table (key + 1 per slot, 0 = empty, at most half
/// full), one allocation.
std::size_t firstRepeat(const std::vector<Rgba>& colors)
{
  std::size_t n = 16;
  while (n < 2 * colors.size())
    n *= 2;
  std::vector<std::uint32_t> slots(n, 0);
  for (std::size_t k = 0; k < colors.size(); ++k)
  {
    const std::uint32_t packed = colors[k].packed();
    std::uint32_t h = packed * 0x9E3779B1u; // Fibonacci hashing, high bits folded down
    h ^= h >> 16;
    for (std::size_t i = h & (n - 1);; i = (i + 1) & (n - 1))
    {
      if (slots[i] == 0)
      {
        slots[i] = static_cast<std::uint32_t>(k + 1);
        break;
      }
      if (colors[slots[i] - 1].packed() == packed)
        return k;
    }
  }
  return colors.size();
}
} // namespace

ColorDictionary::ColorDictionary(Rgba defaultColor, FullPolicy policy)
  : Policy(policy)
{
  this->Colors.push_back(defaultColor);
  this->Index.emplace(defaultColor.packed(), 0);
}

ColorKey ColorDictionary::add(Rgba color)
{
  if (this->Index.empty())
  {
    this->Index.reserve(this->Colors.size());
    for (std::size_t k = 0; k < this->Colors.size(); ++k)
      this->Index.emplace(this->Colors[k].packed(), static_cast<ColorKey>(k));
  }
  auto it = this->Index.find(color.packed());
  if (it != this->Index.end())
  {
    return it->second;
  }
  if (this->full())
  {
    if (this->Policy == FullPolicy::Nearest)
    {
      return this->nearest(color);
    }
    std::ostringstream msg;
    msg << "colour dictionary is full (" << Capacity << " colours); cannot add RGBA("
        << int(color.r) << "," << int(color.g) << "," << int(color.b) << "," << int(color.a)
        << "); choose the Nearest policy to reuse the closest colour";
    throw Error(ErrorCode::DictionaryFull, msg.str());
  }
  const ColorKey key = static_cast<ColorKey>(this->Colors.size());
  this->Colors.push_back(color);
  this->Index.emplace(color.packed(), key);
  return key;
}

bool ColorDictionary::find(Rgba color, ColorKey& key) const
{
  if (this->Index.empty())
  {
    for (std::size_t k = 0; k < this->Colors.size(); ++k)
      if (this->Colors[k] == color)
      {
        key = static_cast<ColorKey>(k);
        return true;
      }
    return false;
  }
  auto it = this->Index.find(color.packed());
  if (it == this->Index.end())
  {
    return false;
  }
  key = it->second;
  return true;
}

Rgba ColorDictionary::color(ColorKey key) const
{
  if (key >= this->Colors.size())
  {
    std::ostringstream msg;
    msg << "colour key " << key << " is not in the dictionary (" << this->Colors.size()
        << " colours)";
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
  return this->Colors[key];
}

void ColorDictionary::assign(const std::vector<Rgba>& colors)
{
  if (colors.empty() || colors.size() > Capacity)
  {
    std::ostringstream msg;
    msg << "colour dictionary must hold 1 to " << Capacity << " colours, got " << colors.size();
    throw Error(ErrorCode::CorruptData, msg.str());
  }
  const std::size_t repeat = firstRepeat(colors);
  if (repeat != colors.size())
  {
    std::ostringstream msg;
    msg << "colour dictionary has a duplicate colour at key " << repeat;
    throw Error(ErrorCode::CorruptData, msg.str());
  }
  this->Colors = colors;
  std::unordered_map<std::uint32_t, ColorKey>().swap(this->Index); // built by the next add()
}

ColorKey ColorDictionary::nearest(Rgba c) const
{
  long best = std::numeric_limits<long>::max();
  ColorKey bestKey = 0;
  for (std::size_t i = 0; i < this->Colors.size(); ++i)
  {
    const Rgba& o = this->Colors[i];
    const long dr = long(c.r) - o.r, dg = long(c.g) - o.g, db = long(c.b) - o.b,
               da = long(c.a) - o.a;
    const long d = dr * dr + dg * dg + db * db + da * da;
    if (d < best)
    {
      best = d;
      bestKey = static_cast<ColorKey>(i);
    }
  }
  return bestKey;
}

} // namespace lvdif
