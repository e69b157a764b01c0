// The batch API computes exactly what the single-item functions compute.
#include "dispatch_check.hpp"
#include "laws.hpp"

#include <qverify/batch/batch.hpp>
#include <qverify/batch/items.hpp>
#include <qverify/exact/double_batch.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/interval_batch.hpp>

#include <algorithm>
#include <cfenv>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using namespace qverify;
using Q = Rational;

namespace {
/// A batch stores a symmetric result by its upper triangle; compare those entries (a floating
/// M^T A M is symmetric only up to its last bits).
template <class S> bool same_upper(const SymBatch<S>& X, Eigen::Index i, const Mat4<S>& m) {
  for (int k = 0; k < 10; ++k)
    if (!(X(i, k) == m(kSymRow[k], kSymCol[k]))) return false;
  return true;
}

/// `dispatched`: double batches by double_shadow_batch / double_reflection_batch
/// (exact/double_batch.hpp), which run the second kernel where the build has one and this
/// processor runs it (else the same template as the others).
template <class S> void check_batch_equals_items(int threads, bool dispatched = false) {
  test::RandomRationals rng(5);
  // above the single-thread cut-off, so threads really split the work; odd, so that chunks end
  // in items that do not fill a pack
  const Eigen::Index n = 3001;
  SymBatch<S> A(n, 10);
  Vec4Batch<S> L(n, 4), planes(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    scatter_sym(A, i, test::to_scalar<S>(rng.symmetric()));
    Vec4<Q> l = rng.vec4();
    l(3) = i % 5 == 0 ? Q(0) : Q(1);  // some parallel lights
    if (i % 7 == 0) l(2) = 0;          // some singular frames for the paper route
    L.row(i) = test::to_scalar<S>(l).transpose();
    Vec4<Q> p = rng.vec4();
    if (p.head<3>().isZero()) p(0) = 1;
    planes.row(i) = test::to_scalar<S>(p).transpose();
  }
  for (Method m : {Method::direct, Method::paper}) {
    SymBatch<S> P, R, B;
    Vec4Batch<S> pi;
    AffineBatch<S> M;
    if constexpr (std::is_same_v<S, double>) {
      if (dispatched) {
        double_shadow_batch(A, L, m, P, pi, R, threads);
        double_reflection_batch(A, planes, m, M, B, threads);
      }
    }
    if (!dispatched) {
      shadow_batch<S>(A, L, m, P, pi, R, threads);
      reflection_batch<S>(A, planes, m, M, B, threads);
    }
    // every item in floating point (the packs' stores included), every 37th in exact arithmetic
    for (Eigen::Index i = 0; i < n; i += std::is_same_v<S, Q> ? 37 : 1) {
      const Mat4<S> a = gather_sym(A, i);
      const Vec4<S> l = L.row(i).transpose();
      const ShadowResult<S> s = shadow<S>(a, l, m);
      CHECK(same_upper(P, i, s.P));
      CHECK(Vec4<S>(pi.row(i).transpose()) == s.polar_plane);
      CHECK(same_upper(R, i, s.R));
      const Mat4<S> mm = mirror_matrix<S>(planes.row(i).transpose());
      CHECK(same_upper(B, i, reflection_in_plane<S>(a, planes.row(i).transpose(), m).B));
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) CHECK(M(i, 4 * r + c) == mm(r, c));
    }
  }
}
}  // namespace

TEST_CASE("batch results equal the single-item results: double on 2 threads", "[batch]") {
  check_batch_equals_items<double>(2);
}

TEST_CASE("the fastest double kernel here (exact/double_batch.hpp) gives the single-item results bit for bit",
          "[batch][pack][dispatch]") {
  INFO("double kernel: " << double_batch_kernel() << "; the build's: " << build_instruction_set());
  test::check_dispatch(double_batch_second_kernel(), double_batch_dispatched(), double_batch_kernel());
  // 8 lanes for x86-64-v4 unless its kernel was compiled with 256-bit packs (cmake/ChooseArch.cmake, c4n)
  const bool narrow = std::string(double_batch_kernel()).find("256-bit packs") != std::string::npos;
  CHECK(double_batch_lanes() == (double_batch_dispatched()
                                     ? (std::string(double_batch_second_kernel()) == "x86-64-v4" && !narrow ? 8 : 4)
                                     : static_cast<int>(DoublePack::size())));
  check_batch_equals_items<double>(2, true);
  check_batch_equals_items<double>(1, true);
}

