// The colour dictionary: up to 65,535 distinct RGBA colours, each named by a
// 16-bit key stored in every voxel. Colours are deduplicated; key 0 always
// exists and holds the default colour of unpainted material.
//
// When the dictionary is full, add() follows the policy chosen at
// construction: FullPolicy::Error (the default) throws Error(DictionaryFull);
// FullPolicy::Nearest returns the key of the nearest stored colour
// (Euclidean distance in RGBA, lowest key on ties) without adding.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace lvdif
{

using ColorKey = std::uint16_t;

struct Rgba
{
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  std::uint32_t packed() const
  {
    return static_cast<std::uint32_t>(r) | (static_cast<std::uint32_t>(g) << 8) |
      (static_cast<std::uint32_t>(b) << 16) | (static_cast<std::uint32_t>(a) << 24);
  }
  static Rgba unpack(std::uint32_t v)
  {
    return Rgba{ static_cast<std::uint8_t>(v & 0xff), static_cast<std::uint8_t>((v >> 8) & 0xff),
      static_cast<std::uint8_t>((v >> 16) & 0xff), static_cast<std::uint8_t>(v >> 24) };
  }
  bool operator==(const Rgba& o) const { return packed() == o.packed(); }
  bool operator!=(const Rgba& o) const { return !(*this == o); }
};

class ColorDictionary
{
public:
  static constexpr std::size_t Capacity = 65535; // keys 0..65534
  enum class FullPolicy
  {
    Error,
    Nearest
  };

  explicit ColorDictionary(Rgba defaultColor = Rgba{ 200, 200, 200, 255 },
    FullPolicy policy = FullPolicy::Error);

  /// Key of the colour, adding it if new (see the full policy above).
  ColorKey add(Rgba color);
  /// Key of the colour if present; returns false if absent.
  bool find(Rgba color, ColorKey& key) const;
  /// The colour of a key; throws Error(InvalidArgument) for an unused key.
  Rgba color(ColorKey key) const;
  /// Unchecked access for hot loops (key < size()).
  const Rgba& operator[](ColorKey key) const { return this->Colors[key]; }

  std::size_t size() const { return this->Colors.size(); }
  bool full() const { return this->Colors.size() >= Capacity; }
  FullPolicy policy() const { return this->Policy; }
  void setPolicy(FullPolicy p) { this->Policy = p; }
  const std::vector<Rgba>& colors() const { return this->Colors; }

  /// Replaces the contents (used by readers); validates size and uniqueness.
  void assign(const std::vector<Rgba>& colors);

  bool operator==(const ColorDictionary& o) const { return this->Colors == o.Colors; }

private:
  ColorKey nearest(Rgba color) const;

  std::vector<Rgba> Colors;
  std::unordered_map<std::uint32_t, ColorKey> Index;
  FullPolicy Policy;
};

inline bool operator==(const std::vector<Rgba>& a, const std::vector<Rgba>& b)
{
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].packed() != b[i].packed()) return false;
  return true;
}

} // namespace lvdif
