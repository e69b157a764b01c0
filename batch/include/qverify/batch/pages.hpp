#pragma once
/// \file pages.hpp
/// Memory pages for large batches: transparent huge pages (2 MiB on x86-64)
/// where the system gives them on request.
///
/// Why. A double batch streams five arrays (two inputs, three outputs) and
/// does little arithmetic per byte, so it runs at the memory's pace, and with
/// 4 KiB pages it pays a TLB miss every 4 KiB of every array (in a virtual
/// machine a two-dimensional page walk) and the hardware prefetchers stop at
/// every page. On this project's machine (AMD EPYC, Zen 5, 2 threads) the
/// double shadow batch went from about 5.0 to 3.8 ns per item with its arrays
/// on huge pages, while a stream copy of the same bytes barely moved (README,
/// "bench"; `qverify bench` reports the pages it got).
///
/// How. Linux backs anonymous memory with huge pages at the first touch of a
/// 2 MiB-aligned range that `madvise(MADV_HUGEPAGE)` marked, when
/// /sys/kernel/mm/transparent_hugepage/enabled is `always` or `madvise` (the
/// usual default; with `always` the advice changes nothing). Pages already
/// touched stay 4 KiB until the kernel's background collapse (khugepaged) gets
/// to them. So advise a batch right after sizing it and before writing it:
///
///     SymBatch<double> A;
///     A.resize(n, 10);
///     advise_huge_pages(A);  // then fill A
///
/// The batch functions do this themselves for the outputs they allocate
/// (sized_output, batch.hpp). The advice covers the whole 2 MiB pages inside
/// the storage only (nothing else of the allocation is affected), it is a
/// hint (the kernel may still give 4 KiB pages, e.g. when memory is
/// fragmented), and it never changes a value. Elsewhere than Linux it does
/// nothing. (glibc's `GLIBC_TUNABLES=glibc.malloc.hugetlb=1` gives every
/// large allocation of a process the same advice.)

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace qverify {

/// The huge page size the advice aims at (x86-64 and AArch64 with 4 KiB base pages).
constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

/// Advises huge pages for the whole 2 MiB pages inside [data, data + bytes).
/// Returns the bytes advised: 0 where none (less than one whole huge page
/// inside, not Linux, or the system refused the advice, e.g. THP compiled out).
inline std::size_t advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  const std::uintptr_t last = (begin + bytes) / kHugePageBytes * kHugePageBytes;
  if (data == nullptr || last <= first) return 0;
  const std::size_t length = last - first;
  // The range lies inside the caller's storage, so the advice touches no other allocation; madvise only
  // marks the range (no page is touched, no value changes).
  if (madvise(reinterpret_cast<void*>(first), length, MADV_HUGEPAGE) != 0) return 0;
  return length;
#else
  (void)data, (void)bytes;
  return 0;
#endif
}

/// The same for the storage of an Eigen matrix or array (a batch).
template <class Derived> std::size_t advise_huge_pages(const Eigen::PlainObjectBase<Derived>& m) {
  return advise_huge_pages(m.data(), sizeof(typename Derived::Scalar) * static_cast<std::size_t>(m.size()));
}

}  // namespace qverify
