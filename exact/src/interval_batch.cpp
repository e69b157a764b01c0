#include <qverify/exact/interval_batch.hpp>

#include <qverify/exact/interval_pack.hpp>

#include "interval_batch_kernel.hpp"
#include "processor_level.hpp"

#ifndef QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL  // set by exact/CMakeLists.txt where the build has a second kernel
#define QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL 0
#endif

#include <string>

namespace qverify {
namespace {

/// Does the second kernel exist in this build and run on this processor?
bool second_kernel_here() { return second_kernel_runs(QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL); }

}  // namespace

template <bool Pr>
void interval_shadow_batch(const SymBatch<CGAL::Interval_nt<Pr>>& A, const Vec4Batch<CGAL::Interval_nt<Pr>>& L,
                           Method method, SymBatch<CGAL::Interval_nt<Pr>>& P, Vec4Batch<CGAL::Interval_nt<Pr>>& pi,
                           SymBatch<CGAL::Interval_nt<Pr>>& R, int threads) {
#if QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL  // (else no call to it, not even an unreachable one: -O0 keeps those)
  if (method == Method::direct && second_kernel_here()) {
    const Eigen::Index n = batch_items("interval_shadow_batch", A.rows(), L.rows());
    sized_output(P, n), sized_output(pi, n), sized_output(R, n);
    second_kernel::shadow(A, L, P, pi, R, threads);
    return;
  }
#endif
  shadow_batch<CGAL::Interval_nt<Pr>>(A, L, method, P, pi, R, threads, interval_batch_setup<Pr>());
}

template <bool Pr>
void interval_reflection_batch(const SymBatch<CGAL::Interval_nt<Pr>>& A,
                               const Vec4Batch<CGAL::Interval_nt<Pr>>& planes, Method method,
                               AffineBatch<CGAL::Interval_nt<Pr>>& M, SymBatch<CGAL::Interval_nt<Pr>>& B, int threads) {
#if QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL
  if (method == Method::direct && second_kernel_here()) {
    const Eigen::Index n = batch_items("interval_reflection_batch", A.rows(), planes.rows());
    sized_output(M, n), sized_output(B, n);
    second_kernel::reflection(A, planes, M, B, threads);
    return;
  }
#endif
  reflection_batch<CGAL::Interval_nt<Pr>>(A, planes, method, M, B, threads, false, interval_batch_setup<Pr>());
}

template void interval_shadow_batch<true>(const SymBatch<CGAL::Interval_nt<true>>&,
                                          const Vec4Batch<CGAL::Interval_nt<true>>&, Method,
                                          SymBatch<CGAL::Interval_nt<true>>&, Vec4Batch<CGAL::Interval_nt<true>>&,
                                          SymBatch<CGAL::Interval_nt<true>>&, int);
template void interval_shadow_batch<false>(const SymBatch<CGAL::Interval_nt<false>>&,
                                           const Vec4Batch<CGAL::Interval_nt<false>>&, Method,
                                           SymBatch<CGAL::Interval_nt<false>>&, Vec4Batch<CGAL::Interval_nt<false>>&,
                                           SymBatch<CGAL::Interval_nt<false>>&, int);
template void interval_reflection_batch<true>(const SymBatch<CGAL::Interval_nt<true>>&,
                                              const Vec4Batch<CGAL::Interval_nt<true>>&, Method,
                                              AffineBatch<CGAL::Interval_nt<true>>&, SymBatch<CGAL::Interval_nt<true>>&,
                                              int);
template void interval_reflection_batch<false>(const SymBatch<CGAL::Interval_nt<false>>&,
                                               const Vec4Batch<CGAL::Interval_nt<false>>&, Method,
                                               AffineBatch<CGAL::Interval_nt<false>>&,
                                               SymBatch<CGAL::Interval_nt<false>>&, int);

const char* build_instruction_set() {
#if defined(__AVX512F__)
  return "AVX-512";
#elif defined(__AVX2__)
  return "AVX2";
#elif defined(__AVX__)
  return "AVX";
#elif defined(__SSE2__)
  return "SSE2";
#else
  return "scalar";
#endif
}

bool interval_batch_dispatched() { return second_kernel_here(); }

const char* interval_batch_second_kernel() {
#if QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL
  return QVERIFY_INTERVAL_SECOND_KERNEL_MARCH;
#else
  return "";
#endif
}

const char* interval_batch_kernel() {
#if QVERIFY_INTERVAL_SECOND_KERNEL_LEVEL
  if (second_kernel_here()) {
    static const std::string name = std::string(QVERIFY_INTERVAL_SECOND_KERNEL_NAME) + " (run-time dispatch)";
    return name.c_str();
  }
#endif
  return build_instruction_set();
}

}  // namespace qverify
