// The batch API computes exactly what the single-item functions compute.
#include "laws.hpp"

#include <qverify/core/batch.hpp>

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

template <class S> void check_batch_equals_items(int threads) {
  test::RandomRationals rng(5);
  const Eigen::Index n = 3000;  // above the single-thread cut-off, so threads really split the work
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
    shadow_batch<S>(A, L, m, P, pi, R, threads);
    reflection_batch<S>(A, planes, m, M, B, threads);
    for (Eigen::Index i = 0; i < n; i += 37) {
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
