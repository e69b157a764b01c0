#pragma once
// The entry points of the second double kernel (double_batch_kernel.cpp, compiled for
// QVERIFY_DOUBLE_MARCH; exact/double_batch.hpp says why). As for the interval kernel
// (interval_batch_kernel.hpp), only these symbols of its object stay global: plain functions taking
// the batches by reference, outputs sized by the caller.

#include <qverify/batch/rows.hpp>

namespace qverify::second_kernel {

void shadow(const SymBatch<double>& A, const Vec4Batch<double>& L, SymBatch<double>& P, Vec4Batch<double>& pi,
            SymBatch<double>& R, int threads);
void reflection(const SymBatch<double>& A, const Vec4Batch<double>& planes, AffineBatch<double>& M,
                SymBatch<double>& B, int threads);
int double_lanes();

}  // namespace qverify::second_kernel
