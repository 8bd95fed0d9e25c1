// Parallel sort for the mesh passes (OpenMP): the parts sorted on threads,
// then merged pairwise, each merge cut into pieces on the threads (merge
// path), so no merge runs on one thread over more than a small part. For a strict total order (every
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

/// Merge path (Odeh, Green, Mwassi, Shmueli, Birk, "Merge Path - Parallel
/// Merging Made Simple", IPDPS workshops 2012): how many of the first k
/// outputs of std::merge(a, a + na, c, c + nc) come from a (ties from a
/// first, as std::merge takes them), by a binary search; so a merge splits
/// into independent pieces that give exactly std::merge's output.
template <typename T, typename Less>
std::size_t mergeCoRank(const T* a, std::size_t na, const T* c, std::size_t nc, std::size_t k, Less& less)
{
  std::size_t lo = k > nc ? k - nc : 0, hi = std::min(k, na);
  while (lo < hi)
  {
    const std::size_t i = lo + (hi - lo) / 2; // a[i] is among the first k when it does not follow c[k - i - 1]
    if (!less(c[k - i - 1], a[i]))
      lo = i + 1;
    else
      hi = i;
  }
  return lo;
}

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
    // every merge of this level cut into pieces of about n / (4 parts)
    // outputs (merge path), all pieces on the threads
    struct Piece
    {
      std::size_t lo, mid, hi, k0, k1; // the merge of [lo, mid) and [mid, hi); its outputs [k0, k1)
    };
    std::vector<Piece> pieces;
    const std::size_t pieceSize = std::max<std::size_t>(1, n / (4 * parts));
    for (std::size_t i = 0; i < parts; i += 2 * width)
    {
      const std::size_t lo = b[i], mid = b[std::min(i + width, parts)], hi = b[std::min(i + 2 * width, parts)];
      for (std::size_t k = 0; k < hi - lo; k += pieceSize) pieces.push_back({ lo, mid, hi, k, std::min(hi - lo, k + pieceSize) });
    }
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t p = 0; p < static_cast<std::int64_t>(pieces.size()); ++p)
    {
      const Piece& q = pieces[static_cast<std::size_t>(p)];
      const T* a = src->data() + q.lo;
      const T* c = src->data() + q.mid;
      const std::size_t na = q.mid - q.lo, nc = q.hi - q.mid;
      const std::size_t i0 = mergeCoRank(a, na, c, nc, q.k0, less), i1 = mergeCoRank(a, na, c, nc, q.k1, less);
      std::merge(a + i0, a + i1, c + (q.k0 - i0), c + (q.k1 - i1), dst->begin() + static_cast<std::ptrdiff_t>(q.lo + q.k0), less);
    }
    std::swap(src, dst);
  }
  if (src != &v) v.swap(tmp);
}

} // namespace detail::meshtosdf
} // namespace lvdif
