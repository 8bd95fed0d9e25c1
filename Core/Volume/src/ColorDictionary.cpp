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
  this->Index.emplace(defaultColor.packed(), 0);
}

ColorKey ColorDictionary::add(Rgba color)
{
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
  std::unordered_map<std::uint32_t, ColorKey> index;
  index.reserve(colors.size());
  for (std::size_t i = 0; i < colors.size(); ++i)
  {
    if (!index.emplace(colors[i].packed(), static_cast<ColorKey>(i)).second)
    {
      std::ostringstream msg;
      msg << "colour dictionary has a duplicate colour at key " << i;
      throw Error(ErrorCode::CorruptData, msg.str());
    }
  }
  this->Colors = colors;
  this->Index.swap(index);
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
