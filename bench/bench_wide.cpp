// Micro-benchmarks of the exact arithmetic for doubles (Google Benchmark): one item's shadow
// (polar plane, cone, R) and reflection (division-free mirror matrix and image) on WideInt<10>,
// from double-valued inputs (full 53-bit significands, exponents spread over 2^-30..2^30, as
// `qverify bench`'s "double-valued" rows) and, for the cost of the operations apart from the limb
// products, from inputs of one limb; one product of one-limb operands copied into place against
// constructed in place; and the exact rows' digit blocks (exact/digit_batch.hpp: W items at once
// on DigitPack<24>, the kernel this processor runs), 256 items per iteration (items_per_second
// gives the time per item). Each item includes reading its doubles and, for the digit blocks,
// the normalization and storing of its results.
//
//   cmake --preset release -DQVERIFY_BUILD_BENCH=ON && cmake --build build/release --target bench_wide
//   build/release/bench/bench_wide
#include <qverify/core/mirror.hpp>
#include <qverify/core/mirror_division_free.hpp>
#include <qverify/core/shadow.hpp>
#include <qverify/exact/digit_batch.hpp>
#include <qverify/exact/wide_int.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <new>
#include <random>
#include <vector>

using namespace qverify;
using W = WideInt<10>;

namespace {

/// Distinct items, cycled (the second argument of the item benchmarks): 2^14 are enough that the
/// branch predictors cannot learn the pattern of operand sizes, as in `qverify bench`'s rows; with
/// 256 they can, and the difference is what the mispredicted branches on the sizes cost.
constexpr int kItems = 1 << 14;
constexpr int kRow[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3}, kCol[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

/// Ten entries of A and a point light (x, y, z, 1) per item; `spread` the range of binary exponents
/// (0: all in [1, 2), one limb after the shift).
struct Doubles {
  std::vector<double> a, l;
  int items;
  Doubles(int spread, int n) : a(10 * static_cast<std::size_t>(n)), l(4 * static_cast<std::size_t>(n)), items(n) {
    std::mt19937_64 g(2026);
    std::uniform_int_distribution<int> exponent(-spread / 2, spread - spread / 2);
    auto next = [&] {
      const double significand = 1 + std::ldexp(static_cast<double>(g() >> 12), -52);  // [1, 2), 53 bits
      return (g() & 1 ? -1 : 1) * std::ldexp(significand, exponent(g));
    };
    for (double& x : a) x = next();
    for (int i = 0; i < n; ++i) l[4 * i] = next(), l[4 * i + 1] = next(), l[4 * i + 2] = next(), l[4 * i + 3] = 1;
  }
  void load(int i, Mat4<W>& A, Vec4<W>& L) const {
    W ai[10], li[4];
    wide_from_doubles<10>(&a[10 * i], 10, ai);
    wide_from_doubles<10>(&l[4 * i], 4, li);
    for (int k = 0; k < 10; ++k) A(kRow[k], kCol[k]) = A(kCol[k], kRow[k]) = ai[k];
    for (int k = 0; k < 4; ++k) L(k) = li[k];
  }
};

void BM_wide_shadow(benchmark::State& state) {
  const Doubles in(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Mat4<W> A;
  Vec4<W> L;
  int i = 0;
  for (auto _ : state) {
    in.load(i, A, L);
    const Vec4<W> p = polar_plane<W>(A, L);
    const Mat4<W> P = tangent_cone_from_polar<W>(A, L, p);
    const Mat4<W> R = terminator_quadric_from_polar<W>(L, p);
    benchmark::DoNotOptimize(P.data());
    benchmark::DoNotOptimize(R.data());
    i = (i + 1) % in.items;
  }
}

void BM_wide_reflection(benchmark::State& state) {
  const Doubles in(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  Mat4<W> A;
  Vec4<W> plane;
  int i = 0;
  for (auto _ : state) {
    in.load(i, A, plane);  // the light's numbers as the mirror plane
    const Mat4<W> M = scaled_mirror_matrix<W>(plane);
    const Mat4<W> B = mirror_image_division_free<W>(A, plane);
    benchmark::DoNotOptimize(M.data());
    benchmark::DoNotOptimize(B.data());
    i = (i + 1) % in.items;
  }
}

/// The digit blocks of the exact rows (exact/digit_batch.hpp, on the kernel this processor runs:
/// W items at once), a chunk of 256 items per iteration, as `qverify bench` calls them; the time
/// per item is the benchmark's time / 256 (items_per_second says it).
template <DigitOp Op> void BM_digit_blocks(benchmark::State& state) {
  const Doubles in(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  constexpr int kChunk = 256;
  DigitBlocks out;
  int i = 0;
  for (auto _ : state) {
    if (digit_blocks(Op, DoubleItems{&in.a[10 * static_cast<std::size_t>(i)], &in.l[4 * static_cast<std::size_t>(i)], kChunk}, out) != 0) {
      state.SkipWithError("a block did not fit");
      break;
    }
    benchmark::DoNotOptimize(out.digits.data());
    i = (i + kChunk) % in.items;
  }
  state.SetItemsProcessed(state.iterations() * kChunk);
  state.SetLabel(digit_blocks_kernel());
}

/// One product of one-limb operands, copied into an array entry (as a formula's result is copied
/// into its matrix) or constructed there.
template <bool InPlace> void BM_wide_product(benchmark::State& state) {
  std::vector<W> a, b, c(kItems);
  std::mt19937_64 g(7);
  for (int k = 0; k < kItems; ++k)
    a.push_back(W::from_magnitude(g() >> 1, g() & 1)), b.push_back(W::from_magnitude(g() >> 1, g() & 1));
  int i = 0;
  for (auto _ : state) {
    if constexpr (InPlace) new (&c[i]) W(a[i] * b[i]);
    else c[i] = a[i] * b[i];
    benchmark::DoNotOptimize(c.data());
    i = (i + 1) % kItems;
  }
}

}  // namespace

// Arguments: the spread of binary exponents (60: double-valued; 0: one limb), the distinct items.
BENCHMARK(BM_wide_shadow)->Name("wide_shadow/double_valued")->Args({60, kItems})->Args({60, 256});
BENCHMARK(BM_wide_shadow)->Name("wide_shadow/one_limb")->Args({0, kItems});
BENCHMARK(BM_wide_reflection)->Name("wide_reflection/double_valued")->Args({60, kItems})->Args({60, 256});
BENCHMARK(BM_wide_reflection)->Name("wide_reflection/one_limb")->Args({0, kItems});
BENCHMARK_TEMPLATE(BM_digit_blocks, DigitOp::shadow)->Name("digit_shadow/double_valued")->Args({60, kItems});
BENCHMARK_TEMPLATE(BM_digit_blocks, DigitOp::reflection)->Name("digit_reflection/double_valued")->Args({60, kItems});
BENCHMARK_TEMPLATE(BM_wide_product, false)->Name("wide_product_1x1/copied");
BENCHMARK_TEMPLATE(BM_wide_product, true)->Name("wide_product_1x1/in_place");

BENCHMARK_MAIN();
