// The second interval kernel: the generic batch template of batch/batch.hpp on IntervalPack,
// compiled with -march=QVERIFY_INTERVAL_MARCH (exact/CMakeLists.txt; exact/interval_batch.hpp says
// why and when it runs). Direct method only: the paper route runs item by item.
#include "interval_batch_kernel.hpp"

#include <qverify/exact/interval_pack.hpp>

// The point of this file is its instruction set: a -march lost or overridden on the way (a later
// flag wins) must fail the build, not give a second copy of the build's own kernel.
#if QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL == 4 && !defined(__AVX512F__)
#error "the second interval kernel must be compiled with AVX-512 (-march=x86-64-v4)"
#elif QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL == 3 && !defined(__AVX2__)
#error "the second interval kernel must be compiled with AVX2 (-march=x86-64-v3)"
#endif

namespace qverify::second_kernel {
namespace {

template <bool Pr>
void shadow_of(const SymBatch<CGAL::Interval_nt<Pr>>& A, const Vec4Batch<CGAL::Interval_nt<Pr>>& L,
               SymBatch<CGAL::Interval_nt<Pr>>& P, Vec4Batch<CGAL::Interval_nt<Pr>>& pi,
               SymBatch<CGAL::Interval_nt<Pr>>& R, int threads) {
  shadow_batch<CGAL::Interval_nt<Pr>>(A, L, Method::direct, P, pi, R, threads, interval_batch_setup<Pr>());
}

template <bool Pr>
void reflection_of(const SymBatch<CGAL::Interval_nt<Pr>>& A, const Vec4Batch<CGAL::Interval_nt<Pr>>& planes,
                   AffineBatch<CGAL::Interval_nt<Pr>>& M, SymBatch<CGAL::Interval_nt<Pr>>& B, int threads) {
  reflection_batch<CGAL::Interval_nt<Pr>>(A, planes, Method::direct, M, B, threads, false, interval_batch_setup<Pr>());
}

}  // namespace

void shadow(const SymBatch<Protected>& A, const Vec4Batch<Protected>& L, SymBatch<Protected>& P,
            Vec4Batch<Protected>& pi, SymBatch<Protected>& R, int threads) {
  shadow_of<true>(A, L, P, pi, R, threads);
}
void shadow(const SymBatch<Unprotected>& A, const Vec4Batch<Unprotected>& L, SymBatch<Unprotected>& P,
            Vec4Batch<Unprotected>& pi, SymBatch<Unprotected>& R, int threads) {
  shadow_of<false>(A, L, P, pi, R, threads);
}
void reflection(const SymBatch<Protected>& A, const Vec4Batch<Protected>& planes, AffineBatch<Protected>& M,
                SymBatch<Protected>& B, int threads) {
  reflection_of<true>(A, planes, M, B, threads);
}
void reflection(const SymBatch<Unprotected>& A, const Vec4Batch<Unprotected>& planes, AffineBatch<Unprotected>& M,
                SymBatch<Unprotected>& B, int threads) {
  reflection_of<false>(A, planes, M, B, threads);
}

}  // namespace qverify::second_kernel
