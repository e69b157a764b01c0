// The configure-time probe of QVERIFY_ARCH=auto (cmake/ChooseArch.cmake): times the real batch
// kernels, qverify::shadow_batch of direct items (batch/batch.hpp) in double and in certified
// intervals (exact/interval_pack.hpp), and the exact shadows of double-valued items in digit blocks
// (exact/src/digit_batch_impl.hpp, 2^14 items), built with the -march under test. 2^19 items in row-major
// batches at a configure (about 150 MB of doubles, 2^17 items of intervals: far beyond the caches,
// as in `qverify bench`), one thread, best of several runs of the thread's CPU time (a shared machine
// preempting the probe does not count against either instruction set). Prints the ns per item;
// exits non-zero when a result is not finite (a kernel that does not work is not timed).
//   arch_probe double|interval|exact [items] [runs]   (interval, exact: built with -DQVERIFY_PROBE_INTERVAL=1)
// and, not measured by the configure but for comparing builds by hand (scripts/alternate),
//   arch_probe double-reflection|interval-reflection [items] [runs]   (the reflection batch)
#include <qverify/batch/batch.hpp>
#if QVERIFY_PROBE_INTERVAL  // where CGAL, GMP and MPFR were found (cmake/ChooseArch.cmake)
#include <qverify/exact/interval_pack.hpp>

#include "digit_batch_impl.hpp"  // exact/src: the digit blocks themselves, compiled here
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

namespace {
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

/// The best time per item of `runs` runs of shadow_batch<S> (reflection_batch<S> with `reflection`, the
/// lights read as mirror planes) on n small-rational items.
template <class S, class Setup> int time_kernel(Eigen::Index n, int runs, Setup setup, bool reflection = false) {
  using namespace qverify;
  SymBatch<S> A(n, 10), P(n, 10), R(n, 10);
  Vec4Batch<S> L(n, 4), pi(n, 4);
  std::uint64_t s = 0x9e3779b97f4a7c15ull;
  auto next = [&s] {  // small rationals p/q, |p| <= 20, 1 <= q <= 9, as the bench's first inputs
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    return static_cast<double>(static_cast<int>(s % 41) - 20) / static_cast<double>(1 + (s >> 32) % 9);
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int k = 0; k < 10; ++k) A(i, k) = S(next());
    for (int k = 0; k < 2; ++k) L(i, k) = S(next());
    const double z = next();
    L(i, 2) = S(z == 0 ? 1.0 : z);
    L(i, 3) = S(1);  // point lights
  }
  AffineBatch<S> M(reflection ? n : 0, 12);
  P.setConstant(S(0)), R.setConstant(S(0)), pi.setConstant(S(0)), M.setConstant(S(0));  // the output pages are
                                                                                        // touched before the timing
  double best = HUGE_VAL;
  for (int r = 0; r < runs; ++r) {
    const double t0 = thread_seconds();
    if (reflection) reflection_batch<S>(A, L, Method::direct, M, P, 1, false, setup);
    else shadow_batch<S>(A, L, Method::direct, P, pi, R, 1, setup);
    best = std::min(best, thread_seconds() - t0);
  }
  auto finite = [](const S& x) { return ScalarOps<S>::finite(x); };
  for (Eigen::Index i : {Eigen::Index(0), n / 2, n - 1})
    if (!finite(P(i, 0)) || !finite(R(i, 9)) || !finite(pi(i, 3)) || (reflection && !finite(M(i, 11)))) return 1;
  std::printf("%.2f\n", 1e9 * best / static_cast<double>(n));
  return 0;
}

#if QVERIFY_PROBE_INTERVAL
/// The best time per item of `runs` runs of the exact digit-block shadows of n double-valued items
/// (full 53-bit significands, exponents over 2^-30..2^30, as `qverify bench`'s).
int time_exact(Eigen::Index n, int runs) {
  using namespace qverify;
  std::vector<double> a(static_cast<std::size_t>(10 * n)), l(static_cast<std::size_t>(4 * n));
  std::uint64_t s = 0x9e3779b97f4a7c15ull;
  auto next = [&s] {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    const double m = std::ldexp(static_cast<double>((s >> 11) | (std::uint64_t(1) << 52)), -52);
    return ((s & 1) ? -m : m) * std::ldexp(1.0, static_cast<int>((s >> 1) % 61) - 30);
  };
  for (double& x : a) x = next();
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) l[static_cast<std::size_t>(4 * i + k)] = k == 3 ? 1.0 : next();
  DigitBlocks out;
  double best = HUGE_VAL;
  long left = 0;
  for (int r = 0; r < runs; ++r) {
    const double t0 = thread_seconds();
    left = run_blocks(DigitOp::shadow, DoubleItems{a.data(), l.data(), n}, out);
    best = std::min(best, thread_seconds() - t0);
  }
  if (left != 0 || out.counts.empty() || out.counts[0] == 0) return 1;
  std::printf("%.2f\n", 1e9 * best / static_cast<double>(n));
  return 0;
}
#endif

int main(int argc, char** argv) {
  const std::string kind = argc > 1 ? argv[1] : "double";
  const Eigen::Index n = argc > 2 ? std::atol(argv[2]) : (Eigen::Index(1) << 20);
  const int runs = argc > 3 ? std::atoi(argv[3]) : 5;
  if (n < 1 || runs < 1) return 2;
  if (kind == "double") return time_kernel<double>(n, runs, [] { return 0; });
  if (kind == "double-reflection") return time_kernel<double>(n, runs, [] { return 0; }, true);
#if QVERIFY_PROBE_INTERVAL
  if (kind == "interval")
    return time_kernel<CGAL::Interval_nt<false>>(n, runs, [] { return CGAL::Protect_FPU_rounding<true>(); });
  if (kind == "interval-reflection")
    return time_kernel<CGAL::Interval_nt<false>>(n, runs, [] { return CGAL::Protect_FPU_rounding<true>(); }, true);
  if (kind == "exact") return time_exact(n, runs);
#endif
  return 2;
}
