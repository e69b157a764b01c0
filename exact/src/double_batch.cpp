// exact/double_batch.hpp: the build's own double batches, and the dispatch to the second kernel
// (double_batch_kernel.cpp) where the configure measured it faster and the processor has it.
#include <qverify/exact/double_batch.hpp>

#include <qverify/batch/batch.hpp>
#include <qverify/exact/interval_batch.hpp>  // build_instruction_set

#include "double_batch_kernel.hpp"
#include "processor_level.hpp"

#ifndef QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL  // set by exact/CMakeLists.txt where the build has one
#define QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL 0
#endif

#include <string>

namespace qverify {
namespace {

/// Does the second kernel exist in this build and run on this processor?
bool second_double_kernel_here() { return second_kernel_runs(QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL); }

}  // namespace

void double_shadow_batch(const SymBatch<double>& A, const Vec4Batch<double>& L, Method method, SymBatch<double>& P,
                         Vec4Batch<double>& pi, SymBatch<double>& R, int threads) {
#if QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL  // (else no call to it, not even an unreachable one: -O0 keeps those)
  if (method == Method::direct && second_double_kernel_here()) {
    const Eigen::Index n = batch_items("double_shadow_batch", A.rows(), L.rows());
    sized_output(P, n), sized_output(pi, n), sized_output(R, n);  // here: the copy never allocates
    second_kernel::shadow(A, L, P, pi, R, threads);
    return;
  }
#endif
  shadow_batch<double>(A, L, method, P, pi, R, threads);
}

void double_reflection_batch(const SymBatch<double>& A, const Vec4Batch<double>& planes, Method method,
                             AffineBatch<double>& M, SymBatch<double>& B, int threads) {
#if QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL
  if (method == Method::direct && second_double_kernel_here()) {
    const Eigen::Index n = batch_items("double_reflection_batch", A.rows(), planes.rows());
    sized_output(M, n), sized_output(B, n);
    second_kernel::reflection(A, planes, M, B, threads);
    return;
  }
#endif
  reflection_batch<double>(A, planes, method, M, B, threads);
}

bool double_batch_dispatched() { return second_double_kernel_here(); }

const char* double_batch_second_kernel() {
#if QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL
  return QVERIFY_DOUBLE_SECOND_KERNEL_MARCH;
#else
  return "";
#endif
}

const char* double_batch_kernel() {
#if QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL
  if (second_double_kernel_here()) {
    static const std::string name = std::string(QVERIFY_DOUBLE_SECOND_KERNEL_NAME) + " (run-time dispatch)";
    return name.c_str();
  }
#endif
  return build_instruction_set();
}

int double_batch_lanes() {
#if QVERIFY_DOUBLE_SECOND_KERNEL_LEVEL
  if (second_double_kernel_here()) return second_kernel::double_lanes();
#endif
  return static_cast<int>(DoublePack::size());
}

}  // namespace qverify