TEST_CASE("a batch whose second input has another number of rows is refused before anything is read", "[batch]") {
  SymBatch<double> A(5, 10), P, R;
  Vec4Batch<double> L(4, 4), pi;
  AffineBatch<double> M;
  A.setOnes(), L.setOnes();
  for (Method m : {Method::direct, Method::paper}) {
    CHECK_THROWS_WITH(shadow_batch<double>(A, L, m, P, pi, R, 2), Catch::Contains("5 quadrics but 4 rows"));
    CHECK_THROWS_AS(reflection_batch<double>(A, L, m, M, P, 2), std::invalid_argument);
    CHECK_THROWS_WITH(double_shadow_batch(A, L, m, P, pi, R, 2), Catch::Contains("5 quadrics but 4 rows"));
    CHECK_THROWS_AS(double_reflection_batch(A, L, m, M, P, 2), std::invalid_argument);
  }
  SymBatch<CGAL::Interval_nt<false>> AI(3, 10), PI, RI;
  Vec4Batch<CGAL::Interval_nt<false>> LI(7, 4), piI;
  AffineBatch<CGAL::Interval_nt<false>> MI;
  CHECK_THROWS_WITH(interval_shadow_batch<false>(AI, LI, Method::direct, PI, piI, RI, 2), Catch::Contains("3 quadrics but 7 rows"));
  CHECK_THROWS_AS(interval_reflection_batch<false>(AI, LI, Method::direct, MI, PI, 2), std::invalid_argument);
  CHECK(P.size() == 0);  // nothing computed
}

// The three ways a block of packs reaches its rows: whole vectors (contiguous rows aligned to the pack),
// row by row (aligned to 16 bytes only, or rows farther apart than their entries), and element by
// element (not even 16-byte aligned). Batches of Eigen matrices take the first; the others are what
// a caller's own rows can meet, and each must write exactly the lanes' values where they belong.
TEST_CASE("a block of double packs is stored to its rows whole, row by row and entry by entry", "[batch][pack]") {
  using Ln = BatchLanes<double>;
  constexpr int W = Ln::width;
  const auto check_store = [&](auto n_tag, Eigen::Index stride, Eigen::Index offset) {
    constexpr int N = decltype(n_tag)::value;
    INFO("N " << N << ", stride " << stride << ", offset " << offset);
    DoublePack v[N];
    for (int k = 0; k < N; ++k) v[k] = DoublePack([&](auto j) { return 1000.0 * k + static_cast<double>(j) + 0.25; });
    Eigen::VectorXd buf = Eigen::VectorXd::Constant(offset + W * stride + 8, -1.0);
    Ln::store<N>(buf.data() + offset, stride, v);
    store_fence();
    for (Eigen::Index x = 0; x < buf.size(); ++x) {
      const Eigen::Index rel = x - offset, j = rel / stride, k = rel % stride;
      const bool written = rel >= 0 && j < W && k < N;
      CHECK(buf(x) == (written ? 1000.0 * k + static_cast<double>(j) + 0.25 : -1.0));
    }
  };
  for (Eigen::Index offset : {0, 1, 2, 8}) {  // 0: aligned to the pack; 2: to 16 bytes only (W > 2); 1: to 8
    check_store(std::integral_constant<int, 4>{}, 4, offset);
    check_store(std::integral_constant<int, 10>{}, 10, offset);
    check_store(std::integral_constant<int, 12>{}, 12, offset);
    check_store(std::integral_constant<int, 10>{}, 12, offset);  // rows farther apart than their entries
  }
}

TEST_CASE("batch results equal the single-item results: exact rationals", "[batch]") {
  check_batch_equals_items<Q>(1);
}

