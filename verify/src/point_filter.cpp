#include <qverify/verify/point_filter.hpp>

#include <qverify/exact/root_enclosure.hpp>

#include <cmath>
#include <limits>

namespace qverify {

namespace {

using I = FilterInterval;


/// pass when all of |f|^2 is at most all of the bound, fail when all of it is
/// beyond; a NaN anywhere compares false both ways: undecided.
FilterVerdict decide(const I& f2, const I& bound) {
  if (f2.sup() <= bound.inf()) return FilterVerdict::pass;
  if (f2.inf() > bound.sup()) return FilterVerdict::fail;
  return FilterVerdict::undecided;
}

I norm2(const EnclosedPoint& x) {
  return CGAL::square(x.x[0]) + CGAL::square(x.x[1]) + CGAL::square(x.x[2]) + CGAL::square(x.x[3]);
}

}  // namespace

FilterTarget::FilterTarget(double accuracy_, const Measure& size_)
    : accuracy(accuracy_), T(accuracy_), size(size_), residual_rule(!(size_ > 0)) {
  if (residual_rule) {
    bound = I(accuracy);
    return;
  }
  // T * size to 80 digits, rounded to nearest, then one ulp each way: a strict
  // enclosure (the product's own rounding is ~1e-80 relative).
  const double c = static_cast<double>(Measure(T * size));
  bound = I(std::nextafter(c, -std::numeric_limits<double>::infinity()),
            std::nextafter(c, std::numeric_limits<double>::infinity()));
}

FilterVerdict filter_quadric(const EnclosedPoint& x, const Mat4<double>& Q, const FilterTarget& t) {
  const auto& X = x.x;
  I y[4];
  for (int i = 0; i < 4; ++i) y[i] = X[0] * Q(i, 0) + X[1] * Q(i, 1) + X[2] * Q(i, 2) + X[3] * Q(i, 3);
  const I f = X[0] * y[0] + X[1] * y[1] + X[2] * y[2] + X[3] * y[3];
  const I f2 = CGAL::square(f);
  if (!t.residual_rule) {
    // |f| <= T size |w| 2 |g|, squared: f^2 <= 4 (T size)^2 w^2 |g|^2
    const I g2 = CGAL::square(y[0]) + CGAL::square(y[1]) + CGAL::square(y[2]);
    const FilterVerdict v = decide(f2, CGAL::square(t.bound) * CGAL::square(X[3]) * g2 * 4.0);
    if (v != FilterVerdict::fail) return v;
    // final where the second order cannot do better: d2 < d1 needs 4 |g|^2 < |f| kappa, and every
    // curvature kappa is at most |K|_F (K the symmetrised spatial part)
    I k2(0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) k2 += CGAL::square((I(Q(i, j)) + I(Q(j, i))) / 2.0);
    return (g2 * 4.0).inf() >= (CGAL::abs(f) * CGAL::sqrt(k2)).sup() ? FilterVerdict::fail : FilterVerdict::undecided;
  }
  // |f| <= T |Q|_F |x|^2, squared
  I q2(0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) q2 += CGAL::square(I(Q(i, j)));
  return decide(f2, CGAL::square(t.bound) * q2 * CGAL::square(norm2(x)));
}

FilterVerdict filter_plane(const EnclosedPoint& x, const Vec4<double>& pi, const FilterTarget& t) {
  const auto& X = x.x;
  const I f = X[0] * pi(0) + X[1] * pi(1) + X[2] * pi(2) + X[3] * pi(3);
  const I f2 = CGAL::square(f);
  const I n2 = CGAL::square(I(pi(0))) + CGAL::square(I(pi(1))) + CGAL::square(I(pi(2)));
  if (!t.residual_rule)  // |f| <= T size |w| |pi_xyz|, squared
    return decide(f2, CGAL::square(t.bound) * CGAL::square(X[3]) * n2);
  // |f| <= T |pi| |x|, squared
  return decide(f2, CGAL::square(t.bound) * (n2 + CGAL::square(I(pi(3)))) * norm2(x));
}

FilterVerdict filter_quadric_guarded(const EnclosedPoint& x, const Mat4<double>& Q, const FilterTarget& t) {
  FilterRounding guard;
  return filter_quadric(x, Q, t);
}

FilterVerdict filter_plane_guarded(const EnclosedPoint& x, const Vec4<double>& pi, const FilterTarget& t) {
  FilterRounding guard;
  return filter_plane(x, pi, t);
}

bool exact_quadric_passes(const RootPoint& x, const Mat4<Rational>& Q, const FilterTarget& t) {
  return !(relative(measure_quadric({x}, Q), t.size) > t.T);
}

bool exact_plane_passes(const RootPoint& x, const Vec4<Rational>& pi, const FilterTarget& t) {
  return !(relative(measure_plane({x}, pi), t.size) > t.T);
}

// --------------------------------------------------- exact integers (stage 2, proof mode)

namespace {

/// out = sum_j row[j] * x[j] (zero entries skipped).
void dot4(mpz_t out, const BigInt* row, const std::array<BigInt, 4>& x) {
  mpz_set_ui(out, 0);
  for (int j = 0; j < 4; ++j)
    if (mpz_sgn(mpz(row[j])) != 0) mpz_addmul(out, mpz(row[j]), mpz(x[j]));
}

/// Scratch numbers of one thread (no allocation per check once they have grown).
/// 128 bits: the direct difference of a value's two parts stays tight unless they agree to
/// about 2^-96 of themselves, so the exact norm is rarely needed (root_enclosure.hpp).
constexpr mpfr_prec_t kStageBits = 128;
struct Scratch {
  BigInt y[4], zz[4], a, b, c, t, f0, f1, g0, g1;
  mpfr_t lo[8], hi[8], tmp;
  RootEnclosure& root = thread_root_enclosure(kStageBits);
  Scratch() {
    for (int k = 0; k < 8; ++k) mpfr_init2(lo[k], kStageBits), mpfr_init2(hi[k], kStageBits);
    mpfr_init2(tmp, kStageBits);
  }
  ~Scratch() {
    for (int k = 0; k < 8; ++k) mpfr_clear(lo[k]), mpfr_clear(hi[k]);
    mpfr_clear(tmp);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};
Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

/// pass / fail / undecided from [lhs] against [rhs] (both non-negative).
FilterVerdict decide_mp(mpfr_srcptr lhs_lo, mpfr_srcptr lhs_hi, mpfr_srcptr rhs_lo, mpfr_srcptr rhs_hi) {
  if (mpfr_lessequal_p(lhs_hi, rhs_lo)) return FilterVerdict::pass;
  if (mpfr_greater_p(lhs_lo, rhs_hi)) return FilterVerdict::fail;
  return FilterVerdict::undecided;
}

/// rhs = k c^2 |w|^2 N, down and up: c from the target's enclosure, |w| in [lo[1], hi[1]],
/// N in [lo[2], hi[2]]; into lo[3], hi[3].
void bound_mp(Scratch& s, const FilterTarget& t, double k) {
  mpfr_set_d(s.lo[3], t.bound.inf(), MPFR_RNDD);
  mpfr_sqr(s.lo[3], s.lo[3], MPFR_RNDD);
  mpfr_mul_d(s.lo[3], s.lo[3], k, MPFR_RNDD);
  mpfr_sqr(s.tmp, s.lo[1], MPFR_RNDD);
  mpfr_mul(s.lo[3], s.lo[3], s.tmp, MPFR_RNDD);
  mpfr_mul(s.lo[3], s.lo[3], s.lo[2], MPFR_RNDD);
  mpfr_set_d(s.hi[3], t.bound.sup(), MPFR_RNDU);
  mpfr_sqr(s.hi[3], s.hi[3], MPFR_RNDU);
  mpfr_mul_d(s.hi[3], s.hi[3], k, MPFR_RNDU);
  mpfr_sqr(s.tmp, s.hi[1], MPFR_RNDU);
  mpfr_mul(s.hi[3], s.hi[3], s.tmp, MPFR_RNDU);
  mpfr_mul(s.hi[3], s.hi[3], s.hi[2], MPFR_RNDU);
}

}  // namespace

IntegerQuadric::IntegerQuadric(const Mat4<Rational>& Q) {
  BigInt D;
  clear_denominators(Q, q, D);
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const BigInt e = q[4 * i + j] + q[4 * j + i];
      spatial4 += e * e;
    }
}

IntegerQuadric::IntegerQuadric(const Mat4<double>& Q)
    : IntegerQuadric(Mat4<Rational>(Q.unaryExpr([](double v) { return Rational(v); }))) {}

IntegerPlane::IntegerPlane(const Vec4<Rational>& p) {
  BigInt D;
  clear_denominators(p, pi, D);
}

IntegerPlane::IntegerPlane(const Vec4<double>& p)
    : IntegerPlane(Vec4<Rational>(p.unaryExpr([](double v) { return Rational(v); }))) {}

ClearedPoints::ClearedPoints(const std::vector<RootPoint>& points) {
  pts_.reserve(points.size());
  for (const RootPoint& x : points) {
    IntegerPoint ip(x);
    Point pt;
    pt.w0 = ip.u(3);
    pt.w1 = ip.v(3);
    pt.P = std::move(ip.P), pt.V = std::move(ip.V);
    pt.Dp = std::move(ip.Dp), pt.Dv = std::move(ip.Dv), pt.d = std::move(ip.d);
    pt.rational = ip.rational;
    pt.square = ip.square;
    pt.ka = pt.Dv * pt.Dv;
    pt.kb = pt.d * pt.Dp * pt.Dp;
    pt.m = 2 * pt.Dp * pt.Dv;
    if (pt.square) {
      const BigInt r = sqrt(pt.d);
      pt.kc = r * pt.m;
      pt.la = pt.Dv;
      pt.lb = r * pt.Dp;
    }
    pts_.push_back(std::move(pt));
  }
}

bool ClearedPoints::on_quadric(std::size_t k, const IntegerQuadric& Q) const {
  const Point& x = pts_[k];
  Scratch& s = scratch();
  auto form = [&](const std::array<BigInt, 4>& u, const std::array<BigInt, 4>& v, BigInt& out) {
    // out = u^T Q v
    for (int i = 0; i < 4; ++i) dot4(mpz(s.y[i]), &Q.q[static_cast<std::size_t>(4 * i)], v);
    mpz_set_ui(mpz(out), 0);
    for (int i = 0; i < 4; ++i) mpz_addmul(mpz(out), mpz(u[static_cast<std::size_t>(i)]), mpz(s.y[i]));
  };
  if (x.rational) {
    form(x.P, x.P, s.a);
    return s.a == 0;
  }
  // c = P^T Q V first: a failing candidate usually shows there
  form(x.P, x.V, s.c);
  if (!x.square && s.c != 0) return false;
  form(x.V, x.V, s.b);
  form(x.P, x.P, s.a);
  mpz_mul(mpz(s.t), mpz(s.a), mpz(x.ka));
  mpz_addmul(mpz(s.t), mpz(s.b), mpz(x.kb));
  if (x.square) mpz_addmul(mpz(s.t), mpz(s.c), mpz(x.kc));
  return s.t == 0;
}

bool ClearedPoints::on_plane(std::size_t k, const IntegerPlane& p) const {
  const Point& x = pts_[k];
  Scratch& s = scratch();
  dot4(mpz(s.a), p.pi.data(), x.P);
  if (x.rational) return s.a == 0;
  dot4(mpz(s.b), p.pi.data(), x.V);
  if (!x.square) return s.a == 0 && s.b == 0;
  mpz_mul(mpz(s.t), mpz(s.a), mpz(x.la));
  mpz_addmul(mpz(s.t), mpz(s.b), mpz(x.lb));
  return s.t == 0;
}

FilterCounts ClearedPoints::check_quadric(const IntegerQuadric& Q) const {
  FilterCounts n;
  for (std::size_t k = 0; k < pts_.size(); ++k) {
    ++n.checked;
    if (!on_quadric(k, Q)) ++n.failed;
  }
  return n;
}

FilterCounts ClearedPoints::check_plane(const IntegerPlane& pi) const {
  FilterCounts n;
  for (std::size_t k = 0; k < pts_.size(); ++k) {
    ++n.checked;
    if (!on_plane(k, pi)) ++n.failed;
  }
  return n;
}

FilterVerdict ClearedPoints::decide_quadric(std::size_t k, const IntegerQuadric& Q, const FilterTarget& t) const {
  if (t.residual_rule) return FilterVerdict::undecided;
  const Point& x = pts_[k];
  Scratch& s = scratch();
  const bool root = !x.rational;
  // y = Q P, zz = Q V; a = P.y, b = V.zz, c = P.zz
  for (int i = 0; i < 4; ++i) dot4(mpz(s.y[i]), &Q.q[static_cast<std::size_t>(4 * i)], x.P);
  mpz_set_ui(mpz(s.a), 0);
  for (int i = 0; i < 4; ++i) mpz_addmul(mpz(s.a), mpz(x.P[static_cast<std::size_t>(i)]), mpz(s.y[i]));
  mpz_mul(mpz(s.f0), mpz(s.a), mpz(x.ka));
  mpz_set_ui(mpz(s.f1), 0);
  if (root) {
    for (int i = 0; i < 4; ++i) dot4(mpz(s.zz[i]), &Q.q[static_cast<std::size_t>(4 * i)], x.V);
    mpz_set_ui(mpz(s.b), 0);
    mpz_set_ui(mpz(s.c), 0);
    for (int i = 0; i < 4; ++i) {
      mpz_addmul(mpz(s.b), mpz(x.V[static_cast<std::size_t>(i)]), mpz(s.zz[i]));
      mpz_addmul(mpz(s.c), mpz(x.P[static_cast<std::size_t>(i)]), mpz(s.zz[i]));
    }
    mpz_addmul(mpz(s.f0), mpz(s.b), mpz(x.kb));
    mpz_mul(mpz(s.f1), mpz(s.c), mpz(x.m));
    s.root.set_radicand(x.d);
  }
  // |f| in [lo0, hi0] (times (Dp Dv)^2), |w| in [lo1, hi1], |g|^2 in [lo2, hi2] (times (Dp Dv)^2)
  s.root.enclose(s.lo[0], s.hi[0], s.f0, s.f1, root);
  s.root.enclose(s.lo[1], s.hi[1], x.w0, x.w1, root);
  mpfr_set_ui(s.lo[2], 0, MPFR_RNDD);
  mpfr_set_ui(s.hi[2], 0, MPFR_RNDU);
  for (int i = 0; i < 3; ++i) {
    mpz_mul(mpz(s.g0), mpz(s.y[i]), mpz(x.Dv));
    if (root) mpz_mul(mpz(s.g1), mpz(s.zz[i]), mpz(x.Dp));
    else mpz_set_ui(mpz(s.g1), 0);
    s.root.add_square(s.lo[2], s.hi[2], s.g0, s.g1, root);
  }
  // f^2 <= 4 (T size)^2 w^2 |g|^2
  mpfr_sqr(s.lo[0], s.lo[0], MPFR_RNDD);
  mpfr_sqr(s.hi[0], s.hi[0], MPFR_RNDU);
  bound_mp(s, t, 4.0);
  const FilterVerdict v = decide_mp(s.lo[0], s.hi[0], s.lo[3], s.hi[3]);
  if (v != FilterVerdict::fail) return v;
  // final where the second order cannot do better (as in stage 1): 4 |g|^2 >= |f| |K|_F, squared,
  // 64 (|g|^2)^2 >= f^2 (4 |K|_F^2), in the integers' common scale
  mpfr_sqr(s.lo[4], s.lo[2], MPFR_RNDD);
  mpfr_mul_ui(s.lo[4], s.lo[4], 64, MPFR_RNDD);
  mpfr_mul_z(s.hi[4], s.hi[0], mpz(Q.spatial4), MPFR_RNDU);
  return mpfr_greaterequal_p(s.lo[4], s.hi[4]) ? FilterVerdict::fail : FilterVerdict::undecided;
}

FilterVerdict ClearedPoints::decide_plane(std::size_t k, const IntegerPlane& p, const FilterTarget& t) const {
  if (t.residual_rule) return FilterVerdict::undecided;
  const Point& x = pts_[k];
  Scratch& s = scratch();
  const bool root = !x.rational;
  // f = pi.x times Dp Dv: (pi.P) Dv + sqrt(d) (pi.V) Dp
  dot4(mpz(s.a), p.pi.data(), x.P);
  mpz_mul(mpz(s.f0), mpz(s.a), mpz(x.Dv));
  mpz_set_ui(mpz(s.f1), 0);
  if (root) {
    dot4(mpz(s.b), p.pi.data(), x.V);
    mpz_mul(mpz(s.f1), mpz(s.b), mpz(x.Dp));
    s.root.set_radicand(x.d);
  }
  s.root.enclose(s.lo[0], s.hi[0], s.f0, s.f1, root);
  s.root.enclose(s.lo[1], s.hi[1], x.w0, x.w1, root);
  // |pi_xyz|^2, exactly as an integer, then rounded outwards
  mpz_set_ui(mpz(s.t), 0);
  for (int i = 0; i < 3; ++i) mpz_addmul(mpz(s.t), mpz(p.pi[static_cast<std::size_t>(i)]), mpz(p.pi[static_cast<std::size_t>(i)]));
  mpfr_set_z(s.lo[2], mpz(s.t), MPFR_RNDD);
  mpfr_set_z(s.hi[2], mpz(s.t), MPFR_RNDU);
  // f^2 <= (T size)^2 w^2 |pi_xyz|^2
  mpfr_sqr(s.lo[0], s.lo[0], MPFR_RNDD);
  mpfr_sqr(s.hi[0], s.hi[0], MPFR_RNDU);
  bound_mp(s, t, 1.0);
  return decide_mp(s.lo[0], s.hi[0], s.lo[3], s.hi[3]);
}

std::size_t ClearedPoints::limb_bytes() const {
  std::size_t b = 0;
  auto add = [&](const BigInt& x) { b += mpz_size(mpz(x)) * sizeof(mp_limb_t); };
  for (const Point& x : pts_) {
    for (const BigInt& v : x.P) add(v);
    for (const BigInt& v : x.V) add(v);
    add(x.ka), add(x.kb), add(x.kc);
  }
  return b;
}

// ----------------------------------------------------------------- the three stages

FilterPoints::FilterPoints(std::vector<RootPoint> points, const Measure& size, double accuracy)
    : exact(std::move(points)), cleared(exact), target(accuracy, size) {
  enclosed.reserve(exact.size());
  for (const RootPoint& x : exact) enclosed.push_back(enclose_point(x));
}

namespace {

template <class Candidate, class Integer, class Filter, class Stage2, class Exact>
FilterCounts check_filtered(const FilterPoints& pts, const Candidate& c, std::vector<char>* passed, Filter filter,
                            Stage2 stage2, Exact exact) {
  FilterCounts n;
  if (passed) passed->assign(pts.exact.size(), 1);
  std::optional<Integer> integer;
  std::optional<Eigen::Matrix<Rational, Candidate::RowsAtCompileTime, Candidate::ColsAtCompileTime>> rational;
  FilterRounding guard;
  for (std::size_t k = 0; k < pts.enclosed.size(); ++k) {
    FilterVerdict v = filter(pts.enclosed[k], c, pts.target);
    if (v == FilterVerdict::undecided) {
      // exact arithmetic at this point, in round-to-nearest (GMP, MPFR)
      FilterRounding nearest(CGAL_FE_TONEAREST);
      ++n.fallbacks;
      if (!integer) integer.emplace(c);
      v = (pts.cleared.*stage2)(k, *integer, pts.target);
      if (v == FilterVerdict::undecided) {
        ++n.measured;
        if (!rational) rational = c.unaryExpr([](double x) { return Rational(x); });
        v = exact(pts.exact[k], *rational, pts.target) ? FilterVerdict::pass : FilterVerdict::fail;
      }
    }
    ++n.checked;
    if (v == FilterVerdict::fail) {
      ++n.failed;
      if (passed) (*passed)[k] = 0;
    }
  }
  return n;
}

}  // namespace

FilterCounts check_quadric_filtered(const FilterPoints& pts, const Mat4<double>& Q, std::vector<char>* passed) {
  if (Q != Mat4<double>(Q.transpose())) {
    // (stages 1 and 2 take Q x for the gradient; the surface's is its symmetric part's, which
    // measure_quadric takes: every point of an asymmetric candidate is decided there)
    FilterCounts n;
    if (passed) passed->assign(pts.exact.size(), 1);
    const Mat4<Rational> R = Q.unaryExpr([](double x) { return Rational(x); });
    for (std::size_t k = 0; k < pts.exact.size(); ++k) {
      ++n.checked, ++n.fallbacks, ++n.measured;
      if (!exact_quadric_passes(pts.exact[k], R, pts.target)) {
        ++n.failed;
        if (passed) (*passed)[k] = 0;
      }
    }
    return n;
  }
  return check_filtered<Mat4<double>, IntegerQuadric>(pts, Q, passed, filter_quadric, &ClearedPoints::decide_quadric,
                                                      exact_quadric_passes);
}

FilterCounts check_plane_filtered(const FilterPoints& pts, const Vec4<double>& pi, std::vector<char>* passed) {
  return check_filtered<Vec4<double>, IntegerPlane>(pts, pi, passed, filter_plane, &ClearedPoints::decide_plane,
                                                    exact_plane_passes);
}

}  // namespace qverify
