#pragma once
// The entry points of the second interval kernel (interval_batch_kernel.cpp, compiled for
// QVERIFY_INTERVAL_MARCH; exact/interval_batch.hpp says why). Only these symbols of its object stay
// global (exact/CMakeLists.txt keeps qverify::second_kernel::*): plain functions, one per interval
// type and operation, taking the batches by reference (dynamic Eigen matrices: a pointer and a row
// count, the same layout whatever the instruction set; the caller sizes the outputs, so the copy
// never allocates what the rest of the program frees).

#include <qverify/batch/rows.hpp>
#include <qverify/core/method.hpp>

#include <CGAL/Interval_nt.h>

namespace qverify {

/// What every thread of an interval batch sets up first: the rounding mode upward for unprotected
/// intervals (the protected ones set it per operation, the packs per run of packs). Outside
/// second_kernel: that namespace holds the entry points alone, the symbols kept global.
template <bool Pr> auto interval_batch_setup() {
  if constexpr (Pr) return [] { return 0; };
  else return [] { return CGAL::Protect_FPU_rounding<true>(); };
}

}  // namespace qverify

namespace qverify::second_kernel {

using Protected = CGAL::Interval_nt<true>;
using Unprotected = CGAL::Interval_nt<false>;

void shadow(const SymBatch<Protected>& A, const Vec4Batch<Protected>& L, SymBatch<Protected>& P,
            Vec4Batch<Protected>& pi, SymBatch<Protected>& R, int threads);
void shadow(const SymBatch<Unprotected>& A, const Vec4Batch<Unprotected>& L, SymBatch<Unprotected>& P,
            Vec4Batch<Unprotected>& pi, SymBatch<Unprotected>& R, int threads);
void reflection(const SymBatch<Protected>& A, const Vec4Batch<Protected>& planes, AffineBatch<Protected>& M,
                SymBatch<Protected>& B, int threads);
void reflection(const SymBatch<Unprotected>& A, const Vec4Batch<Unprotected>& planes, AffineBatch<Unprotected>& M,
                SymBatch<Unprotected>& B, int threads);

}  // namespace qverify::second_kernel