TEST_CASE("the exact integer path: cleared denominators give the same quadrics up to a positive factor", "[batch]") {
  using Int = __int128;
  test::RandomRationals rng(9);
  for (int k = 0; k < 200; ++k) {
    const Mat4<Q> A = rng.symmetric();
    Vec4<Q> L = rng.vec4();
    L(3) = 1;
    Vec4<Q> plane = rng.vec4();
    if (plane.head<3>().isZero()) plane(2) = 1;
    // clear denominators: multiply by the common denominator (a positive factor)
    auto clear = [](auto m) {
      Q l = 1;
      for (Eigen::Index i = 0; i < m.size(); ++i) l = Q(boost::multiprecision::lcm(numerator(l), denominator(m(i))));
      return Eigen::Matrix<Int, decltype(m)::RowsAtCompileTime, decltype(m)::ColsAtCompileTime>(
          m.unaryExpr([&](const Q& x) { return static_cast<Int>(numerator(Q(x * l)).template convert_to<long long>()); }));
    };
    const Mat4<Int> Ai = clear(A);
    const Vec4<Int> Li = clear(L), Pi = clear(plane);
    auto to_q = [](auto m) { return m.unaryExpr([](Int x) { return Q(static_cast<long long>(x)); }).eval(); };
    const Vec4<Int> p = polar_plane<Int>(Ai, Li);
    CHECK(proportional(to_q(tangent_cone_from_polar<Int>(Ai, Li, p)), tangent_cone<Q>(A, L), Factor::positive, Q(0)));
    CHECK(proportional(to_q(p), polar_plane<Q>(A, L), Factor::positive, Q(0)));
    CHECK(proportional(to_q(terminator_quadric_from_polar<Int>(Li, p)), terminator_quadric<Q>(A, L), Factor::nonzero, Q(0)));
    const Mat4<Int> Ms = scaled_mirror_matrix<Int>(Pi);
    CHECK(proportional(to_q(Ms), mirror_matrix<Q>(plane), Factor::positive, Q(0)));
    CHECK(proportional(to_q(mirror_image<Int>(Ai, Ms)), mirror_image<Q>(A, mirror_matrix<Q>(plane)), Factor::positive, Q(0)));
  }
}

// ------------------------------------------------------------------------------------------
// SIMD packs: the batch runs the same formulas W items at a time (batch/pack.hpp,
// exact/interval_pack.hpp).

TEST_CASE("a pack decides only when all its lanes agree", "[batch][pack]") {
  const DoublePack zero(0), one(1);
  CHECK(equals_zero<DoublePack>(zero));
  CHECK_FALSE(equals_zero<DoublePack>(one));
  CHECK(less_than<DoublePack>(zero, one));
  if (DoublePack::size() > 1) {
    const DoublePack mixed([](auto j) { return j == 0 ? 0.0 : 1.0; });
    CHECK_THROWS_AS(equals_zero<DoublePack>(mixed), MixedLanes);
    CHECK_THROWS_AS(less_than<DoublePack>(mixed, DoublePack(0.5)), MixedLanes);
  }
}

namespace {
using IF = CGAL::Interval_nt<false>;

template <class I> bool same_bounds(const I& a, const I& b) {
  auto same = [](double x, double y) { return x == y || (x != x && y != y); };
  return same(a.inf(), b.inf()) && same(a.sup(), b.sup());
}

/// m rounded to double, as exact rationals (inputs whose exact results are known).
template <int R, int C> Eigen::Matrix<Rational, R, C> through_double(const Eigen::Matrix<Rational, R, C>& m) {
  const Eigen::Matrix<double, R, C> d = test::to_scalar<double>(m);
  return d.unaryExpr([](double x) { return to_rational(x); });
}

double as_double(const Rational& q) { return q.convert_to<double>(); }  // exact for these inputs

IF pack_lane(const IntervalPack& p, int j) { return IF(-double(p.nlo[j]), double(p.hi[j])); }

/// A random interval: a point, or two random doubles in order (either sign, or around 0).
IF random_interval(std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(-4, 4);
  const double a = u(g), b = u(g);
  switch (g() % 4) {
    case 0: return IF(a);
    case 1: return IF(std::min(a, b), std::max(a, b));
    case 2: return IF(std::fabs(a) / 8 + 1e-3, std::fabs(a) / 8 + 1e-3 + std::fabs(b));  // positive
    default: return IF(-std::fabs(a) - std::fabs(b) - 1e-3, -std::fabs(a) - 1e-3);       // negative
  }
}
}  // namespace

