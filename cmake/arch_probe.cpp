// The configure-time probe of QVERIFY_ARCH=auto (cmake/ChooseArch.cmake): times the real batch
// kernel, qverify::shadow_batch of double direct items (batch/batch.hpp), built with the -march
// under test. 2^20 items in row-major batches (about 320 MB, far beyond the caches, as in
// `qverify bench`), one thread, best of several runs of the thread's CPU time (a shared machine
// preempting the probe does not count against either instruction set). Prints the ns per item;
// exits non-zero when a result is not finite (a kernel that does not work is not timed).
//   arch_probe [items] [runs]
#include <qverify/batch/batch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace {
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

int main(int argc, char** argv) {
  using namespace qverify;
  const Eigen::Index n = argc > 1 ? std::atol(argv[1]) : (Eigen::Index(1) << 20);
  const int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  if (n < 1 || runs < 1) return 2;
  SymBatch<double> A(n, 10), P(n, 10), R(n, 10);
  Vec4Batch<double> L(n, 4), pi(n, 4);
  std::uint64_t s = 0x9e3779b97f4a7c15ull;
  auto next = [&s] {  // small rationals p/q, |p| <= 20, 1 <= q <= 9, as the bench's first inputs
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return static_cast<double>(static_cast<int>(s % 41) - 20) / static_cast<double>(1 + (s >> 32) % 9);
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int k = 0; k < 10; ++k) A(i, k) = next();
    for (int k = 0; k < 3; ++k) L(i, k) = next();
    if (L(i, 2) == 0) L(i, 2) = 1;
    L(i, 3) = 1;  // point lights
  }
  P.setZero(), R.setZero(), pi.setZero();  // the output pages are touched before the timing
  double best = HUGE_VAL;
  for (int r = 0; r < runs; ++r) {
    const double t0 = thread_seconds();
    shadow_batch<double>(A, L, Method::direct, P, pi, R, 1);
    best = std::min(best, thread_seconds() - t0);
  }
  for (Eigen::Index i : {Eigen::Index(0), n / 2, n - 1})
    if (!std::isfinite(P(i, 0)) || !std::isfinite(R(i, 9)) || !std::isfinite(pi(i, 3))) return 1;
  std::printf("%.2f\n", 1e9 * best / static_cast<double>(n));
  return 0;
}
