// The second double kernel: the generic batch template of batch/batch.hpp on DoublePack, compiled
// with the -march (and, where measured faster, the compiler: clang++) chosen for it
// (exact/CMakeLists.txt; exact/double_batch.hpp says why and
// when it runs). Direct method only: the paper route runs item by item.
#include "double_batch_kernel.hpp"

#include <qverify/batch/batch.hpp>

// The point of this file is its instruction set: a -march lost or overridden on the way must fail
// the build, not give a second copy of the build's own kernel.
#if QVERIFY_SECOND_KERNEL_LEVEL == 4 && !defined(__AVX512F__)
#error "the second double kernel must be compiled with AVX-512 (-march=x86-64-v4)"
#elif QVERIFY_SECOND_KERNEL_LEVEL == 3 && !defined(__AVX2__)
#error "the second double kernel must be compiled with AVX2 (-march=x86-64-v3)"
#endif

namespace qverify::second_kernel {

void shadow(const SymBatch<double>& A, const Vec4Batch<double>& L, SymBatch<double>& P, Vec4Batch<double>& pi,
            SymBatch<double>& R, int threads) {
  shadow_batch<double>(A, L, Method::direct, P, pi, R, threads);
}
void reflection(const SymBatch<double>& A, const Vec4Batch<double>& planes, AffineBatch<double>& M,
                SymBatch<double>& B, int threads) {
  reflection_batch<double>(A, planes, Method::direct, M, B, threads);
}
int double_lanes() { return static_cast<int>(DoublePack::size()); }

}  // namespace qverify::second_kernel