TEST_CASE("interval packs give CGAL's bounds, operation by operation", "[batch][pack]") {
  CGAL::Protect_FPU_rounding<true> upward;
  std::mt19937_64 g(11);
  constexpr int W = static_cast<int>(DoublePack::size());
  int divisions = 0, refused = 0;
  for (int t = 0; t < 20000; ++t) {
    IF a[W], b[W];
    for (int j = 0; j < W; ++j) a[j] = random_interval(g), b[j] = random_interval(g);
    if (t % 2 == 0)  // divisors of one sign in every lane (with W = 8 random ones rarely are)
      for (int j = 0; j < W; ++j) {
        while (!(b[j].inf() > 0)) b[j] = random_interval(g);
        if (t % 4 == 0) b[j] = -b[j];
      }
    const IntervalPack pa{DoublePack([&](auto j) { return -a[j].inf(); }), DoublePack([&](auto j) { return a[j].sup(); })};
    const IntervalPack pb{DoublePack([&](auto j) { return -b[j].inf(); }), DoublePack([&](auto j) { return b[j].sup(); })};
    const IntervalPack sum = pa + pb, diff = pa - pb, prod = pa * pb, neg = -pa, abs = abs_of<IntervalPack>(pa);
    for (int j = 0; j < W; ++j) {
      CHECK(same_bounds(pack_lane(sum, j), a[j] + b[j]));
      CHECK(same_bounds(pack_lane(diff, j), a[j] - b[j]));
      CHECK(same_bounds(pack_lane(prod, j), a[j] * b[j]));
      CHECK(same_bounds(pack_lane(neg, j), -a[j]));
      CHECK(same_bounds(pack_lane(abs, j), CGAL::abs(a[j])));
    }
    bool all_positive = true, all_negative = true;
    for (int j = 0; j < W; ++j) all_positive &= b[j].inf() > 0, all_negative &= b[j].sup() < 0;
    if (all_positive || all_negative) {
      ++divisions;
      const IntervalPack quot = pa / pb;
      for (int j = 0; j < W; ++j) CHECK(same_bounds(pack_lane(quot, j), a[j] / b[j]));
    } else {
      ++refused;
      CHECK_THROWS_AS(pa / pb, MixedLanes);  // a divisor that may contain 0 (or mixed signs): item by item
    }
  }
  CHECK(divisions > 1000);
  CHECK(refused > 1000);
}

