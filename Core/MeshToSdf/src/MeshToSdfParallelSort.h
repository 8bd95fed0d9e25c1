// Parallel sort for the mesh passes (OpenMP): the parts sorted on threads,
// then merged pairwise, also on threads. For a strict total order (every
// caller breaks ties by an index) the result is the one std::sort gives, so it
// does not depend on the thread count.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

template <typename T, typename Less>
void parallelSort(std::vector<T>& v, Less less)
{
  const std::size_t n = v.size();
  std::size_t parts = 1;
  while (parts * 2 <= static_cast<std::size_t>(omp_get_max_threads()) && n / (parts * 2) >= 32768) parts *= 2;
  if (parts < 2)
  {
    std::sort(v.begin(), v.end(), less);
    return;
  }
  std::vector<std::size_t> b(parts + 1);
  for (std::size_t i = 0; i <= parts; ++i) b[i] = n * i / parts;
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(parts); ++i)
    std::sort(v.begin() + static_cast<std::ptrdiff_t>(b[i]), v.begin() + static_cast<std::ptrdiff_t>(b[i + 1]), less);
  std::vector<T> tmp(n);
  std::vector<T>*src = &v, *dst = &tmp;
  for (std::size_t width = 1; width < parts; width *= 2)
  {
#pragma omp parallel for schedule(static, 1)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(parts); i += static_cast<std::int64_t>(2 * width))
    {
      const std::size_t lo = b[static_cast<std::size_t>(i)], mid = b[std::min(static_cast<std::size_t>(i) + width, parts)],
                        hi = b[std::min(static_cast<std::size_t>(i) + 2 * width, parts)];
      std::merge(src->begin() + static_cast<std::ptrdiff_t>(lo), src->begin() + static_cast<std::ptrdiff_t>(mid),
        src->begin() + static_cast<std::ptrdiff_t>(mid), src->begin() + static_cast<std::ptrdiff_t>(hi),
        dst->begin() + static_cast<std::ptrdiff_t>(lo), less);
    }
    std::swap(src, dst);
  }
  if (src != &v) v.swap(tmp);
}

} // namespace detail::meshtosdf
} // namespace lvdif
