#include <qverify/exact/interval.hpp>
#include <qverify/exact/integer_point.hpp>
#include <qverify/exact/root_point.hpp>

#include <mpfr.h>

#include <stdexcept>

namespace qverify {

Gmpq to_gmpq(const Rational& q) { return Gmpq(q.backend().data()); }

Rational to_rational(const Gmpq& q) { return Rational(q.mpq()); }

Measure to_measure(const Rational& q) {
  Measure m;
  mpfr_set_q(m.backend().data(), q.backend().data(), MPFR_RNDN);
  return m;
}

Rational exact_measure(const Measure& m) {
  Rational q;
  mpfr_get_q(q.backend().data(), m.backend().data());
  return q;
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
  enclose_coordinates();
}

RootPoint RootPoint::with_integer_radicand(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& n) {
  if (n < 0 || denominator(n) != 1) throw std::domain_error("RootPoint: the radicand is not a non-negative integer");
  return n == 0 ? RootPoint(p, Vec4<Rational>::Zero(), n, normalised{}) : RootPoint(p, q, n, normalised{});
}

namespace {

/// x_i = p_i + sign_i r_i with p_i and r_i = sqrt(delta) |q_i| >= 0 enclosed
/// (sign_i = 0 where q_i or delta is 0).
struct EnclosedParts {
  FilterInterval p[4], r[4];
  int sign[4];
};

EnclosedParts enclose_parts(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& delta) {
  // sqrt(delta) |q_i| from the enclosures of delta and q_i; where delta is beyond the
  // range of a double, sqrt(delta) is enclosed in MPFR (whose exponent range is wide) and
  // multiplied by the exact q_i there, each step rounded outwards (no rational product, no
  // gcd; a huge delta with a small q_i is then no harder than a small one).
  const Interval ed = enclose(delta);
  const bool small_root = std::isfinite(ed.sup());
  EnclosedParts e;
  FilterInterval s[4];
  for (int i = 0; i < 4; ++i) {
    const Interval pe = enclose(p(i));
    e.p[i] = FilterInterval(pe.inf(), pe.sup());
    e.sign[i] = delta == 0 ? 0 : q(i).sign();
    if (e.sign[i] == 0 || !small_root) continue;
    const Interval r = enclose(q(i));
    s[i] = e.sign[i] > 0 ? FilterInterval(r.inf(), r.sup()) : FilterInterval(-r.sup(), -r.inf());  // |q_i|
  }
  if (!small_root) {
    MPFR_DECL_INIT(sdlo, 53);
    MPFR_DECL_INIT(sdhi, 53);
    MPFR_DECL_INIT(lo, 53);
    MPFR_DECL_INIT(hi, 53);
    mpfr_set_q(sdlo, delta.backend().data(), MPFR_RNDD);
    mpfr_sqrt(sdlo, sdlo, MPFR_RNDD);
    mpfr_set_q(sdhi, delta.backend().data(), MPFR_RNDU);
    mpfr_sqrt(sdhi, sdhi, MPFR_RNDU);
    for (int i = 0; i < 4; ++i) {
      if (e.sign[i] == 0) continue;
      // |sqrt(delta) q_i|: for q_i < 0 the product rounded up (towards 0) is the lower bound of its magnitude
      const bool neg = e.sign[i] < 0;
      mpfr_mul_q(lo, sdlo, q(i).backend().data(), neg ? MPFR_RNDU : MPFR_RNDD);
      mpfr_mul_q(hi, sdhi, q(i).backend().data(), neg ? MPFR_RNDD : MPFR_RNDU);
      mpfr_abs(lo, lo, MPFR_RNDD);
      mpfr_abs(hi, hi, MPFR_RNDU);
      e.r[i] = FilterInterval(mpfr_get_d(lo, MPFR_RNDD), mpfr_get_d(hi, MPFR_RNDU));
    }
    return e;
  }
  CGAL::Protect_FPU_rounding<true> guard;
  const FilterInterval sd = CGAL::sqrt(FilterInterval(ed.inf(), ed.sup()));
  for (int i = 0; i < 4; ++i)
    if (e.sign[i] != 0) e.r[i] = sd * s[i];
  return e;
}

/// The enclosure of p + sqrt(delta) q (flip = 1) or of its conjugate p - sqrt(delta) q (flip = -1).
PointEnclosure combine(const EnclosedParts& e, int flip) {
  CGAL::Protect_FPU_rounding<true> guard;
  PointEnclosure x;
  for (std::size_t i = 0; i < 4; ++i) {
    const int sign = e.sign[i] * flip;
    x[i] = sign > 0 ? e.p[i] + e.r[i] : sign < 0 ? e.p[i] - e.r[i] : e.p[i];
  }
  return x;
}

}  // namespace

void RootPoint::enclose_coordinates() { enclosure_ = combine(enclose_parts(p_, q_, delta_), 1); }

std::array<RootPoint, 2> RootPoint::conjugates(const Vec4<Rational>& p, const Vec4<Rational>& q, const Rational& n) {
  if (n <= 0 || denominator(n) != 1) throw std::domain_error("RootPoint: the radicand is not a positive integer");
  const EnclosedParts e = enclose_parts(p, q, n);
  return {RootPoint(p, q, n, combine(e, 1)), RootPoint(p, Vec4<Rational>(-q), n, combine(e, -1))};
}

namespace {
/// x -> M x on integers, one canonical fraction per coordinate at the end (Eigen's
/// rational product takes a gcd per operation); M's denominators cleared once.
class ClearedMap {
 public:
  explicit ClearedMap(const Mat4<Rational>& M) { clear_denominators(M, Mi_, DM_); }
  Vec4<Rational> operator()(const Vec4<Rational>& v) const {
    std::array<BigInt, 4> V;
    BigInt Dv;
    clear_denominators(v, V, Dv);
    const BigInt den = DM_ * Dv;
    Vec4<Rational> out;
    for (int i = 0; i < 4; ++i) {
      BigInt num;
      for (int j = 0; j < 4; ++j) num += Mi_[static_cast<std::size_t>(4 * i + j)] * V[static_cast<std::size_t>(j)];
      out(i) = Rational(num, den);
    }
    return out;
  }

