// The SDF dictionary: a 16-bit key for a signed distance (paper Sect. 3.3.2).
//
// Two groups of values, as in the paper:
//   Group A: every multiple of stepA in [-groupALimit, +groupALimit]
//            (defaults 0.001 and 4.001: -4.001, -4.000, ..., 0, ..., 4.001);
//   Group B: the remaining keys, multiples of stepB continuing outward from
//            the first multiple of stepB above groupALimit (default 4.1),
//            28,766 negative values and 28,767 positive ones by default, so the
//            range is [-2880.6, +2880.7].
//
// Key order IS value order: key 0 is the most negative value, key 65535 the
// most positive, and decode() is strictly increasing in the key. Comparing
// keys therefore compares distances, and the sign of a voxel is
// (key < zeroKey()) for inside (negative, by the project's convention).
//
// encode(x) returns the key of the nearest value (ties go to the value of
// smaller magnitude), so |decode(encode(x)) - x| <= stepA/2 in Group A,
// <= stepB/2 in Group B, and <= (firstB - groupALimit)/2 in the gap between
// the groups. Beyond the largest value it saturates to the extreme key of the
// same sign (never wraps); NaN encodes to the most positive key ("outside").
#pragma once

#include "lvdif/HostDevice.h"

#include <cstdint>
#include <vector>


namespace lvdif
{

using SdfKey = std::uint16_t;

struct SdfDictionaryParams
{
  double groupALimit = 4.001; // largest |value| of Group A
  double stepA = 0.001;       // spacing of Group A
  double stepB = 0.1;         // spacing of Group B
  bool operator==(const SdfDictionaryParams& o) const
  {
    return groupALimit == o.groupALimit && stepA == o.stepA && stepB == o.stepB;
  }
  bool operator!=(const SdfDictionaryParams& o) const { return !(*this == o); }
};

class SdfDictionary
{
public:
  static constexpr int KeyCount = 65536;

  /// Validates the parameters (throws Error(InvalidArgument)) and builds the table.
  explicit SdfDictionary(const SdfDictionaryParams& params = SdfDictionaryParams());

  const SdfDictionaryParams& params() const { return this->Params; }

  /// Nearest key; saturates beyond the range, NaN -> maxKey().
  SdfKey encode(float value) const { return encodeWith(this->Consts, value); }

  /// What encode() needs, for device code that must round identically
  /// (MeshToSdfCuda.cu encodes chunks on the GPU with encodeWith).
  struct EncodeConstants
  {
    std::int64_t halfA = 0;   // Group A keys on one side of zero
    std::int64_t zeroKey = 0; // key of 0.0
    double invStepA = 0, invStepB = 0;
    double firstB = 0;       // first positive Group B value
    double encodeALimit = 0; // |x| up to which Group A rounding applies
  };
  const EncodeConstants& encodeConstants() const { return this->Consts; }

  /// encode() from the constants: one definition for the host and the GPU.
  LVDIF_HD static SdfKey encodeWith(const EncodeConstants& c, float value)
  {
    if (!(value == value)) // NaN
    {
      return static_cast<SdfKey>(KeyCount - 1);
    }
    const double a = value < 0 ? -static_cast<double>(value) : static_cast<double>(value);
    std::int64_t offset; // distance from the zero key, in keys
    if (a <= c.encodeALimit)
    {
      offset = roundHalfDown(a * c.invStepA);
      if (offset > c.halfA) // the lower half of the gap between the groups
      {
        offset = c.halfA;
      }
    }
    else
    {
      // Group B index j counts from firstB; ties between groups resolved by the midpoint.
      // clamp before converting so huge values and infinity saturate instead of overflowing
      const double t = (a - c.firstB) * c.invStepB;
      const double j = t > 1e6 ? 1e6 : static_cast<double>(roundHalfDown(t));
      offset = c.halfA + 1 + static_cast<std::int64_t>(j < 0 ? 0 : j);
    }
    if (value < 0)
    {
      return offset > c.zeroKey ? 0 : static_cast<SdfKey>(c.zeroKey - offset);
    }
    const std::int64_t k = c.zeroKey + offset;
    return k > KeyCount - 1 ? static_cast<SdfKey>(KeyCount - 1) : static_cast<SdfKey>(k);
  }

  float decode(SdfKey key) const { return this->Table[key]; }
  const float* table() const { return this->Table.data(); }
  /// How many keys decode below `value`: a key's value is >= `value` exactly when
  /// key >= keysBelow(value) (KeyCount when none is; NaN: KeyCount).
  std::int32_t keysBelow(float value) const;

  /// The key that decodes to exactly 0.
  SdfKey zeroKey() const { return static_cast<SdfKey>(this->Consts.zeroKey); }
  float minValue() const { return this->Table.front(); }
  float maxValue() const { return this->Table.back(); }
  /// First value of Group B (4.1 by default).
  double firstGroupBValue() const { return this->Consts.firstB; }
  /// Largest |decode(encode(x)) - x| for |x| <= maxValue (the gap between groups dominates).
  double maxErrorInRange() const;
  /// Largest error for |x| <= groupALimit.
  double maxErrorGroupA() const { return this->Params.stepA * 0.5; }
  /// Largest error inside Group B.
  double maxErrorGroupB() const { return this->Params.stepB * 0.5; }

  /// The key of +d or -d saturated as a band would: encode(clamp(x, -band, band)).
  SdfKey encodeClamped(float value, float band) const
  {
    if (value > band) value = band;
    if (value < -band) value = -band;
    return this->encode(value);
  }

private:
  LVDIF_HD static std::int64_t roundHalfDown(double x)
  {
    // nearest integer; exact .5 goes down (toward the smaller magnitude)
    const double f = static_cast<double>(static_cast<std::int64_t>(x));
    return static_cast<std::int64_t>(x - f > 0.5 ? f + 1 : f);
  }

  SdfDictionaryParams Params;
  EncodeConstants Consts;
  std::vector<float> Table;
};

/// The dictionary with the paper's parameters, shared (built once, thread-safe).
const SdfDictionary& defaultSdfDictionary();

} // namespace lvdif
