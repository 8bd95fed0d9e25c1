// LVDIFVolumeBridge: StoreRange, the value ranges of the arrays the filters
// make, computed in one (threaded, for large arrays) pass and cached in the
// arrays' information as VTK's own range keys, so that VTK and ParaView do not
// scan them again.
#include "LVDIFVolumeBridge.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationInformationVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

namespace LVDIFVolumeBridge
{
namespace
{
/// Stores the given ranges as the array's cached ranges (VTK's information
/// keys, newer than the array's MTime): per component and finite per
/// component, and for several components the magnitude (L2 norm) range and its
/// finite twin. Every value is finite here, so each range equals its finite one.
void CacheRanges(vtkDataArray* array, const std::vector<std::array<double, 2>>& components,
  const std::array<double, 2>& magnitude)
{
  vtkInformation* info = array->GetInformation();
  for (vtkInformationInformationVectorKey* key :
    { vtkAbstractArray::PER_COMPONENT(), vtkAbstractArray::PER_FINITE_COMPONENT() })
  {
    vtkNew<vtkInformationVector> perComponent;
    perComponent->SetNumberOfInformationObjects(static_cast<int>(components.size()));
    for (std::size_t c = 0; c < components.size(); ++c)
    {
      perComponent->GetInformationObject(static_cast<int>(c))
        ->Set(vtkDataArray::COMPONENT_RANGE(), components[c].data(), 2);
    }
    info->Set(key, perComponent);
  }
  if (components.size() > 1)
  {
    info->Set(vtkDataArray::L2_NORM_RANGE(), magnitude.data(), 2);
    info->Set(vtkDataArray::L2_NORM_FINITE_RANGE(), magnitude.data(), 2);
  }
}

/// fn(begin, end, local) over [0, n) with one T per thread, merged by
/// merge(total, local). Threads only for large arrays: a partition of the
/// sparse volume (one chunk, ~36k values) costs VTK's STDThread backend a
/// thread pool per call, more than the pass itself (ParaView's data
/// information visits every partition).
template <typename T, typename Fn, typename Merge>
T ReduceOver(vtkIdType n, Fn&& fn, Merge&& merge)
{
  T total;
  if (n < (vtkIdType(1) << 20))
  {
    fn(0, n, total);
    return total;
  }
  vtkSMPThreadLocal<T> local;
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) { fn(begin, end, local.Local()); });
  for (const T& t : local)
  {
    merge(total, t);
  }
  return total;
}
} // namespace

namespace
{
/// The ranges of an array of NC components of T in one pass: every
/// component's (in T) and the squared magnitudes' (1 component: none); for
/// floating types whether every value is finite.
template <typename T, int NC>
struct TupleRanges
{
  using Square = std::conditional_t<std::is_floating_point<T>::value, double, long long>;
  T lo[NC], hi[NC];
  Square normLo = std::numeric_limits<Square>::max(), normHi = 0;
  bool finite = true;
  TupleRanges()
  {
    std::fill(lo, lo + NC, std::numeric_limits<T>::max());
    std::fill(hi, hi + NC, std::numeric_limits<T>::lowest());
  }
  void add(const T* v, vtkIdType begin, vtkIdType end)
  {
    bool ok = true;
    for (vtkIdType t = begin; t < end; ++t)
    {
      Square norm = 0;
      for (int c = 0; c < NC; ++c)
      {
        const T x = v[t * NC + c];
        lo[c] = std::min(lo[c], x);
        hi[c] = std::max(hi[c], x);
        if constexpr (NC > 1) norm += static_cast<Square>(x) * static_cast<Square>(x);
        if constexpr (std::is_floating_point<T>::value) ok &= (x - x == 0); // false for NaN and +-inf
      }
      if constexpr (NC > 1)
      {
        normLo = std::min(normLo, norm);
        normHi = std::max(normHi, norm);
      }
    }
    finite = finite && ok;
  }
  void merge(const TupleRanges& o)
  {
    for (int c = 0; c < NC; ++c)
    {
      lo[c] = std::min(lo[c], o.lo[c]);
      hi[c] = std::max(hi[c], o.hi[c]);
    }
    normLo = std::min(normLo, o.normLo);
    normHi = std::max(normHi, o.normHi);
    finite = finite && o.finite;
  }
};

template <typename T, int NC>
void StoreRangeOf(vtkAOSDataArrayTemplate<T>* array)
{
  array->Modified(); // written through the pointer: drop whatever was cached before
  const T* v = array->GetPointer(0);
  using R = TupleRanges<T, NC>;
  const R all = ReduceOver<R>(
    array->GetNumberOfTuples(), [v](vtkIdType begin, vtkIdType end, R& r) { r.add(v, begin, end); },
    [](R& a, const R& b) { a.merge(b); });
  if (!all.finite)
  {
    return;
  }
  std::vector<std::array<double, 2>> components(NC);
  for (int c = 0; c < NC; ++c)
  {
    components[c] = { static_cast<double>(all.lo[c]), static_cast<double>(all.hi[c]) };
  }
  CacheRanges(array, components,
    { std::sqrt(static_cast<double>(all.normLo)), std::sqrt(static_cast<double>(all.normHi)) });
}

/// StoreRange for any array of VTK's own layout with 1 to 4 components.
template <typename T>
void StoreRangeOf(vtkAOSDataArrayTemplate<T>* array)
{
  if (!array || array->GetNumberOfTuples() == 0)
  {
    return;
  }
  switch (array->GetNumberOfComponents())
  {
    case 1: StoreRangeOf<T, 1>(array); break;
    case 2: StoreRangeOf<T, 2>(array); break;
    case 3: StoreRangeOf<T, 3>(array); break;
    case 4: StoreRangeOf<T, 4>(array); break;
    default: break; // VTK computes
  }
}
} // namespace

void StoreRange(vtkFloatArray* array)
{
  StoreRangeOf(array);
}

void StoreRange(vtkUnsignedCharArray* array)
{
  StoreRangeOf(array);
}

void StoreRange(vtkIntArray* array)
{
  StoreRangeOf(array);
}

void StoreRange(vtkIdTypeArray* array)
{
  StoreRangeOf(array);
}
} // namespace LVDIFVolumeBridge