// As for double packs: a block of interval packs is read from and written to its rows by whole
// vectors (contiguous rows: load_pair_rows, and stream_pair_rows where aligned to the pack), or pair
// by pair (rows farther apart than their entries, or only 16-byte aligned); every way must read
// and write exactly the lanes' intervals where they belong.
TEST_CASE("a block of interval packs is loaded from and stored to its rows whole or pair by pair", "[batch][pack]") {
  using Ln = BatchLanes<IF>;
  constexpr int W = Ln::width;
  const auto value = [](int k, int j) { return IF(-1000.0 * k - j - 0.5, 1000.0 * k + j + 0.25); };
  const auto check = [&](auto n_tag, Eigen::Index stride, Eigen::Index offset) {
    constexpr int N = decltype(n_tag)::value;
    INFO("N " << N << ", stride " << stride << ", offset " << offset);
    Eigen::Matrix<IF, Eigen::Dynamic, 1> buf(offset + W * stride + 8);
    buf.setConstant(IF(-7, 7));
    IntervalPack v[N];
    for (int k = 0; k < N; ++k)
      v[k] = IntervalPack(DoublePack([&](auto j) { return -value(k, static_cast<int>(j)).inf(); }),
                          DoublePack([&](auto j) { return value(k, static_cast<int>(j)).sup(); }));
    {
      CGAL::Protect_FPU_rounding<true> upward;
      Ln::store<N>(buf.data() + offset, stride, v);
      store_fence();
    }
    for (Eigen::Index x = 0; x < buf.size(); ++x) {
      const Eigen::Index rel = x - offset, j = rel / stride, k = rel % stride;
      const bool written = rel >= 0 && j < W && k < N;
      CHECK(same_bounds(buf(x), written ? value(static_cast<int>(k), static_cast<int>(j)) : IF(-7, 7)));
    }
    IntervalPack back[N];
    Ln::load<N>(buf.data() + offset, stride, back);
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < W; ++j) CHECK(same_bounds(pack_lane(back[k], j), value(k, j)));
  };
  for (Eigen::Index offset : {0, 1, 2, 4}) {  // in intervals: 0 aligned to the pack; 1 to 16 bytes only
    check(std::integral_constant<int, 4>{}, 4, offset);
    check(std::integral_constant<int, 10>{}, 10, offset);
    check(std::integral_constant<int, 12>{}, 12, offset);
    check(std::integral_constant<int, 10>{}, 12, offset);  // rows farther apart than their entries
  }
}

TEST_CASE("the terminator quadric of intervals is the plane pair pi h^T + h pi^T, bound for bound", "[batch][pack]") {
  // terminator_quadric_from_polar leaves out the terms with a zero factor of h and doubles the diagonal's one
  // product (core/shadow.hpp): for CGAL intervals and for interval packs the same bounds as plane_pair
  CGAL::Protect_FPU_rounding<true> upward;
  std::mt19937_64 g(12);
  constexpr int W = static_cast<int>(DoublePack::size());
  for (int t = 0; t < 2000; ++t) {
    Vec4<IF> pi[W], L[W];
    for (int j = 0; j < W; ++j) {
      for (int k = 0; k < 4; ++k) pi[j](k) = random_interval(g), L[j](k) = random_interval(g);
      L[j](3) = t % 2 ? IF(0) : IF(1);  // parallel and point lights, one kind per pack
    }
    for (int j = 0; j < W; ++j) {
      const Mat4<IF> R = terminator_quadric_from_polar<IF>(L[j], pi[j]);
      const Mat4<IF> pair = plane_pair<IF>(pi[j], frame_plane<IF>(L[j]));
      for (int k = 0; k < 16; ++k) REQUIRE(same_bounds(R(k), pair(k)));
    }
    Vec4<IntervalPack> ppi, pL;
    for (int k = 0; k < 4; ++k) {
      ppi(k) = IntervalPack{DoublePack([&](auto j) { return -pi[j](k).inf(); }), DoublePack([&](auto j) { return pi[j](k).sup(); })};
      pL(k) = IntervalPack{DoublePack([&](auto j) { return -L[j](k).inf(); }), DoublePack([&](auto j) { return L[j](k).sup(); })};
    }
    const Mat4<IntervalPack> R = terminator_quadric_from_polar<IntervalPack>(pL, ppi);
    for (int j = 0; j < W; ++j) {
      const Mat4<IF> pair = plane_pair<IF>(pi[j], frame_plane<IF>(L[j]));
      for (int k = 0; k < 16; ++k) REQUIRE(same_bounds(pack_lane(R(k), j), pair(k)));
    }
  }
}

