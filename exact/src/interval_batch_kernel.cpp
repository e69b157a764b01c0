// The second interval kernel: the generic batch template of batch/batch.hpp on IntervalPack,
// compiled with -march=QVERIFY_INTERVAL_MARCH (QVERIFY_SECOND_KERNEL_LEVEL; exact/CMakeLists.txt; exact/interval_batch.hpp says
// why and when it runs). Direct method only: the paper route runs item by item.
#include "interval_batch_kernel.hpp"

#include <qverify/exact/interval_pack.hpp>

// The point of this file is its instruction set: a -march lost or overridden on the way (a later
// flag wins) must fail the build, not give a second copy of the build's own kernel.
#if QVERIFY_SECOND_KERNEL_LEVEL == 4 && !defined(__AVX512F__)
#error "the second interval kernel must be compiled with AVX-512 (-march=x86-64-v4)"
#elif QVERIFY_SECOND_KERNEL_LEVEL == 3 && !defined(__AVX2__)
#error "the second interval kernel must be compiled with AVX2 (-march=x86-64-v3)"
#endif

namespace qverify::second_kernel {

void shadow(const SymBatch<Protected>& A, const Vec4Batch<Protected>& L, SymBatch<Protected>& P,
            Vec4Batch<Protected>& pi, SymBatch<Protected>& R, int threads) {
  shadow_batch<Protected>(A, L, Method::direct, P, pi, R, threads, interval_batch_setup<true>());
}
void shadow(const SymBatch<Unprotected>& A, const Vec4Batch<Unprotected>& L, SymBatch<Unprotected>& P,
            Vec4Batch<Unprotected>& pi, SymBatch<Unprotected>& R, int threads) {
  shadow_batch<Unprotected>(A, L, Method::direct, P, pi, R, threads, interval_batch_setup<false>());
}
void reflection(const SymBatch<Protected>& A, const Vec4Batch<Protected>& planes, AffineBatch<Protected>& M,
                SymBatch<Protected>& B, int threads) {
  reflection_batch<Protected>(A, planes, Method::direct, M, B, threads, false, interval_batch_setup<true>());
}
void reflection(const SymBatch<Unprotected>& A, const Vec4Batch<Unprotected>& planes, AffineBatch<Unprotected>& M,
                SymBatch<Unprotected>& B, int threads) {
  reflection_batch<Unprotected>(A, planes, Method::direct, M, B, threads, false, interval_batch_setup<false>());
}

}  // namespace qverify::second_kernel
