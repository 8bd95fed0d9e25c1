#include "lvdif/ColorDictionary.h"

#include "lvdif/Error.h"

#include <limits>
#include <sstream>

namespace lvdif
{

ColorDictionary::ColorDictionary(Rgba defaultColor, FullPolicy policy)
  : Policy(policy)
{
  this->Colors.push_back(defaultColor);
  this->reindex();
}

std::size_t ColorDictionary::probe(std::uint32_t packed) const
{
  const std::size_t mask = this->Slots.size() - 1;
  std::uint32_t h = packed * 0x9E3779B1u; // Fibonacci hashing, high bits folded down
  h ^= h >> 16;
  std::size_t i = h & mask;
  while (this->Slots[i] != 0 && this->Colors[this->Slots[i] - 1u].packed() != packed)
  {
    i = (i + 1) & mask;
  }
  return i;
}

std::size_t ColorDictionary::reindex()
{
  std::size_t n = 16;
  while (n < 2 * this->Colors.size())
  {
    n *= 2;
  }
  this->Slots.assign(n, 0);
  for (std::size_t k = 0; k < this->Colors.size(); ++k)
  {
    const std::size_t i = this->probe(this->Colors[k].packed());
    if (this->Slots[i] != 0)
    {
      return k;
    }
    this->Slots[i] = static_cast<std::uint16_t>(k + 1); // k < Capacity, so k + 1 fits
  }
  return this->Colors.size();
}

ColorKey ColorDictionary::add(Rgba color)
{
  const std::size_t slot = this->probe(color.packed());
  if (this->Slots[slot] != 0)
  {
    return static_cast<ColorKey>(this->Slots[slot] - 1u);
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
  if (2 * this->Colors.size() > this->Slots.size())
  {
    this->reindex();
  }
  else
  {
    this->Slots[slot] = static_cast<std::uint16_t>(key + 1u);
  }
  return key;
}

bool ColorDictionary::find(Rgba color, ColorKey& key) const
{
  const std::uint16_t s = this->Slots[this->probe(color.packed())];
  if (s == 0)
  {
    return false;
  }
  key = static_cast<ColorKey>(s - 1u);
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
  ColorDictionary next(colors[0], this->Policy);
  next.Colors = colors;
  const std::size_t duplicate = next.reindex();
  if (duplicate != colors.size())
  {
    std::ostringstream msg;
    msg << "colour dictionary has a duplicate colour at key " << duplicate;
    throw Error(ErrorCode::CorruptData, msg.str());
  }
  this->Colors.swap(next.Colors);
  this->Slots.swap(next.Slots);
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