namespace {
/// Batches of CGAL intervals by packs, against the same formulas item by item with CGAL's
/// Interval_nt (bound for bound), and against the exact results (enclosure). `dispatched`: by
/// interval_shadow_batch / interval_reflection_batch (exact/interval_batch.hpp), which run the
/// second kernel, compiled for another instruction set, where the build has one and this
/// processor runs it (else the same template as here).
template <bool Pr> void check_interval_batch(bool with_faults, bool dispatched = false) {
  using I = CGAL::Interval_nt<Pr>;
  test::RandomRationals rng(21);
  const Eigen::Index n = 2051;
  SymBatch<I> A(n, 10);
  Vec4Batch<I> L(n, 4), planes(n, 4);
  std::vector<Mat4<Rational>> Aq(n);
  std::vector<Vec4<Rational>> Lq(n), Pq(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    // inputs exact in double, so that the exact results of the double inputs are known
    Aq[i] = through_double(rng.symmetric());
    Lq[i] = through_double(rng.vec4());
    Lq[i](3) = i % 5 == 0 ? 0 : 1;  // parallel and point lights share packs: mixed decisions
    Pq[i] = through_double(rng.vec4());
    if (i % 9 == 0) Pq[i](0) = Pq[i](1) = Pq[i](2) = 0, Pq[i](2) = i % 2 ? 1 : -1;
    if (Pq[i].head<3>().isZero()) Pq[i](0) = 1;
    for (int k = 0; k < 10; ++k) A(i, k) = I(as_double(Aq[i](kSymRow[k], kSymCol[k])));
    for (int k = 0; k < 4; ++k) L(i, k) = I(as_double(Lq[i](k))), planes(i, k) = I(as_double(Pq[i](k)));
  }
  if (with_faults) {
    const double inf = std::numeric_limits<double>::infinity(), big = 1e300;
    A(100, 0) = I(1, inf);                   // a non-finite input: its block goes item by item
    A(201, 4) = I(big), L(201, 0) = I(big);  // overflow: inf * 0 = NaN raises invalid
    A(202, 7) = I(-big, big);
    planes(303, 0) = I(-1e-200, 1e-200);     // a divisor n.n that contains 0
  }
  auto upward = [] { return CGAL::Protect_FPU_rounding<true>(); };
  SymBatch<I> P, R, B;
  Vec4Batch<I> pi;
  AffineBatch<I> M;
  if (dispatched) {
    interval_shadow_batch<Pr>(A, L, Method::direct, P, pi, R, 2);
    interval_reflection_batch<Pr>(A, planes, Method::direct, M, B, 2);
  } else {
    shadow_batch<I>(A, L, Method::direct, P, pi, R, 2, upward);
    reflection_batch<I>(A, planes, Method::direct, M, B, 2, false, upward);
  }
  CGAL::Protect_FPU_rounding<true> guard;
  long enclosed = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Mat4<I> a = gather_sym(A, i);
    const Vec4<I> l = L.row(i).transpose(), pl = planes.row(i).transpose();
    const Vec4<I> p = polar_plane<I>(a, l);
    const Mat4<I> Pi = tangent_cone_from_polar<I>(a, l, p), Ri = terminator_quadric_from_polar<I>(l, p);
    const Mat4<I> Mi = mirror_matrix<I>(pl), Bi = mirror_image_of_plane<I>(a, pl);
    bool same = true;
    for (int k = 0; k < 10; ++k) {
      same &= same_bounds(P(i, k), Pi(kSymRow[k], kSymCol[k])) && same_bounds(R(i, k), Ri(kSymRow[k], kSymCol[k])) &&
              same_bounds(B(i, k), Bi(kSymRow[k], kSymCol[k]));
    }
    for (int k = 0; k < 4; ++k) same &= same_bounds(pi(i, k), p(k));
    for (int k = 0; k < 12; ++k) same &= same_bounds(M(i, k), Mi(k / 4, k % 4));
    CHECK(same);
    if (!with_faults && i % 7 == 0) {  // the exact results lie in the intervals
      const Mat4<Rational> Pe = tangent_cone<Rational>(Aq[i], Lq[i]), Be = mirror_image_of_plane<Rational>(Aq[i], Pq[i]);
      bool inside = true;
      for (int k = 0; k < 10; ++k) {
        const Rational pe = Pe(kSymRow[k], kSymCol[k]), be = Be(kSymRow[k], kSymCol[k]);
        inside &= to_rational(P(i, k).inf()) <= pe && pe <= to_rational(P(i, k).sup());
        inside &= to_rational(B(i, k).inf()) <= be && be <= to_rational(B(i, k).sup());
      }
      CHECK(inside);
      ++enclosed;
    }
  }
  if (!with_faults) CHECK(enclosed > 250);
}
}  // namespace

