// Micro-benchmarks of single items (Google Benchmark): the tangent cone P and
// the mirror image B = M^T A M, for every scalar type of the ladder and for
// the three exact rational candidates (Boost mpq_rational on GMP, CGAL::Gmpq,
// Boost cpp_rational). Inputs are random small rationals (|p| <= 20, q <= 9),
// converted once; results are kept (DoNotOptimize) so nothing is optimised away.
//
//   cmake --preset release -DQVERIFY_BUILD_BENCH=ON && cmake --build build/release --target bench_scalars
//   build/release/bench/bench_scalars --benchmark_filter='Rational|Gmpq|Cpp'
//   build/release/bench/bench_scalars --benchmark_filter='shadow_(direct|status)/double'   # the status filter's cost
#include <boost/multiprecision/cpp_int.hpp>
#include <qverify/core/core.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/root_point.hpp>  // CGAL::Gmpq

#include <CGAL/Gmpq.h>
#include <benchmark/benchmark.h>

#include <random>

// Boost 1.74's cpp_int asks whether any argument type is a "byte container" (has a
// const_iterator over bytes); Eigen 3.4 declares const_iterator = void for matrices and
// expressions, which breaks the trait. This translation unit
// never builds a cpp_int from bytes, so the trait is switched off here, and only here.
namespace boost::multiprecision::detail {
template <class C> struct is_byte_container_imp<C, true> : boost::false_type {};
}  // namespace boost::multiprecision::detail

using namespace qverify;
using CppRational =
    boost::multiprecision::number<boost::multiprecision::cpp_rational_backend, boost::multiprecision::et_off>;

namespace {

constexpr int kItems = 64;

Rational random_rational(std::mt19937_64& g) {
  std::uniform_int_distribution<int> p(-20, 20), q(1, 9);
  return Rational(p(g)) / Rational(q(g));
}

template <class S> S convert(const Rational& q) {
  if constexpr (std::is_same_v<S, CGAL::Gmpq>) return to_gmpq(q);
  else if constexpr (std::is_same_v<S, CppRational>) return CppRational(numerator(q).str()) / CppRational(denominator(q).str());
  else {
    RoundingReport rep;
    return round_rational<S>(q, rep);
  }
}

template <class S> struct Inputs {
  std::vector<Mat4<S>> A;
  std::vector<Vec4<S>> L, planes;
  Inputs() {
    std::mt19937_64 g(42);
    for (int k = 0; k < kItems; ++k) {
      Mat4<S> a;
      for (int i = 0; i < 4; ++i)
        for (int j = i; j < 4; ++j) a(i, j) = a(j, i) = convert<S>(random_rational(g));
      A.push_back(a);
      L.emplace_back(convert<S>(random_rational(g)), convert<S>(random_rational(g)), convert<S>(random_rational(g)), S(1));
      planes.emplace_back(convert<S>(random_rational(g)), convert<S>(random_rational(g)), S(1), convert<S>(random_rational(g)));
    }
  }
};

template <class S> void BM_shadow_direct(benchmark::State& state) {
  if constexpr (std::is_same_v<S, Mpfr>) set_mpfr_bits(static_cast<unsigned>(state.range(0)));
  const Inputs<S> in;
  std::size_t k = 0;
  for (auto _ : state) {
    Mat4<S> P = tangent_cone<S>(in.A[k], in.L[k]);
    Vec4<S> pi = polar_plane<S>(in.A[k], in.L[k]);
    benchmark::DoNotOptimize(P);
    benchmark::DoNotOptimize(pi);
    k = (k + 1) % kItems;
  }
  state.SetItemsProcessed(state.iterations());
}

template <class S> void BM_shadow_paper(benchmark::State& state) {
  if constexpr (std::is_same_v<S, Mpfr>) set_mpfr_bits(static_cast<unsigned>(state.range(0)));
  const Inputs<S> in;
  std::size_t k = 0;
  for (auto _ : state) {
    const PaperFrame<S> f = paper_frame<S>(in.L[k]);
    const Mat4<S> C = paper_C<S>(in.A[k], f);
    Mat4<S> P = paper_P<S>(paper_D<S>(C), f);
    benchmark::DoNotOptimize(P);
    k = (k + 1) % kItems;
  }
  state.SetItemsProcessed(state.iterations());
}

template <class S> void BM_reflection(benchmark::State& state) {
  if constexpr (std::is_same_v<S, Mpfr>) set_mpfr_bits(static_cast<unsigned>(state.range(0)));
  const Inputs<S> in;
  std::size_t k = 0;
  for (auto _ : state) {
    const Mat4<S> M = mirror_matrix<S>(in.planes[k]);
    Mat4<S> B = mirror_image<S>(in.A[k], M);
    benchmark::DoNotOptimize(B);
    k = (k + 1) % kItems;
  }
  state.SetItemsProcessed(state.iterations());
}

/// The status predicates (core/predicates.hpp) of the same inputs, random and non-degenerate: what deciding
/// the status words costs beside an item. For double the core's filter (Filtered<double>); the counter
/// `undecided` is the fraction of items it leaves to the exact settlement (none here, as it should be).
template <class S> void BM_shadow_status(benchmark::State& state) {
  const Inputs<S> in;
  std::size_t k = 0;
  long undecided = 0;
  for (auto _ : state) {
    StatusDecision d = shadow_status<S>(in.A[k], in.L[k]);
    undecided += d.undecided != 0;
    benchmark::DoNotOptimize(d);
    k = (k + 1) % kItems;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["undecided"] = static_cast<double>(undecided) / static_cast<double>(state.iterations());
}

}  // namespace

namespace Eigen {
template <> struct NumTraits<CppRational> : GenericNumTraits<CppRational> {
  using Real = CppRational;
  using NonInteger = CppRational;
  using Literal = CppRational;
  using Nested = CppRational;
  enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 1, ReadCost = 1, AddCost = 20, MulCost = 40 };
  static Real epsilon() { return Real(0); }
  static Real dummy_precision() { return Real(0); }
  static int digits10() { return 0; }
};
}  // namespace Eigen

#define QV_BENCH_ALL(S, NAME)                                         \
  BENCHMARK_TEMPLATE(BM_shadow_direct, S)->Name("shadow_direct/" NAME); \
  BENCHMARK_TEMPLATE(BM_shadow_paper, S)->Name("shadow_paper/" NAME);   \
  BENCHMARK_TEMPLATE(BM_reflection, S)->Name("reflection/" NAME);

QV_BENCH_ALL(float, "float")
QV_BENCH_ALL(double, "double")
QV_BENCH_ALL(long double, "long_double")
QV_BENCH_ALL(Float128, "float128")
BENCHMARK_TEMPLATE(BM_shadow_direct, Mpfr)->Name("shadow_direct/mpfr")->Arg(128)->Arg(256);
BENCHMARK_TEMPLATE(BM_reflection, Mpfr)->Name("reflection/mpfr")->Arg(128)->Arg(256);
QV_BENCH_ALL(Rational, "Rational_mpq")
QV_BENCH_ALL(CGAL::Gmpq, "Gmpq")
QV_BENCH_ALL(CppRational, "CppRational")

BENCHMARK_TEMPLATE(BM_shadow_status, double)->Name("shadow_status/double");
BENCHMARK_TEMPLATE(BM_shadow_status, Rational)->Name("shadow_status/Rational_mpq");

BENCHMARK_MAIN();
