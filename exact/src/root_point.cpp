#include <qverify/exact/root_point.hpp>

namespace qverify {

Gmpq to_gmpq(const Rational& q) { return Gmpq(q.backend().data()); }

Rational to_rational(const Gmpq& q) { return Rational(q.mpq()); }

Measure to_measure(const Rational& q) {
  Measure m;
  mpfr_set_q(m.backend().data(), q.backend().data(), MPFR_RNDN);
  return m;
}

Measure to_measure(const RootNumber& v) {
  const Rational a0 = to_rational(v.a0());
  if (!v.is_extended() || v.a1() == 0) return to_measure(a0);
  const Rational a1 = to_rational(v.a1()), r = to_rational(v.root());
  const Measure s = sqrt(to_measure(r));
  if (a0 == 0 || (a0 > 0) == (a1 > 0)) return to_measure(a0) + to_measure(a1) * s;
  const Rational num = a0 * a0 - a1 * a1 * r;  // exact: no cancellation left
  return to_measure(num) / (to_measure(a0) - to_measure(a1) * s);
}

RootPoint::RootPoint(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& delta) : p_(p), q_(q) {
  if (delta < 0) throw std::domain_error("RootPoint: negative delta");
  // sqrt(n/d) = sqrt(n d) / d: keep an integer radicand.
  const Rational n = numerator(delta), d = denominator(delta);
  delta_ = n * d;
  q_ = q / d;
  if (delta_ == 0) q_.setZero();
}

std::array<RootNumber, 4> RootPoint::coords() const {
  std::array<RootNumber, 4> x;
  const Gmpq root = to_gmpq(delta_);
  for (int i = 0; i < 4; ++i)
    x[static_cast<std::size_t>(i)] = q_(i) == 0 ? RootNumber(to_gmpq(p_(i))) : RootNumber(to_gmpq(p_(i)), to_gmpq(q_(i)), root);
  return x;
}

void RootPoint::check_root(const RootNumber& v) const {
  if (v.is_extended() && v.a1() != 0 && to_rational(v.root()) != delta_)
    throw std::logic_error("RootPoint: value left the field Q(sqrt(delta)) (mixed roots)");
}

RootNumber RootPoint::form(const Mat4<Rational>& Q) const {
  const auto x = coords();
  RootNumber sum(0);
  for (int i = 0; i < 4; ++i) {
    RootNumber row(0);
    for (int j = 0; j < 4; ++j)
      if (Q(i, j) != 0) row += RootNumber(to_gmpq(Q(i, j))) * x[static_cast<std::size_t>(j)];
    sum += x[static_cast<std::size_t>(i)] * row;
  }
  check_root(sum);
  return sum;
}

RootNumber RootPoint::linear(const Vec4<Rational>& pi) const {
  const auto x = coords();
  RootNumber sum(0);
  for (int i = 0; i < 4; ++i)
    if (pi(i) != 0) sum += RootNumber(to_gmpq(pi(i))) * x[static_cast<std::size_t>(i)];
  check_root(sum);
  return sum;
}

Vec3<double> RootPoint::approx_cartesian() const {
  const auto x = coords();
  const Measure w = to_measure(x[3]);
  Vec3<double> c;
  for (int i = 0; i < 3; ++i) c(i) = static_cast<double>(to_measure(x[static_cast<std::size_t>(i)]) / w);
  return c;
}

}  // namespace qverify