TEST_CASE("interval batches by packs equal CGAL item by item and enclose the exact results", "[batch][pack]") {
  check_interval_batch<false>(false);
  check_interval_batch<true>(false);
}

TEST_CASE("interval batches: non-finite inputs, overflow and a divisor around 0 fall back to CGAL", "[batch][pack]") {
  check_interval_batch<false>(true);
}

TEST_CASE("the fastest interval kernel here (exact/interval_batch.hpp) gives the same bounds, faults included",
          "[batch][pack][dispatch]") {
  INFO("interval kernel: " << interval_batch_kernel() << "; the build's: " << build_instruction_set());
  test::check_dispatch(interval_batch_second_kernel(), interval_batch_dispatched(), interval_batch_kernel());
  check_interval_batch<false>(false, true);
  check_interval_batch<true>(false, true);
  check_interval_batch<false>(true, true);
  check_interval_batch<true>(true, true);
}

TEST_CASE("interval batches of the paper method go through the generic template", "[batch][dispatch]") {
  // the second kernel is the direct route only: the paper route runs item by item either way
  test::RandomRationals rng(23);
  const Eigen::Index n = 64;
  using I = CGAL::Interval_nt<true>;
  SymBatch<I> A(n, 10);
  Vec4Batch<I> L(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Mat4<Rational> a = through_double(rng.symmetric());
    Vec4<Rational> l = through_double(rng.vec4());
    l(3) = 1;
    for (int k = 0; k < 10; ++k) A(i, k) = I(as_double(a(kSymRow[k], kSymCol[k])));
    for (int k = 0; k < 4; ++k) L(i, k) = I(as_double(l(k)));
  }
  SymBatch<I> P1, R1, P2, R2;
  Vec4Batch<I> pi1, pi2;
  interval_shadow_batch<true>(A, L, Method::paper, P1, pi1, R1, 1);
  shadow_batch<I>(A, L, Method::paper, P2, pi2, R2, 1);
  bool same = true;
  for (Eigen::Index i = 0; i < n; ++i) {
    for (int k = 0; k < 10; ++k) same &= same_bounds(P1(i, k), P2(i, k)) && same_bounds(R1(i, k), R2(i, k));
    for (int k = 0; k < 4; ++k) same &= same_bounds(pi1(i, k), pi2(i, k));
  }
  CHECK(same);
}

TEST_CASE("for_each_item runs every item once and reports progress 1..n in order, on 1 and 2 threads", "[batch][items]") {
  for (int threads : {1, 2}) {
    const std::size_t n = 257;
    std::vector<int> runs(n, 0);
    std::vector<std::size_t> seen;
    for_each_item(n, threads, [&](std::size_t done, std::size_t total) {
      CHECK(total == n);
      seen.push_back(done);  // the calls are serialised: no lock needed here
    }, [&](std::size_t k) { ++runs[k]; });
    CHECK(std::count(runs.begin(), runs.end(), 1) == static_cast<long>(n));
    REQUIRE(seen.size() == n);
    for (std::size_t i = 0; i < n; ++i) CHECK(seen[i] == i + 1);
  }
}

TEST_CASE("for_each_item rethrows the first exception of an item, and no progress counts the failed item", "[batch][items]") {
  for (int threads : {1, 2}) {
    std::size_t last = 0;
    CHECK_THROWS_WITH(for_each_item(100, threads, [&](std::size_t done, std::size_t) { last = done; },
                                    [](std::size_t k) {
                                      if (k == 40) throw std::runtime_error("item 40");
                                    }),
                      "item 40");
    CHECK(last < 100);
  }
  int calls = 0;
  for_each_item(0, 2, [&](std::size_t, std::size_t) { ++calls; }, [&](std::size_t) { ++calls; });
  CHECK(calls == 0);
}
