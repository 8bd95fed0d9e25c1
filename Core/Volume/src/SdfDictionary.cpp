#include "lvdif/SdfDictionary.h"

#include "lvdif/Error.h"

#include <cmath>
#include <sstream>

namespace lvdif
{

SdfDictionary::SdfDictionary(const SdfDictionaryParams& params)
  : Params(params)
{
  require(std::isfinite(params.stepA) && params.stepA > 0, "SDF dictionary: stepA must be > 0");
  require(std::isfinite(params.stepB) && params.stepB >= params.stepA,
    "SDF dictionary: stepB must be >= stepA");
  require(std::isfinite(params.groupALimit) && params.groupALimit >= params.stepA,
    "SDF dictionary: groupALimit must be >= stepA");

  this->Consts.halfA = std::llround(params.groupALimit / params.stepA);
  // Group B needs at least one key per side; 2*HalfA+1 + 2 <= 65536.
  if (2 * this->Consts.halfA + 3 > KeyCount)
  {
    std::ostringstream msg;
    msg << "SDF dictionary: Group A [-" << params.groupALimit << ", " << params.groupALimit
        << "] in steps of " << params.stepA << " needs " << (2 * this->Consts.halfA + 1)
        << " keys and leaves none for Group B (65,536 keys in all)";
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
  const double aMax = static_cast<double>(this->Consts.halfA) * params.stepA;
  this->Consts.firstB = (std::floor(aMax / params.stepB + 1e-9) + 1.0) * params.stepB;
  const std::int64_t bKeys = KeyCount - (2 * this->Consts.halfA + 1);
  const std::int64_t bNeg = bKeys / 2;       // 28,766 by default
  const std::int64_t bPos = bKeys - bNeg;    // 28,767 by default (one more: 65,536 is even)
  this->Consts.zeroKey = bNeg + this->Consts.halfA;
  this->Consts.invStepA = 1.0 / params.stepA;
  this->Consts.invStepB = 1.0 / params.stepB;
  this->Consts.encodeALimit = 0.5 * (aMax + this->Consts.firstB);

  this->Table.resize(KeyCount);
  for (std::int64_t k = 0; k < KeyCount; ++k)
  {
    const std::int64_t off = k - this->Consts.zeroKey; // signed distance from zero in keys
    const std::int64_t m = off < 0 ? -off : off;
    double v;
    if (m <= this->Consts.halfA)
    {
      v = static_cast<double>(m) * params.stepA;
    }
    else
    {
      v = this->Consts.firstB + static_cast<double>(m - this->Consts.halfA - 1) * params.stepB;
    }
    this->Table[static_cast<size_t>(k)] = static_cast<float>(off < 0 ? -v : v);
  }
  (void)bPos;
  // Distinctness is what makes the order usable: refuse steps that float cannot resolve.
  for (int k = 1; k < KeyCount; ++k)
  {
    if (!(this->Table[k] > this->Table[k - 1]))
    {
      std::ostringstream msg;
      msg << "SDF dictionary: values " << this->Table[k - 1] << " and " << this->Table[k]
          << " collapse in float precision; use larger steps";
      throw Error(ErrorCode::InvalidArgument, msg.str());
    }
  }
}

double SdfDictionary::maxErrorInRange() const
{
  const double aMax = static_cast<double>(this->Consts.halfA) * this->Params.stepA;
  double gap = 0.5 * (this->Consts.firstB - aMax);
  double e = this->maxErrorGroupB();
  return gap > e ? gap : e;
}

const SdfDictionary& defaultSdfDictionary()
{
  static const SdfDictionary dictionary;
  return dictionary;
}

std::int32_t SdfDictionary::keysBelow(float value) const
{
  std::int32_t lo = 0, hi = KeyCount; // the first key whose value is >= value
  while (lo < hi)
  {
    const std::int32_t mid = lo + (hi - lo) / 2;
    if (this->Table[static_cast<std::size_t>(mid)] >= value)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

} // namespace lvdif
