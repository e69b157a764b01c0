#pragma once
/// \file interval_batch.hpp
/// Batches of certified intervals on the fastest code this machine runs.
///
/// `shadow_batch` and `reflection_batch` (batch/batch.hpp) of CGAL intervals
/// run the generic formulas on IntervalPack (interval_pack.hpp), compiled
/// for the build's instruction set (x86-64-v3 with QVERIFY_ARCH=auto, so that
/// valgrind runs the build). Interval packs are bound by arithmetic and
/// registers: a product is about a dozen vector operations (sign-selected
/// corners) on two registers per value. On AMD Zen 5 (family 26) the AVX-512
/// kernel (8 lanes, 32 registers) takes about 2/3 of the AVX2 one's time.
///
/// These functions are those batches, with one difference: a build that
/// measured a faster interval kernel for another instruction set than its
/// own (QVERIFY_ARCH=auto, cmake/ChooseArch.cmake) carries a second copy of
/// the same template compiled for it, and runs that copy when the processor
/// has the instruction set (asked at run time: never under valgrind, which
/// does not emulate AVX-512). The results are the same bit for bit: every
/// lane performs the same IEEE operations whatever the width
/// (tests/batch/test_batch.cpp, "[dispatch]").
///
/// The copy is compiled in its own file and linked with every symbol but
/// its entry points made local (exact/CMakeLists.txt): else the linker could
/// pick its AVX-512 instantiation of an inline function (Eigen's, CGAL's,
/// the standard library's) for the rest of the program, which would fault on
/// a processor without AVX-512. What of it runs on every processor: its
/// static initializers (those of the standard streams and Boost's MPFR
/// cleanup object, calls only); the valgrind tests of a release build with a
/// second kernel run them on a virtual processor without AVX-512.
///
/// Method paper runs item by item (batch.hpp) and is passed to the generic
/// template. CGAL::Interval_nt<false> needs the rounding mode upward: the
/// functions set it on every thread they run (and restore it).

#include <qverify/batch/rows.hpp>
#include <qverify/core/method.hpp>

#include <CGAL/Interval_nt.h>

namespace qverify {

/// P, pi and R of every item, as shadow_batch (batch.hpp), on the fastest interval kernel here.
template <bool Protected>
void interval_shadow_batch(const SymBatch<CGAL::Interval_nt<Protected>>& A, const Vec4Batch<CGAL::Interval_nt<Protected>>& L,
                           Method method, SymBatch<CGAL::Interval_nt<Protected>>& P,
                           Vec4Batch<CGAL::Interval_nt<Protected>>& pi, SymBatch<CGAL::Interval_nt<Protected>>& R,
                           int threads);

/// M (rows 1-3) and B of every item, as reflection_batch (batch.hpp), on the fastest interval kernel here.
template <bool Protected>
void interval_reflection_batch(const SymBatch<CGAL::Interval_nt<Protected>>& A,
                               const Vec4Batch<CGAL::Interval_nt<Protected>>& planes, Method method,
                               AffineBatch<CGAL::Interval_nt<Protected>>& M, SymBatch<CGAL::Interval_nt<Protected>>& B,
                               int threads);

/// The widest x86 vector extension the library was compiled for ("AVX-512", "AVX2", "AVX",
/// "SSE2", "scalar"): what the batches run where they have no second kernel (double_batch.hpp).
const char* build_instruction_set();

/// Whether the two functions above run the second kernel here (it was built, and this processor
/// has its instruction set).
bool interval_batch_dispatched();

/// The -march of the build's second interval kernel ("x86-64-v4"), "" when it has none.
const char* interval_batch_second_kernel();

/// Which kernel the two functions above run on this processor: the build's instruction set
/// ("AVX2", "AVX-512", ...), or that of the second copy, e.g. "AVX-512 (run-time dispatch)".
const char* interval_batch_kernel();

}  // namespace qverify
