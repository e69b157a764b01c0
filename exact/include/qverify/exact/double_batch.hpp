#pragma once
/// \file double_batch.hpp
/// Batches of doubles on the fastest code this machine runs.
///
/// `shadow_batch` and `reflection_batch` (batch/batch.hpp) of doubles run
/// the generic formulas on DoublePack (batch/pack.hpp), compiled for the
/// instruction set of the code that calls them. The library itself is
/// compiled for x86-64-v3 (AVX2) also where the processor has AVX-512, so
/// that valgrind, which does not emulate AVX-512, runs it (QVERIFY_ARCH=auto,
/// cmake/ChooseArch.cmake). Whether the 8-lane AVX-512 kernel is faster
/// depends on the processor: on AMD Zen 4 it was 2-3x slower than AVX2 before
/// the store order of the batches was fixed; on AMD Zen 5 it was 30% faster
/// once they stored whole vectors, and level with AVX2 on other days. So does
/// the compiler: on Zen 5, clang 14's AVX2
/// kernel took 70% of GCC 12's time (GCC keeps the matrices of packs on the
/// stack), and clang's x86-64-v4 kernel with 256-bit packs (4 lanes in
/// AVX-512's 32 registers, where 16 spill) took 85% of its AVX2 one's time.
///
/// These functions are those batches, with one difference: a build that
/// measured the double kernel more than 10% faster with x86-64-v4, or
/// compiled by clang++ (at either level), carries a second copy of the same
/// template compiled that way, and runs that copy when the processor has the
/// instruction set (asked at run time: never an AVX-512 copy under
/// valgrind). The results are the same bit for bit: contraction is off, and
/// every lane performs the same IEEE operations whatever the width
/// (tests/batch/test_batch.cpp, "[dispatch]"). The copy lives in the exact
/// library beside the second interval kernel (interval_batch.hpp says how it
/// is linked and why); method paper runs item by item and is passed to the
/// generic template.

#include <qverify/batch/rows.hpp>
#include <qverify/core/method.hpp>

namespace qverify {

/// P, pi and R of every item, as shadow_batch<double> (batch.hpp), on the fastest double kernel here.
void double_shadow_batch(const SymBatch<double>& A, const Vec4Batch<double>& L, Method method, SymBatch<double>& P,
                         Vec4Batch<double>& pi, SymBatch<double>& R, int threads);

/// M (rows 1-3) and B of every item, as reflection_batch<double> (batch.hpp), on the fastest double kernel here.
void double_reflection_batch(const SymBatch<double>& A, const Vec4Batch<double>& planes, Method method,
                             AffineBatch<double>& M, SymBatch<double>& B, int threads);

/// Whether the two functions above run the second kernel here (it was built, and this processor
/// has its instruction set).
bool double_batch_dispatched();

/// The -march of the build's second double kernel ("x86-64-v4", or "x86-64-v3" for one compiled by
/// clang), "" when it has none.
const char* double_batch_second_kernel();

/// Which kernel the two functions above run on this processor: the build's instruction set
/// ("AVX2", ...), or that of the second copy, e.g. "AVX-512 (run-time dispatch)" or, compiled by
/// clang, "AVX2, clang 14.0.6 (run-time dispatch)" or "AVX-512, clang 14.0.6, 256-bit packs (run-time
/// dispatch)".
const char* double_batch_kernel();

/// Doubles per instruction of that kernel (2, 4 or 8).
int double_batch_lanes();

}  // namespace qverify