 private:
  std::array<BigInt, 16> Mi_;
  BigInt DM_;
};
}  // namespace

RootPoint RootPoint::mapped(const Mat4<Rational>& M) const {
  const ClearedMap apply(M);
  return RootPoint(apply(p_), apply(q_), delta_, normalised{});
}

std::vector<RootPoint> RootPoint::mapped(const std::vector<RootPoint>& xs, const Mat4<Rational>& M) {
  const ClearedMap apply(M);  // once per point set
  std::vector<RootPoint> out;
  out.reserve(xs.size());
  for (const RootPoint& x : xs) out.push_back(RootPoint(apply(x.p_), apply(x.q_), x.delta_, normalised{}));
  return out;
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

// ------------------------------------------------------------ integer_point.hpp

namespace qverify {

namespace {
/// D = lcm of the denominators of n rationals (equal ones, the common case, without a gcd).
void common_denominator(const Rational* v, int n, BigInt& D) {
  D = 1;
  for (int i = 0; i < n; ++i) {
    mpz_srcptr den = mpq_denref(v[i].backend().data());
    if (mpz_cmp_ui(den, 1) == 0 || mpz_cmp(den, mpz(D)) == 0) continue;
    if (mpz_cmp_ui(mpz(D), 1) == 0) mpz_set(mpz(D), den);
    else mpz_lcm(mpz(D), mpz(D), den);
  }
}

void scale_to(const Rational* v, int n, const BigInt& D, BigInt* out) {
  for (int i = 0; i < n; ++i) {
    const auto* e = v[i].backend().data();
    mpz_divexact(mpz(out[i]), mpz(D), mpq_denref(e));
    mpz_mul(mpz(out[i]), mpz(out[i]), mpq_numref(e));
  }
}
}  // namespace

void clear_denominators(const Vec4<Rational>& v, std::array<BigInt, 4>& out, BigInt& D) {
  common_denominator(v.data(), 4, D);
  scale_to(v.data(), 4, D, out.data());
}

void clear_denominators(const Mat4<Rational>& Q, std::array<BigInt, 16>& out, BigInt& D) {
  const Eigen::Matrix<Rational, 4, 4, Eigen::RowMajor> R = Q;
  common_denominator(R.data(), 16, D);
  scale_to(R.data(), 16, D, out.data());
}

namespace {
template <std::size_t N> void divide_gcd(std::array<BigInt, N>& a) {
  BigInt g = 0;
  for (const BigInt& x : a) mpz_gcd(mpz(g), mpz(g), mpz(x));
  if (g > 1)
    for (BigInt& x : a) mpz_divexact(mpz(x), mpz(x), mpz(g));
}
}  // namespace

void primitive_integers(const Vec4<Rational>& v, std::array<BigInt, 4>& out) {
  BigInt D;
  clear_denominators(v, out, D);
  divide_gcd(out);
}

void primitive_integers(const Mat4<Rational>& Q, std::array<BigInt, 16>& out) {
  BigInt D;
  clear_denominators(Q, out, D);
  divide_gcd(out);
}

IntegerPoint::IntegerPoint(const RootPoint& x) {
  clear_denominators(x.p(), P, Dp);
  clear_denominators(x.q(), V, Dv);
  d = numerator(x.delta());  // RootPoint keeps an integer radicand
  rational = d == 0 || x.q().isZero();
  square = !rational && mpz_perfect_square_p(mpz(d)) != 0;
}

void root_norm(BigInt& out, const BigInt& u, const BigInt& v, const BigInt& d, BigInt& t) {
  mpz_mul(mpz(out), mpz(u), mpz(u));
  mpz_mul(mpz(t), mpz(v), mpz(v));
  mpz_submul(mpz(out), mpz(t), mpz(d));
}

int root_sign(const BigInt& u, const BigInt& v, const BigInt& d) {
  const int su = mpz_sgn(mpz(u)), sv = mpz_sgn(mpz(d)) == 0 ? 0 : mpz_sgn(mpz(v));
  if (sv == 0) return su;
  if (su == 0 || su == sv) return sv;
  BigInt n, t;  // opposite signs: the larger of u^2 and v^2 d wins
  root_norm(n, u, v, d, t);
  return su * mpz_sgn(mpz(n));
}

bool root_is_zero(const BigInt& u, const BigInt& v, const BigInt& d, bool square) {
  if (!square && mpz_sgn(mpz(v)) != 0 && mpz_sgn(mpz(d)) != 0) return false;  // sqrt(d) irrational, v != 0
  return root_sign(u, v, d) == 0;
}

namespace {
Measure sqrt_of(const BigInt& d) {
  Measure s;
  mpfr_set_z(s.backend().data(), mpz(d), MPFR_RNDN);
  return sqrt(s);
}
}  // namespace

namespace {
/// root_magnitude with the norm u^2 - v^2 d given when the caller has it (root_value's sign needs it too).
Measure magnitude_with_norm(const BigInt& u, const BigInt& v, const BigInt& d, const Measure& root, const BigInt& den,
                            const BigInt* norm) {
  Measure mu, mv, md;
  mpfr_set_z(mu.backend().data(), mpz(u), MPFR_RNDN);
  mpfr_set_z(md.backend().data(), mpz(den), MPFR_RNDN);
  if (mpz_sgn(mpz(v)) == 0 || mpz_sgn(mpz(d)) == 0) return abs(mu) / md;
  mpfr_set_z(mv.backend().data(), mpz(v), MPFR_RNDN);
  const Measure sum = abs(mu) + abs(mv) * root;
  if (mpz_sgn(mpz(u)) == 0 || mpz_sgn(mpz(u)) == mpz_sgn(mpz(v))) return sum / md;
  BigInt c, t;  // |u^2 - v^2 d|, exact: no cancellation left
  if (norm) c = *norm;
  else root_norm(c, u, v, d, t);
  mpz_abs(mpz(c), mpz(c));
  Measure mc;
  mpfr_set_z(mc.backend().data(), mpz(c), MPFR_RNDN);
  return mc / (sum * md);
}
}  // namespace

Measure root_magnitude(const BigInt& u, const BigInt& v, const BigInt& d, const Measure& root, const BigInt& den) {
  return magnitude_with_norm(u, v, d, root, den, nullptr);
}

Measure root_value(const BigInt& u, const BigInt& v, const BigInt& d, const Measure& root, const BigInt& den) {
  const int su = mpz_sgn(mpz(u)), sv = mpz_sgn(mpz(d)) == 0 ? 0 : mpz_sgn(mpz(v));
  if (sv == 0 || su == 0 || su == sv) {  // no cancellation: the sign is that of either part
    const int sign = sv == 0 ? su : sv;
    if (sign == 0) return Measure(0);
    const Measure m = magnitude_with_norm(u, v, d, root, den, nullptr);
    return sign < 0 ? Measure(-m) : m;
  }
  BigInt n, t;  // opposite signs: the norm decides the sign and serves the magnitude
  root_norm(n, u, v, d, t);
  const int sign = su * mpz_sgn(mpz(n));
  if (sign == 0) return Measure(0);
  const Measure m = magnitude_with_norm(u, v, d, root, den, &n);
  return sign < 0 ? Measure(-m) : m;
}

const Measure& IntegerPoint::root() const {
  if (!root_) root_ = rational ? Measure(0) : sqrt_of(d);
  return *root_;
}

Measure IntegerPoint::coordinate(int i) const { return root_value(u(i), v(i), d, root(), den()); }

Measure IntegerPoint::magnitude(int i) const { return root_magnitude(u(i), v(i), d, root(), den()); }

Measure IntegerPoint::offset(int i, const Rational& c) const {
  // x_i / x_3 - c = ((u_i + v_i s) cd - cn (u_3 + v_3 s)) / ((u_3 + v_3 s) cd), c = cn / cd, s = sqrt(d)
  const BigInt cn = numerator(c), cd = denominator(c);
  const BigInt U = u(i) * cd - cn * u(3), V = v(i) * cd - cn * v(3);
  return root_value(U, V, d, root(), cd) / root_value(u(3), v(3), d, root(), BigInt(1));
}

}  // namespace qverify
