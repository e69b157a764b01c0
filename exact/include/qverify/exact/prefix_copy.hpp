#pragma once
/// \file prefix_copy.hpp
/// dst[0 .. n) = src[0 .. n) for the fixed-capacity exact integers (WideInt's limbs, DigitPack's
/// digit vectors): by a jump into a straight run of element moves. A loop of a variable count
/// became a call to memmove, and a fixed copy of all Cap elements moved wide words just written
/// narrow (a stalled store forwarding) or bytes never in use; measured in bench/bench_wide.

namespace qverify::detail {

template <int Cap, class T> inline void copy_prefix(T (&dst)[Cap], const T (&src)[Cap], int n) {
  static_assert(Cap >= 1 && Cap <= 32, "copy_prefix unrolls at most 32 elements");
  switch (n) {
#define QVERIFY_PREFIX_COPY(k) \
  case (k) + 1: \
    if constexpr ((k) < Cap) dst[k] = src[k]; \
    [[fallthrough]];
    QVERIFY_PREFIX_COPY(31) QVERIFY_PREFIX_COPY(30) QVERIFY_PREFIX_COPY(29) QVERIFY_PREFIX_COPY(28)
    QVERIFY_PREFIX_COPY(27) QVERIFY_PREFIX_COPY(26) QVERIFY_PREFIX_COPY(25) QVERIFY_PREFIX_COPY(24)
    QVERIFY_PREFIX_COPY(23) QVERIFY_PREFIX_COPY(22) QVERIFY_PREFIX_COPY(21) QVERIFY_PREFIX_COPY(20)
    QVERIFY_PREFIX_COPY(19) QVERIFY_PREFIX_COPY(18) QVERIFY_PREFIX_COPY(17) QVERIFY_PREFIX_COPY(16)
    QVERIFY_PREFIX_COPY(15) QVERIFY_PREFIX_COPY(14) QVERIFY_PREFIX_COPY(13) QVERIFY_PREFIX_COPY(12)
    QVERIFY_PREFIX_COPY(11) QVERIFY_PREFIX_COPY(10) QVERIFY_PREFIX_COPY(9) QVERIFY_PREFIX_COPY(8)
    QVERIFY_PREFIX_COPY(7) QVERIFY_PREFIX_COPY(6) QVERIFY_PREFIX_COPY(5) QVERIFY_PREFIX_COPY(4)
    QVERIFY_PREFIX_COPY(3) QVERIFY_PREFIX_COPY(2) QVERIFY_PREFIX_COPY(1) QVERIFY_PREFIX_COPY(0)
#undef QVERIFY_PREFIX_COPY
    default: break;
  }
}

}  // namespace qverify::detail
