#pragma once
/// \file pages.hpp
/// Memory pages for large batches: transparent huge pages where the system
/// gives them on request.
///
/// Why. A double batch streams five arrays (two inputs, three outputs) and
/// does little arithmetic per byte, so memory sets its pace, and with 4 KiB
/// pages it takes a TLB miss every 4 KiB of every array (in a virtual machine,
/// a two-dimensional page walk). On this project's machine (AMD EPYC, Zen 5,
/// 2 threads) `qverify bench` put the double direct rows at 5.2-6.1 ns per
/// item with huge pages against 6.6-7.8 without; its bandwidth copy gained
/// more still (README, "bench"; `--no-huge-pages` compares, and the report's
/// `"pages"` says what the buffers got).
///
/// How. Linux backs anonymous memory with huge pages at the first touch of a
/// huge-page-aligned range that `madvise(MADV_HUGEPAGE)` marked, when
/// /sys/kernel/mm/transparent_hugepage/enabled is `always` or `madvise` (the
/// usual default). Pages already touched stay small until the kernel's
/// background collapse (khugepaged) gets to them. So advise a batch right
/// after sizing it and before writing it:
///
///     SymBatch<double> A;
///     A.resize(n, 10);
///     advise_huge_pages(A);  // then fill A
///
/// The batch functions do this for the outputs they allocate (sized_output,
/// batch.hpp). The advice is a hint: it never changes a value, the kernel may
/// still give small pages (fragmented memory), and where the defrag setting
/// is `madvise` (the default) an advised first touch may compact memory to
/// find a huge page, which costs time once. It marks an address range, not
/// an allocation: once the storage is freed, later allocations at those
/// addresses (glibc's heap, for blocks below its mmap threshold) keep the
/// mark, which only lets them have huge pages too. Elsewhere than Linux it
/// does nothing. (glibc's `GLIBC_TUNABLES=glibc.malloc.hugetlb=1` gives every
/// large allocation of a process the same advice.)
///
/// <sys/mman.h> comes with this header on Linux (its MAP_, PROT_ and MADV_
/// macros included): the header-only batch library has no source file to
/// hide it in.

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <fstream>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace qverify {

/// The system's huge page size for transparent huge pages
/// (/sys/kernel/mm/transparent_hugepage/hpage_pmd_size: 2 MiB on x86-64, more
/// on some AArch64 and POWER configurations); 2 MiB where it cannot be read.
inline std::size_t huge_page_bytes() {
  static const std::size_t bytes = [] {
    std::size_t b = 0;
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/hpage_pmd_size");
    if (in >> b && b > 0 && (b & (b - 1)) == 0) return b;  // a power of two, as a page size is
    return std::size_t(2) << 20;
  }();
  return bytes;
}

/// Advises huge pages for the whole huge pages (huge_page_bytes) inside
/// [data, data + bytes): the range is rounded inwards, so nothing outside the
/// caller's storage is marked. Returns the bytes advised: 0 where none (less
/// than one whole huge page inside, not Linux, or the advice refused, e.g. a
/// kernel without transparent huge pages).
inline std::size_t advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t page = huge_page_bytes();
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + page - 1) / page * page;
  const std::uintptr_t last = (begin + bytes) / page * page;
  if (data == nullptr || last <= first) return 0;
  const std::size_t length = last - first;
  // madvise only marks the range: no page is touched, no value changes.
  if (::madvise(reinterpret_cast<void*>(first), length, MADV_HUGEPAGE) != 0) return 0;
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
