#include <qverify/core/predicates.hpp>
#include <qverify/core/quadric.hpp>
#include <qverify/exact/integer_point.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/sampling.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

namespace qverify {
namespace {

using Q = Rational;

struct Draw {
  std::mt19937_64 gen;
  explicit Draw(std::uint64_t seed) : gen(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  Q small() { return Q(std::uniform_int_distribution<int>(-9, 9)(gen)); }
  /// A rational in [-1, 1] in steps of 2^-12.
  Q unit() { return Q(std::uniform_int_distribution<int>(-4096, 4096)(gen), 4096); }
  /// Draws x, then y, then z (sequenced: the order of a call's arguments is
  /// unspecified, and gcc and clang differ, which gave other points per compiler).
  Vec3<Q> vec3() {
    Vec3<Q> v;
    do {
      const Q x = small(), y = small(), z = small();
      v = Vec3<Q>(x, y, z);
    } while (v.isZero());
    return v;
  }
};

/// Lines b + t u through a base point b, met with A, on integers: A is
/// scaled to its primitive integer matrix Ai (a positive multiple: the same quadric), b
/// is B / Db, and each direction u is scaled to its primitive integer vector U (a
/// positive multiple: the same line). Primitive, so that every positive multiple of A or u gives
/// the same points in the same representation (p, q, delta: plane_points steps along q); the
/// rational formulas below are those of Ai and U themselves (DA = Du = 1). With alpha = U^T Ai U, beta = U^T Ai B,
/// c = B^T Ai B (B's part computed once per base point) the line meets A at
///   x = (alpha B - beta U) / (Db alpha) +- sqrt(beta^2 - alpha c) U / (Db alpha),
/// the points of the rational quadratic of the line, with one gcd per
/// coordinate at the end instead of one per rational operation (and p, q,
/// delta the very values RootPoint would make of the rational formulas).
class Lines {
 public:
  Lines(const Mat4<Q>& A, const Vec4<Q>& b) {
    primitive_integers(A, Ai_);
    set_base(b);
  }
  void set_base(const Vec4<Q>& b) {
    b_ = b;
    clear_denominators(b, B_, Db_);
    c_ = 0;
    for (int i = 0; i < 4; ++i) {
      AB_[i] = 0;
      for (int j = 0; j < 4; ++j) AB_[i] += Ai_[static_cast<std::size_t>(4 * i + j)] * B_[static_cast<std::size_t>(j)];
      c_ += B_[static_cast<std::size_t>(i)] * AB_[i];
    }
  }
  const Vec4<Q>& base() const { return b_; }

  /// Adds the points where the line b + t u meets A (u at infinity); false when it misses (or touches) A.
  bool intersect(const Vec4<Q>& u, std::vector<RootPoint>& out, int want) const {
    std::array<BigInt, 4> U;
    primitive_integers(u, U);
    BigInt alpha, beta;
    for (int i = 0; i < 4; ++i) {
      BigInt ui;
      for (int j = 0; j < 4; ++j) ui += Ai_[static_cast<std::size_t>(4 * i + j)] * U[static_cast<std::size_t>(j)];
      alpha += U[static_cast<std::size_t>(i)] * ui;
      beta += U[static_cast<std::size_t>(i)] * AB_[i];
    }
    if (alpha == 0) {  // the one finite root, x = (2 beta B - c U) / (2 beta Db)
      if (beta == 0) return false;
      const BigInt den = 2 * beta * Db_;
      Vec4<Q> x;
      for (std::size_t i = 0; i < 4; ++i) x(static_cast<Eigen::Index>(i)) = Q(BigInt(2 * beta * B_[i] - c_ * U[i]), den);
      out.emplace_back(x, Vec4<Q>::Zero(), Q(0));
      return true;
    }
    const BigInt delta = beta * beta - alpha * c_;
    if (delta <= 0) return false;
    // In the rational terms of the primitive forms (U, Ai): q = U / (U^T Ai U) = U / alpha and
    // delta = delta_int / Db^2. The same p, q and delta as the rational formulas, not merely the
    // same points: plane_points (accuracy.cpp) steps along q. RootPoint keeps sqrt(n / m) (n / m in
    // lowest terms) as sqrt(n m) / m: the radicand n m and q / m are made here on integers, one
    // canonical fraction per coordinate.
    const BigInt den = Db_ * alpha, droot = Db_;
    const Q d(delta, BigInt(droot * droot));
    const BigInt n = numerator(d), m = denominator(d), qden = alpha * m;
    Vec4<Q> p, q;
    for (std::size_t i = 0; i < 4; ++i) {
      p(static_cast<Eigen::Index>(i)) = Q(BigInt(alpha * B_[i] - beta * U[i]), den);
      q(static_cast<Eigen::Index>(i)) = Q(U[i], qden);
    }
    const Q radicand(BigInt(n * m));
    if (static_cast<int>(out.size()) + 1 < want) {
      auto both = RootPoint::conjugates(p, q, radicand);
      out.push_back(std::move(both[0]));
      out.push_back(std::move(both[1]));
    } else {
      out.push_back(RootPoint::with_integer_radicand(p, q, radicand));
    }
    return true;
  }

 private:
  std::array<BigInt, 16> Ai_;
  Vec4<Q> b_;
  std::array<BigInt, 4> B_;
  BigInt Db_, AB_[4], c_;
};

Vec4<Q> finite(const Vec3<Q>& v) { return Vec4<Q>(v(0), v(1), v(2), Q(1)); }

/// A plane's normal as its primitive integer vector (the same for every positive multiple).
Vec3<Q> primitive_normal(const Vec3<Q>& normal) {
  std::array<BigInt, 4> np;
  primitive_integers(Vec4<Q>(normal(0), normal(1), normal(2), Q(0)), np);
  return Vec3<Q>(Q(np[0]), Q(np[1]), Q(np[2]));
}

/// A direction (a line's, either way) as its primitive integer vector with its first non-zero
/// entry positive: the same however it was found (a plane basis pivoted on another entry, a kernel).
Vec3<Q> primitive_direction(const Vec3<Q>& d) {
  Vec3<Q> v = primitive_normal(d);
  for (int i = 0; i < 3; ++i)
    if (v(i) != 0) return v(i) < 0 ? Vec3<Q>(-v) : v;
  return v;
}

Q max_abs(const Vec3<Q>& v) { return std::max({Q(abs(v(0))), Q(abs(v(1))), Q(abs(v(2)))}); }

/// v (non-zero) scaled to L-infinity length `reach`.
Vec3<Q> scaled_to(const Vec3<Q>& v, const Q& reach) { return Vec3<Q>(v * Q(reach / max_abs(v))); }

/// sqrt(r) = x 2^k (r > 0), a function of r alone: r = r' 4^k with r' near 1 (exactly, by the bit
/// lengths of its numerator and denominator), x = sqrt(r') in double, correctly rounded. (Through a
/// double alone a ratio beyond 1e308, a plane's normal of long decimals squared, overflowed; below
/// 1e-308 it underflowed to 0.)
std::pair<double, long> split_sqrt(const Q& r) {
  const long k = (static_cast<long>(msb(numerator(r))) - static_cast<long>(msb(denominator(r)))) / 2;
  return {std::sqrt(Q(r * exact_pow2(-2 * k)).convert_to<double>()), k};  // (r' in [1/4, 4])
}
/// A positive rational within 2^-52 of sqrt(r) (relative): x 2^k of split_sqrt. (With 24 bits, as it
/// was, a cylinder's size, which its stretch's ends make, moved by 1.5e-8 when it was turned: audit
/// 34a F6.)
Q rough_sqrt(const Q& r) {
  const auto [x, k] = split_sqrt(r);
  return Q(x) * exact_pow2(k);
}

/// The axes of a non-singular form G (k x k, exact) in the metric M = diag(m) of an orthogonal basis
/// whose vectors' squared lengths are m (so that a basis of unequal lengths is not taken for an
/// anisotropic form): Y, the eigenvectors of a floating decomposition of S^-1 G S^-1, S = sqrt(M /
/// max m) in double (sd its diagonal), their directions u = S^-1 y taken back exactly (a rational
/// division by each double of sd); rq, their exact Rayleigh quotients u^T G u / u^T M u (exact, so
/// that an axis 10^9 shorter than the others, whose eigenvalue the double decomposition does not
/// resolve, still has its own). nullopt where a decomposition fails or a quotient is 0.
template <int k>
struct FormAxes {
  Eigen::Matrix<double, k, k> Y;
  Eigen::Matrix<double, k, 1> sd;
  std::array<Q, k> rq;
};
template <int k>
std::optional<FormAxes<k>> form_axes(const Eigen::Matrix<Q, k, k>& G, const Eigen::Matrix<Q, k, 1>& m) {
  Q big = 0;
  for (Eigen::Index i = 0; i < G.size(); ++i) big = std::max(big, Q(abs(G(i))));
  if (big == 0) return std::nullopt;
  const Q mmax = m.maxCoeff();
  Eigen::Matrix<double, k, 1> sd;
  for (int i = 0; i < k; ++i) sd(i) = std::sqrt(Q(m(i) / mmax).template convert_to<double>());
  if (!sd.allFinite() || !(sd.minCoeff() > 0)) return std::nullopt;
  Eigen::Matrix<double, k, k> Gd;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) Gd(i, j) = Q(G(i, j) / big).template convert_to<double>() / (sd(i) * sd(j));
  if (!Gd.allFinite()) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, k, k>> eig(Gd);
  if (eig.info() != Eigen::Success) return std::nullopt;
  FormAxes<k> f;
  f.Y = eig.eigenvectors();
  f.sd = sd;
  if (!f.Y.allFinite()) return std::nullopt;
  for (int c = 0; c < k; ++c) {
    Eigen::Matrix<Q, k, 1> u;
    for (int i = 0; i < k; ++i) u(i) = Q(f.Y(i, c)) / Q(sd(i));
    if (u.isZero()) return std::nullopt;
    Q& r = f.rq[static_cast<std::size_t>(c)];
    r = Q(u.dot(Eigen::Matrix<Q, k, 1>(G * u)) / u.dot(Eigen::Matrix<Q, k, 1>(m.cwiseProduct(u))));
    if (r == 0) return std::nullopt;
  }
  return f;
}

/// The smallest |rq| of the axes.
template <int k>
Q least_quotient(const FormAxes<k>& f) {
  Q lo = abs(f.rq[0]);
  for (const Q& r : f.rq) lo = std::min(lo, Q(abs(r)));
  return lo;
}

/// The semi-axes of the form's level set, relative to its longest: column c is u_c / sqrt(|rq_c| /
/// lo), lo the least |rq| (split_sqrt), u_c = S^-1 y_c with y_c's entries rounded to 40 bits of its
/// largest (smaller numbers in every sampled point, and the last bits of the decomposition, which may
/// differ between builds, mostly gone; 40 bits keep a column's error along an axis 10^9 shorter below
/// a thousandth of that axis). Rounded before S^-1, in the metric's own units: rounded after it, to
/// 40 bits of the column's largest coordinate, the coordinate along a basis vector 2^40 times longer
/// than the other (a plane's normal of long decimals) was 0, and the shape lost (audit 34b F1).
/// nullopt if the columns come out dependent.
template <int k>
std::optional<Eigen::Matrix<Q, k, k>> semi_axes(const FormAxes<k>& f) {
  const Q lo = least_quotient(f);
  Eigen::Matrix<Q, k, k> W;
  for (int c = 0; c < k; ++c) {
    // (the ratio's root as x 2^e, split_sqrt: in one double a ratio of 1e-600 underflowed to 0 and
    // the shape was dropped; audit 34a F5)
    const auto [axis, e] = split_sqrt(Q(lo / abs(f.rq[static_cast<std::size_t>(c)])));
    const double top_d = f.Y.col(c).cwiseAbs().maxCoeff() * axis;
    if (!(top_d > 0) || !std::isfinite(top_d)) return std::nullopt;
    const int top = std::ilogb(top_d);
    for (int i = 0; i < k; ++i)
      W(i, c) = Q(std::ldexp(std::round(std::ldexp(f.Y(i, c) * axis, 40 - top)), top - 40)) / Q(f.sd(i)) * exact_pow2(e);
  }
  if (W.determinant() == 0) return std::nullopt;
  return W;
}

/// Directions shaped by a definite form G (k x k, exact; the quadratic part of an ellipsoid, or of
/// an elliptic section in two in-plane coordinates of an orthogonal basis whose squared lengths are m:
/// form_axes; the first form of this, without m, shaped every section of a plane with a long normal
/// and made verify 10% slower): W = semi_axes, so that a line through the centre along W v, v
/// random, meets the ellipse or ellipsoid at about W v / |v|: all over it. Random directions v
/// themselves meet a coin of radius 1 and thickness 2 10^-9 within about 10^-8 of its centre, so the
/// sampled object size was 2.6e-8 and the rim was never checked: a double B of that coin 0.73
/// object sizes off at the rim passed verify (audit 30a F1). nullopt where G is not definite, or its
/// axes are within a factor 16 of each other (random directions sample such a shape well, and a
/// sample stays as it was).
template <int k>
bool elongated(const FormAxes<k>& f) {
  Q hi = 0;
  for (const Q& r : f.rq) {
    if ((r > 0) != (f.rq[0] > 0)) return false;  // (not for a definite G)
    hi = std::max(hi, Q(abs(r)));
  }
  return hi > 256 * least_quotient(f);  // (not: axes within a factor 16)
}
template <int k>
std::optional<Eigen::Matrix<Q, k, k>> shaped_directions(const Eigen::Matrix<Q, k, k>& G, const Eigen::Matrix<Q, k, 1>& m) {
  // (exactly: a parabola's in-plane form is singular, and the Rayleigh quotient of its null vector as
  // a double decomposition gives it is some tiny number of either sign)
  if (*definiteness<Q, k>(G) == 0) return std::nullopt;
  const auto f = form_axes<k>(G, m);
  if (!f || !elongated(*f)) return std::nullopt;
  return semi_axes(*f);
}

/// (16 f)^2 for A without a centre, f = |k_n| / (2 |K|_F) (a parabolic cylinder's focal length; a
/// paraboloid's, its principal ones' at most); K != 0.
Q sixteen_f_squared(const QuadricCore& core, const Mat3<Q>& K) { return 64 * core.kn.squaredNorm() / (K * K).trace(); }

/// A rational point at A's core, to draw lines through: its centre; the point of its axis (plane) of
/// centres nearest `anchor`, or any where none is given (a cylinder: A does not change along its
/// axis); for a paraboloid (K y = -k has no solution) a point inside it on its axis, a focal length or
/// so beyond the vertex. Not the origin: lines drawn from a world origin 10^6 away from a cylinder of
/// radius 1 miss it (no point found, so no check) or meet it 10^6 away along its axis (so an object
/// size of 10^6). Nor the particular solution of K y = -k a factorisation gives: it slides along the
/// axis when the scene moves, and with it the lamp's distance the sampler steps by (a cylinder's
/// sampled object size was 42.9 at the origin, 12.1 moved by 10^6: audit 31a F4).
Vec3<Q> core_point(const Mat4<Q>& A, const QuadricCore& core, const std::optional<Vec3<Q>>& anchor) {
  if (!core.found) return Vec3<Q>::Zero();  // (not expected)
  const Vec3<Q> y = anchor ? core.nearest(*anchor) : core.y;  // (K y + k - k_n = 0 along the kernel)
  if (core.kn.isZero()) return y;
  // no centre (a paraboloid, a parabolic cylinder, a plane): on the line y + s k_n, A = A(y) + 2 s
  // |k_n|^2: the vertex at s = -A(y) / (2 |k_n|^2). Beyond it by t k_n, A = 2 t |k_n|^2: inside (on the
  // side of the quadric's convexity, where sign(A) = -sign(trace K)) for t of the sign of -trace K,
  // |t k_n| about |k_n| / max|K|; a plane (K = 0): off it by k_n, where lines meet it.
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  const Vec3<Q> vertex = core.vertex(A, y);
  Q big = 0;
  for (Eigen::Index i = 0; i < 9; ++i) big = std::max(big, Q(abs(K(i))));
  if (big == 0) return Vec3<Q>(vertex + core.kn);
  const Q side = K.trace() < 0 ? Q(1) : Q(-1);
  return Vec3<Q>(vertex + side / big * core.kn);
}
Vec3<Q> core_point(const Mat4<Q>& A, const std::optional<Vec3<Q>>& anchor) { return core_point(A, quadric_core(A), anchor); }

/// Once the base has stepped off a cone's apex, lines through it meet the cone (or its section, a
/// line pair) as far out as they are close to parallel to a generator: of 64 chords of a cone's
/// terminator the farthest lay about 270 steps out, and the object size with it, which divided every
/// error by as much. Points out[from..] farther than kReachCap steps from the base b (L-infinity,
/// judged on their double approximations: a sampling choice, not a measure) are dropped.
constexpr int kReachCap = 16;
void keep_near(std::vector<RootPoint>& out, std::size_t from, const Vec4<Q>& b, const Q& reach) {
  const double cap = kReachCap * reach.convert_to<double>();
  const Vec3<double> base(b(0).convert_to<double>(), b(1).convert_to<double>(), b(2).convert_to<double>());
  const auto far = [&](const RootPoint& x) { return !((x.approx_cartesian() - base).cwiseAbs().maxCoeff() <= cap); };
  out.erase(std::remove_if(out.begin() + static_cast<std::ptrdiff_t>(from), out.end(), far), out.end());
}



/// The sample's size made its ends' (sample_section, sample_quadric): the first `ends` points are
/// the farthest of the stretch drawn from `from` (the point the size is measured from: A's centre,
/// or the stretch's middle); seeded points farther than they (as far as 80 digits tell) are dropped,
/// so that the ends size the sample at every seed and count, unless more than n are (the farthest
/// point is then inside the stretch: from it a single seeded sample would be all there is). Drawn
/// about another point than the stretch's own middle (a hyperbola on a hyperboloid whose centre is
/// off the section's), or with axes rounded (the far point is flat there), a seeded point may lie a
/// little farther than the ends.
class EndsCap {
 public:
  EndsCap(std::optional<Vec3<Q>> from, int ends) : from_(std::move(from)), ends_(ends) {}
  /// Called once a line's points were added at out[had..].
  void apply(std::vector<RootPoint>& out, std::size_t had, int n) {
    if (!from_ || ends_ <= 0) return;
    if (!reach_) {
      if (static_cast<int>(out.size()) < ends_) return;
      Measure far = 0;
      for (int i = 0; i < ends_; ++i) far = std::max(far, distance2(out[static_cast<std::size_t>(i)]));
      reach_ = far;
      return;
    }
    if (dropped_ > n) return;
    const Measure cap = *reach_ * (1 + Measure("1e-60"));  // (points as far as the ends, to 80 digits, kept)
    const auto beyond = std::remove_if(out.begin() + static_cast<std::ptrdiff_t>(had), out.end(),
                                       [&](const RootPoint& x) { return distance2(x) > cap; });
    dropped_ += static_cast<int>(out.end() - beyond);
    out.erase(beyond, out.end());
  }

 private:
  Measure distance2(const RootPoint& x) const {
    const IntegerPoint ip(x);
    Measure d2 = 0;
    for (int i = 0; i < 3; ++i) {
      const Measure o = ip.offset(i, (*from_)(i));
      d2 += o * o;
    }
    return d2;
  }
  std::optional<Vec3<Q>> from_;
  int ends_;
  std::optional<Measure> reach_;  // the ends' largest squared distance from `from`
  int dropped_ = 0;
};

/// How far along its lines a pair of parallel lines is sampled, in half-widths of the pair.
constexpr int kPairReach = 16;

/// The parameters t of a stretch's chords (ParallelPair; a cylinder's lines, sample_quadric): the
/// two ends first (t = +-kPairReach, the farthest points), then seeded ones within.
struct Stretch {
  int ends = 2;
  int inner = kPairReach;  // the seeded ones' reach
  Q next(Draw& draw) { return ends > 0 ? Q(ends-- == 2 ? kPairReach : -kPairReach) : Q(inner * draw.unit()); }
};

/// A section that is a pair of real parallel lines (a cylinder's terminator under a point or a
/// parallel light, a pair of parallel planes cut): where its chords are drawn, and which way. Chords
/// through a point of the lines' midline m in the directions e + t a (e across the lines in the
/// plane, a along them, scaled by a rational within 2^-52 of |e| / |a|) all meet the lines at the
/// same distance s from it across (a is the section's singular point at infinity: A a is orthogonal
/// to the plane, so (e + t a)^T A (e + t a) = e^T A e and (e + t a)^T A m = e^T A m = 0), at
/// m +- s (e + t a), |t| <= kPairReach: the points within kPairReach half-widths of m along the lines
/// (the same whatever the seed: the first two chords are t = +-kPairReach, the farthest points).
/// Random directions met the lines as far out as they were near parallel to them: a cylinder whose
/// axis was 10^-9 from level was sized 3e8 (a chord along a coordinate axis), its double results'
/// bounds over a ball of that size (1.3e-9 to 0.13) failed verify against 10^-25 sampled; and a
/// cylinder's size was 52.3 at one seed and 14.8 at another.
struct ParallelPair {
  Vec4<Q> mid;
  Vec3<Q> across, along;
};
std::optional<ParallelPair> parallel_pair(const Mat4<Q>& A, const Eigen::Matrix<Q, 4, 3>& E, const Mat3<Q>& K,
                                          const Vec3<Q>& normal, const Vec4<Q>& base) {
  if (K.determinant() != 0) return std::nullopt;
  const Mat3<Q> adj = adjugate3<Q>(K);  // l1 l2 z z^T, z the singular point: real lines where l1 l2 < 0
  if (adj.isZero() || !(adj.trace() < 0)) return std::nullopt;
  Vec4<Q> z = Vec4<Q>::Zero();
  for (int j = 0; j < 3 && z.isZero(); ++j) z = E * Eigen::Matrix<Q, 3, 1>(adj.col(j));
  if (z(3) != 0) return std::nullopt;  // (lines crossing at a finite point)
  const Vec3<Q> a = primitive_direction(z.head<3>());
  const Vec3<Q> e = normal.cross(a);
  const Vec4<Q> e4(e(0), e(1), e(2), Q(0));
  const Q alpha = e4.dot(A * e4);  // 0 where one of the lines is the line at infinity (z = xy cut by x = c)
  if (alpha == 0) return std::nullopt;
  ParallelPair pair;
  pair.mid = base - e4.dot(A * base) / alpha * e4;  // the middle of the chord through the base along e
  pair.across = e;
  pair.along = Vec3<Q>(a * rough_sqrt(Q(e.squaredNorm() / a.squaredNorm())));
  return pair;
}

/// How far along a hyperbola its chords reach (a hyperbolic cylinder's cross-section, a terminator
/// on a hyperboloid): directions W_0 + s W_1 through its centre (W_0 the real semi-axis, W_1 the
/// other, made exactly conjugate with the asymptotes at s = +-1 to 2^-52: conic_axes),
/// |s| <= s_end (ConicAxes::end), s_end = 63/65, where the hyperbola is 65/16 (about 4) times
/// as far from the centre as W_0 + s W_1 in its own semi-axes; but at most 16 |W_0| / |W_1|, about
/// 16 real semi-axes out, where the other is longer: a hyperboloid near a cylinder (x^2 + y^2 -
/// 10^-24 z^2 = 1, its terminator two near-parallel branches 1e12 semi-axes long out to s = 63/65)
/// is sampled as the cylinder is, within 16 half-widths, not 3.7e12 (audit 34b F6). Seeded chords
/// |s| <= s_end 15/16, short of the ends.
const Q kHyperbolaEnd(63, 65);

/// A rounded axis x of the form G in the metric diag(m) (an eigenvector of G relative to it: semi_axes)
/// refined by one step of Rayleigh quotient iteration, exactly: (G - rho M)^-1 M x with rho = x^T G x /
/// x^T M x, by the adjugate (the same direction), its error cubed (squared and more in a metric); x
/// itself where the step gives 0. (k = 2: a conic's axes in its plane, conic_axes; k = 3: a quadric's,
/// refined_axis.)
template <int k>
Eigen::Matrix<Q, k, 1> rayleigh_step(const Eigen::Matrix<Q, k, k>& G, const Eigen::Matrix<Q, k, 1>& m,
                                     const Eigen::Matrix<Q, k, 1>& x) {
  static_assert(k == 2 || k == 3, "a conic's or a quadric's axes");
  using V = Eigen::Matrix<Q, k, 1>;
  using M = Eigen::Matrix<Q, k, k>;
  const V mx = m.cwiseProduct(x);
  const Q rho = x.dot(V(G * x)) / x.dot(mx);
  const M S = G - rho * M(m.asDiagonal());
  V y;
  if constexpr (k == 2) y = V(S(1, 1) * mx(0) - S(0, 1) * mx(1), -S(1, 0) * mx(0) + S(0, 0) * mx(1));
  else y = adjugate3<Q>(S) * mx;
  return y.isZero() ? x : y;
}

/// A direction y divided by its largest entry in the metric diag(m)'s units (m >= 1, each entry's unit
/// 2^h, h = floor(log2 m) / 2, within 2 of sqrt(m); m = 1: plain entries), which becomes 1, and
/// the others rounded towards 0 to 2^-bits of it: the same direction rounded alike whatever its scale
/// (A's, which moves with the scene as A is made canonical), and its numbers short.
template <int k> Eigen::Matrix<Q, k, 1> rounded_direction(const Eigen::Matrix<Q, k, 1>& y, const Eigen::Matrix<Q, k, 1>& m, long bits) {
  long h[k];
  for (int i = 0; i < k; ++i) h[i] = floor_log2(m(i)) / 2;
  int j = 0;
  for (int i = 1; i < k; ++i)
    if (abs(y(i)) * exact_pow2(h[i]) > abs(y(j)) * exact_pow2(h[j])) j = i;
  Eigen::Matrix<Q, k, 1> r;
  for (int i = 0; i < k; ++i) {
    if (i == j) {
      r(i) = 1;
      continue;
    }
    const Q ulp = exact_pow2(h[j] - h[i] - bits), t = y(i) / y(j) / ulp;
    r(i) = Q(Rational(numerator(t) / denominator(t)) * ulp);
  }
  return r;
}

/// The semi-axes of a central conic through whose centre b lines are drawn in a plane spanned by
/// `plane` (two orthogonal vectors; a line b + lambda r, r = plane v, meets it where lambda^2
/// r^T K r = -c, c = A(b), K = A_xyz,xyz: b is the conic's centre, so r^T (A b) = 0): `across`
/// holds them (semi_axes of plane^T K plane in the plane's metric), the longest first for an
/// ellipse; for a hyperbola the real one first, the pair made exact conjugate semi-diameters (below).
/// nullopt where c = 0 (lines crossing at b), the form is singular, or no direction is real.
struct ConicAxes {
  Eigen::Matrix<Q, 3, 2> across;
  bool hyperbolic = false;
  Q end{kHyperbolaEnd};  ///< a hyperbola's s_end (kHyperbolaEnd)
  Q inner(Draw& draw) const { return Q(end * 15 / 16 * draw.unit()); }
};
std::optional<ConicAxes> conic_axes(const Mat4<Q>& A, const Eigen::Matrix<Q, 3, 2>& plane, const Q& c) {
  if (c == 0) return std::nullopt;
  const Eigen::Matrix<Q, 2, 2> G = plane.transpose() * Mat3<Q>(A.topLeftCorner<3, 3>()) * plane;
  const Q det = G.determinant();
  if (det == 0) return std::nullopt;
  const Eigen::Matrix<Q, 2, 1> m(plane.col(0).squaredNorm(), plane.col(1).squaredNorm());  // (the metric)
  const auto f = form_axes<2>(G, m);
  if (!f) return std::nullopt;
  const auto W = semi_axes(*f);
  if (!W) return std::nullopt;
  ConicAxes out;
  out.hyperbolic = det < 0;
  if (out.hyperbolic) {
    // Exact conjugate semi-diameters U (real) and V: U the real axis, refined, and V = perp(G U), so
    // that (U + s V)^T G (U + s V) = U^T G U + s^2 V^T G V exactly, V scaled by a rational within
    // 2^-52 of sqrt(-U^T G U / V^T G V): the asymptotes at s = +-1 to 2^-52 whatever the shape. (With
    // the rounded axes themselves, the real axis's rounding along the other, 2^-52 of a semi-axis
    // 10^15 times the other's, moved the asymptotes in s by as much as the other itself: a lamp
    // 10^-30 off a hyperboloid's asymptotic cone was sized 4e29 to 7.6e30 by seed, and a polar plane
    // 2 targets off passed at one seed; audit 35a F1.) The pair's quotients have opposite signs
    // (their product is det G |u v|^2 < 0): V is the imaginary one.
    using V2 = Eigen::Matrix<Q, 2, 1>;
    const auto form = [&](const V2& a, const V2& b) { return Q(a.dot(V2(G * b))); };
    // U: a rounded axis refined by a step of Rayleigh quotient iteration (rayleigh_step), then rounded
    // in the metric's units to 64 bits plus the axes' ratio's (rounded_direction): the pair is the
    // axes themselves to far below that ratio, so the stretch is the same however the scene is turned
    // (the double decomposition's last bits are the turn's), and its points' numbers stay short (kept
    // exact, the refined axes made exact proofs of a sample 7 times slower)
    const long bits = 64 + std::abs(floor_log2(Q(abs(f->rq[0]))) - floor_log2(Q(abs(f->rq[1])))) / 2;
    V2 u = rayleigh_step<2>(G, m, V2(W->col(0)));
    if ((form(u, u) > 0) == (c > 0)) u = rayleigh_step<2>(G, m, V2(W->col(1)));  // (u real: its form's sign not c's)
    u = rounded_direction<2>(u, m, bits);
    const Q qu = form(u, u);
    if (qu == 0 || (qu > 0) == (c > 0)) return std::nullopt;
    const V2 gu = G * u;
    V2 v(-gu(1), gu(0));  // (divided by an entry: the same whatever A's scale, as u)
    v /= Q(v(0) != 0 ? v(0) : v(1));
    const Q qv = form(v, v);
    if (qv == 0 || (qv > 0) != (c > 0)) return std::nullopt;
    v *= rough_sqrt(Q(-qu / qv));
    out.across.col(0) = plane * u;
    out.across.col(1) = plane * v;
    out.end = std::min(kHyperbolaEnd, Q(16 * rough_sqrt(Q(out.across.col(0).squaredNorm() / out.across.col(1).squaredNorm()))));
    return out;
  }
  // an ellipse: real where G's sign is the opposite of c's; the longer semi-axis (the least |rq|) first
  if ((f->rq[0] > 0) == (c > 0) || (f->rq[1] > 0) == (c > 0)) return std::nullopt;
  const int first = abs(f->rq[0]) <= abs(f->rq[1]) ? 0 : 1;
  out.across.col(0) = plane * Eigen::Matrix<Q, 2, 1>(W->col(first));
  out.across.col(1) = plane * Eigen::Matrix<Q, 2, 1>(W->col(1 - first));
  return out;
}

/// Two orthogonal vectors across n (not 0): n x e_j (the first not 0), n x (n x e_j); a function of
/// n alone, so the same for every scene that has it.
Eigen::Matrix<Q, 3, 2> plane_across(const Vec3<Q>& n) {
  Eigen::Matrix<Q, 3, 2> plane;
  for (int j = 0; j < 3; ++j) {
    plane.col(0) = n.cross(Vec3<Q>::Unit(j));
    if (!plane.col(0).isZero()) break;
  }
  plane.col(1) = n.cross(Vec3<Q>(plane.col(0)));
  return plane;
}

/// A section that is a parabola (a paraboloid's terminator under a parallel light): chords across
/// its axis, at distances 0 < X <= 16 f from its vertex along the axis (f its focal length), the
/// first at 16 f (its points, 8 f either side, the farthest from the middle of that stretch of axis;
/// the others at most 15 f out, nearer). In the plane's coordinates x = b + u v + s w (v the in-plane
/// form's kernel, along the axis, w = n x v across it; exactly: v^T K w = 0 = v^T K v) A is
/// c0 + 2 beta u + 2 gamma s + lambda s^2, vertex at s_v = -gamma / lambda, u_v = (gamma^2 / lambda
/// - c0) / (2 beta); about it lambda s'^2 = -2 beta u', Y^2 = 4 f X with X = u' |v|, Y = s' |w|, so
/// 16 f is u' = -8 beta |w|^2 / (lambda |v|^2): rational, a function of A and the plane alone.
/// Random chords through a point inside met it as far out as they were near its axis, and its
/// size (from the sample's centroid) was the seed's. nullopt where the section is no parabola.
struct ParabolaChords {
  Vec4<Q> vertex;
  Vec3<Q> along, across;
  Q end;    ///< the farthest chord's u'
  Q kappa;  ///< the parabola u' = kappa s'^2 (kappa = -lambda / (2 beta)): its rational points, by s'
  Vec4<Q> at(const Q& u) const { return Vec4<Q>(vertex + u * Vec4<Q>(along(0), along(1), along(2), Q(0))); }
  /// Its point at s' (rational for a rational s').
  Vec4<Q> point(const Q& s) const {
    const Vec3<Q> x = Vec3<Q>(kappa * s * s * along + s * across);
    return Vec4<Q>(at(Q(0)) + Vec4<Q>(x(0), x(1), x(2), Q(0)));
  }
};
std::optional<ParabolaChords> parabola_chords(const Mat4<Q>& A, const Eigen::Matrix<Q, 3, 2>& plane, const Vec3<Q>& n,
                                              const Vec4<Q>& b) {
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  const Eigen::Matrix<Q, 2, 2> G = plane.transpose() * K * plane;
  if (G.determinant() != 0 || G.isZero()) return std::nullopt;
  Eigen::Matrix<Q, 2, 1> v2(-G(0, 1), G(0, 0));  // G's kernel (G of rank 1)
  if (v2.isZero()) v2 = Eigen::Matrix<Q, 2, 1>(-G(1, 1), G(0, 1));
  ParabolaChords out;
  out.along = primitive_direction(Vec3<Q>(plane * v2));
  out.across = n.cross(out.along);
  const Vec4<Q> v4(out.along(0), out.along(1), out.along(2), Q(0)), w4(out.across(0), out.across(1), out.across(2), Q(0));
  const Vec4<Q> Ab = A * b;
  const Q lambda = w4.dot(A * w4), beta = v4.dot(Ab) / b(3), gamma = w4.dot(Ab) / b(3), c0 = b.dot(Ab) / (b(3) * b(3));
  if (lambda == 0 || beta == 0) return std::nullopt;  // (a line pair, or lines)
  const Q sv = -gamma / lambda, uv = (gamma * gamma / lambda - c0) / (2 * beta);
  out.vertex = Vec4<Q>(b / b(3) + uv * v4 + sv * w4);
  out.end = -8 * beta * out.across.squaredNorm() / (lambda * out.along.squaredNorm());
  out.kappa = -lambda / (2 * beta);
  return out;
}

/// The point of a parabola's stretch (the chords' 0 < u' <= end, so s'^2 <= end / kappa) farthest
/// from c, where it lies inside the stretch rather than on its end chord: a parabola on a hyperboloid
/// (a lamp on its asymptotic cone), measured from A's centre, may be farthest at its vertex or
/// between it and the end chord. With e = vertex - c, v = along, w = across (v . w = 0), the squared
/// distance D(s) = |e + kappa s^2 v + s w|^2 is a quartic with D'(s) / 2 = a3 s^3 + a1 s + a0,
/// a3 = 2 kappa^2 |v|^2 > 0, a1 = 2 kappa e.v + |w|^2, a0 = e.w. D has an interior maximum iff that
/// cubic has three distinct real roots, 4 a1^3 + 27 a3 a0^2 < 0 (decided exactly), and it is the
/// middle root, 2 sqrt(-p/3) cos(theta/3 - 2 pi/3) with p = a1/a3, q = a0/a3,
/// cos theta = (3q / 2p) sqrt(-3/p) (to 80 digits), taken to a rational within 2^-52 of it: its
/// point is a rational point of the parabola, as far from c as the maximum to about 2^-104 (D is flat
/// there). nullopt where there is no interior maximum, or it lies beyond the end chord.
std::optional<Vec4<Q>> parabola_far_point(const ParabolaChords& p, const Vec3<Q>& c) {
  const Vec3<Q> e = Vec3<Q>(p.vertex.head<3>() / p.vertex(3) - c);
  const Q a3 = 2 * p.kappa * p.kappa * p.along.squaredNorm();
  const Q a1 = 2 * p.kappa * e.dot(p.along) + p.across.squaredNorm(), a0 = e.dot(p.across);
  if (!(4 * a1 * a1 * a1 + 27 * a3 * a0 * a0 < 0)) return std::nullopt;  // (then a1 < 0)
  const Measure pm = to_measure(Q(a1 / a3)), qm = to_measure(Q(a0 / a3));
  using boost::multiprecision::acos, boost::multiprecision::cos, boost::multiprecision::sqrt;
  const Measure cos_theta = std::clamp(Measure(3 * qm / (2 * pm) * sqrt(Measure(-3 / pm))), Measure(-1), Measure(1));
  const Measure third = acos(Measure(-1)) * 2 / 3;  // (2 pi / 3)
  const Measure middle = 2 * sqrt(Measure(-pm / 3)) * cos(Measure(acos(cos_theta) / 3 - third));
  Q s = 0;
  if (middle != 0) {
    int k = 0;
    const Measure f = frexp(middle, &k);  // (f in [1/2, 1): to 53 bits, whatever the scale)
    s = Q(f.convert_to<double>()) * exact_pow2(k);
  }
  if (!(s * s < p.end / p.kappa)) return std::nullopt;
  return p.point(s);
}

/// A section that is one finite line (A's quadratic part vanishes on the plane, its linear part
/// does not: a parabolic cylinder's terminator under a parallel light, a generator along which A does
/// not change): on the plane A(b + y) = A(b) + 2 y . q, q the in-plane part of (A b)_xyz, so the line
/// is m + t d, m = b - A(b) / (2 |q|^2) q (the point nearest b), d = n x q (primitive): rational
/// points, taken as they are, with |t d| <= 16 f, f = |q| / (2 |K|_F) (a parabolic cylinder's focal
/// length: q is k_n there and |K|_F = |lambda| |g|^2), through a rational within 2^-52 of f / |d|.
/// The ends t = +-t_max first (the farthest from m, and from any point, of the points between
/// them), then seeded ones within 15/16 of them. Random chords through a point beside it met it as far out as they were near
/// parallel to it: sized 0.3 to 112 by seed and count (audit 33a F4). nullopt where A's quadratic
/// part does not vanish on the plane, or K = 0 (no length: a plane).
struct SingleLine {
  Vec4<Q> m;
  Vec3<Q> d;
  Q reach;  ///< t_max
};
std::optional<SingleLine> single_line(const Mat4<Q>& A, const Eigen::Matrix<Q, 3, 2>& plane, const Vec3<Q>& n,
                                      const Vec4<Q>& b) {
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  if (K.isZero() || !Eigen::Matrix<Q, 2, 2>(plane.transpose() * K * plane).isZero()) return std::nullopt;
  const Vec4<Q> base = b / b(3);
  const Vec4<Q> Ab = A * base;
  const Vec3<Q> g = Ab.head<3>();
  const Vec3<Q> q = g - g.dot(n) / n.squaredNorm() * n;
  if (q.isZero()) return std::nullopt;  // (the whole plane, or none of it)
  SingleLine out;
  out.m = base - base.dot(Ab) / (2 * q.squaredNorm()) * Vec4<Q>(q(0), q(1), q(2), Q(0));
  out.d = primitive_direction(Vec3<Q>(n.cross(q)));
  out.reach = kPairReach * rough_sqrt(Q(q.squaredNorm() / (4 * (K * K).trace() * out.d.squaredNorm())));
  return out;
}

/// Where a cylinder's lines are drawn (sample_quadric): directions r + t sigma a through its axis
/// point b, a the axis (primitive), r across it, sigma a rational within 2^-52 of |r| / |a|. b is a
/// centre and a K's kernel, so the line's quadratic is r's and it meets the cylinder at b +-
/// lambda (r + t sigma a): at the cross-section's radius in r's direction, sqrt(1 + t^2) times as
/// far out. r is shaped by the cross-section (conic_axes, in the plane across the axis). The first
/// two lines are the farthest: r = across_0 (an ellipse's long semi-axis; a hyperbola's across_0 +
/// ConicAxes::end across_1) and t = +-kPairReach (r is exactly across a: the same distance); the
/// seeded ones stay short of them (an ellipse's r = across v, v random; a hyperbola's
/// ConicAxes::inner; |t| <= kPairReach - 1), so the sample's size, its largest distance from b, is
/// the ends' at every seed and count and scales with the scene. Random directions across the axis
/// met an elliptic cylinder anywhere between its semi-axes (and a hyperbolic one unboundedly far
/// out): one with semi-axes 1 and 100 was sized 28.9 to 1603 by the seed and the count, and a
/// reflection 9 times the target off at the long axis's ends passed where the sample's ball did not
/// reach them (audit 33a F3); a circular one's size moved by 2e-8 with the seed (sigma of a random
/// r; F7). nullopt (random directions across the axis) where conic_axes has none: A's value at its
/// axis is 0 (a pair of planes crossing at the axis, or the axis alone), or it has no real points.
std::optional<ConicAxes> cylinder_chords(const Mat4<Q>& A, const Vec3<Q>& axis, const Vec3<Q>& centre) {
  return conic_axes(A, plane_across(axis), quadric_value(A, centre));
}

/// An axis w of K (a rounded eigenvector: semi_axes) refined by a step of Rayleigh quotient iteration
/// (rayleigh_step: adj(K - rho I) w, rho = w^T K w / |w|^2, its error cubed; w itself where the step
/// gives 0), then divided by its largest entry and rounded to 2^-64 (rounded_direction): a stretch
/// cut across it reaches its far points to first order in the axis's error (D = |x - o|^2 is not
/// stationary along the axis), and with semi_axes's 40 bits a hyperboloid turned was sized 2e-13
/// apart (the double decomposition's last bits are the turn's).
Vec3<Q> refined_axis(const Mat3<Q>& K, const Vec3<Q>& w) {
  const Vec3<Q> one = Vec3<Q>::Ones();  // (the Euclidean metric)
  return primitive_direction(rounded_direction<3>(rayleigh_step<3>(K, one, w), one, 64));
}

/// An unbounded quadric with an axis drawn as its sections across it (sample_quadric): a hyperboloid,
/// a cone, an elliptic or a hyperbolic paraboloid. The planes through o + h w (h rational, |h| <= H;
/// 0 < h <= H for an elliptic paraboloid) with normal n cut A in conics centred at o + h w: for a
/// central A (o its centre, K o = -k), n is its axis of the odd sign (a rounded eigenvector of K,
/// semi_axes, refined: refined_axis) and w = adj(K) n, its conjugate diameter, so A's gradient there,
/// h K w = h det(K) n, is along n; for a paraboloid (o its vertex, w its axis, K's kernel), n = w, and
/// the gradient is k_n, along w. So a line through o + h w across n meets A at o + h w +- lambda r,
/// lambda^2 r^T K r = -A(o + h w): the section's shape (conic_axes) at one h serves every h where
/// A(o + h w) has the same sign, scaled. The stretch and its ends, the farthest of its points from `middle` (the point the size is
/// measured from: o, or the middle o + H/2 w of an elliptic paraboloid's stretch of axis), drawn
/// first: the sections at h = +-H along their longest semi-axis (an ellipse's), at their hyperbola's
/// ends s = +-ConicAxes::end (a hyperbolic paraboloid's, whose sections at -H and H are hyperbolas
/// with their axes swapped); the farthest since a section grows with |h| (from the middle of an
/// elliptic paraboloid's stretch, r(h)^2 + (h - H/2)^2 |w|^2 is convex in h and largest at H). H:
/// - a hyperboloid of one sheet: where its section is 4 times its waist (H^2 = 15 A(o) / q_w, q_w =
///   w^T K w), but at most 16 waist semi-axes out (one near a cylinder is sampled as the cylinder);
/// - of two sheets: 4 times its vertex's h (H^2 = -16 A(o) / q_w);
/// - a cone, which has no length of its own: its far points 16 `reach` from its apex;
/// - a paraboloid: 16 f, f = |k_n| / (2 |K|_F) (a parabolic cylinder's focal length: single_line).
/// Random lines through its centre (its vertex's inside) met it as far out as they were near its
/// asymptotic cone (its axis), and a cone's from its apex stepped off at random: sizes were the
/// seed's, 4.8 to 82 for a hyperbolic paraboloid at 64 samples, and a reflection moved by 2e-9 failed
/// at two seeds of four (audit 35a F2). nullopt where A is none of these (or its axes are not found).
struct AxialSections {
  Vec3<Q> origin, axis, middle;
  Eigen::Matrix<Q, 3, 2> plane;
  Q H;
  bool one_sided = false;
  Q sign_at_H;                   ///< A(o + H w)'s sign
  ConicAxes at_H;                ///< the sections' axes where A(o + h w) has that sign
  std::optional<ConicAxes> other;  ///< and where it has the other (a hyperbolic paraboloid's h < 0)
  Q value(const Q& h, const Mat4<Q>& A) const { return quadric_value(A, Vec3<Q>(origin + h * axis)); }
  Vec4<Q> base(const Q& h) const { return finite(Vec3<Q>(origin + h * axis)); }
};
std::optional<AxialSections> axial_sections(const Mat4<Q>& A, const QuadricCore& core, const Q& reach,
                                            const std::optional<Vec3<Q>>& anchor) {
  if (!core.found) return std::nullopt;
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  AxialSections out;
  const auto conic = [&](const Q& h) { return conic_axes(A, out.plane, out.value(h, A)); };
  if (core.kernel.cols() == 0) {  // central: a hyperboloid or a cone
    const auto f = form_axes<3>(K, Vec3<Q>(1, 1, 1));
    if (!f) return std::nullopt;
    int odd = -1;
    for (int j = 0; j < 3; ++j) {
      const int same = ((f->rq[0] > 0) == (f->rq[j] > 0)) + ((f->rq[1] > 0) == (f->rq[j] > 0)) + ((f->rq[2] > 0) == (f->rq[j] > 0));
      if (same == 1) odd = j;
    }
    if (odd < 0) return std::nullopt;  // (K definite: an ellipsoid, or a point)
    const auto W = semi_axes(*f);
    if (!W) return std::nullopt;
    out.origin = core.y;
    // the planes across the refined axis n itself, their centres along its conjugate diameter u =
    // adj(K) n (K u = det K n, along the normal): cut across K w instead, w's rounding across the
    // axis, times K's largest eigenvalue over the odd one, tilted them (x^2 + y^2 - 1e-24 z^2 = 1
    // turned: a waist 1.5e4 where it is 1; review of bcb247a)
    const Vec3<Q> n = refined_axis(K, Vec3<Q>(W->col(odd)));
    out.axis = primitive_direction(Vec3<Q>(adjugate3<Q>(K) * n));
    out.middle = out.origin;
    const Q qw = out.axis.dot(K * out.axis), a0 = quadric_value(A, out.origin);
    if (qw == 0) return std::nullopt;
    out.plane = plane_across(n);
    const Q w2 = out.axis.squaredNorm();
    if (a0 == 0) {  // a cone: its section at h = 1, and H so that its far points are 16 reach out
      const auto one = conic(Q(1));
      if (!one) return std::nullopt;
      const Vec3<Q> r = one->across.col(0);
      const Q a1 = Q(-qw / r.dot(K * r) * r.squaredNorm());  // (its long semi-axis squared, at h = 1)
      out.H = Q(kReachCap * reach / rough_sqrt(Q(w2 + a1)));
    } else if ((a0 > 0) == (qw > 0)) {  // one sheet
      const auto waist = conic(Q(0));
      if (!waist) return std::nullopt;
      const Vec3<Q> r = waist->across.col(0);
      const Q a2 = Q(-a0 / r.dot(K * r) * r.squaredNorm());  // (its long waist semi-axis squared)
      out.H = std::min(rough_sqrt(Q(15 * a0 / qw)), rough_sqrt(Q(256 * a2 / w2)));
    } else {  // two sheets
      out.H = rough_sqrt(Q(-16 * a0 / qw));
    }
  } else if (core.kernel.cols() == 1 && !core.kn.isZero()) {  // a paraboloid, elliptic or hyperbolic
    const Vec3<Q> y = anchor ? core.nearest(*anchor) : core.y;
    out.origin = core.vertex(A, y);
    out.axis = primitive_direction(Vec3<Q>(core.kernel.col(0)));
    out.plane = plane_across(out.axis);
    const Eigen::Matrix<Q, 2, 2> G = out.plane.transpose() * K * out.plane;
    if (G.determinant() == 0) return std::nullopt;  // (K of rank 2 here: |K|_F > 0)
    out.H = rough_sqrt(Q(sixteen_f_squared(core, K) / out.axis.squaredNorm()));
    out.one_sided = G.determinant() > 0;
    // (an elliptic one opens towards h > 0: A(o + h w) = 2 h w . k_n of the sign opposite to G's)
    if (out.one_sided && (out.axis.dot(core.kn) > 0) == (G(0, 0) > 0)) out.axis = -out.axis;
    out.middle = out.one_sided ? Vec3<Q>(out.origin + out.H / 2 * out.axis) : out.origin;
  } else {
    return std::nullopt;
  }
  const auto at_H = conic(out.H);
  if (!at_H) return std::nullopt;
  out.at_H = *at_H;
  out.sign_at_H = out.value(out.H, A) > 0 ? Q(1) : Q(-1);
  if (!out.one_sided && (out.value(-out.H, A) > 0) != (out.sign_at_H > 0)) {
    out.other = conic(Q(-out.H));
    if (!out.other) return std::nullopt;
  }
  return out;
}

/// Up to n points of A drawn as its axial sections (AxialSections): the ends first (rep.ends of
/// them: 2 per ellipse, 4 per hyperbola, at h = H and, two-sided, at -H), then chords of seeded
/// sections |h| <= 15/16 H (shaped by their ellipse's axes, or within a hyperbola's ConicAxes::inner),
/// seeded points farther from the middle than the ends dropped (EndsCap).
SampleReport sample_axial(const Mat4<Q>& A, const AxialSections& s, int n, Draw& draw) {
  SampleReport rep;
  rep.middle = s.middle;
  Lines lines(A, s.base(s.H));
  const auto axes_at = [&](const Q& h) -> const ConicAxes& {
    return s.other && (s.value(h, A) > 0) != (s.sign_at_H > 0) ? *s.other : s.at_H;
  };
  const auto line = [&](const Q& h, const Vec3<Q>& d) {
    ++rep.attempts;
    lines.set_base(s.base(h));
    lines.intersect(Vec4<Q>(d(0), d(1), d(2), Q(0)), rep.points, n);
  };
  for (const Q& h : {s.H, Q(-s.H)}) {
    if (h < 0 && s.one_sided) break;
    const ConicAxes& c = axes_at(h);
    rep.ends += c.hyperbolic ? 4 : 2;
    if (c.hyperbolic) {
      for (const Q& t : {c.end, Q(-c.end)})
        if (static_cast<int>(rep.points.size()) < n) line(h, Vec3<Q>(c.across.col(0) + t * c.across.col(1)));
    } else if (static_cast<int>(rep.points.size()) < n) {
      line(h, c.across.col(0));
    }
  }
  EndsCap cap(s.middle, rep.ends);
  cap.apply(rep.points, rep.points.size(), n);
  const long long max_attempts = 50LL * n + 50;
  while (static_cast<int>(rep.points.size()) < n && rep.attempts < max_attempts) {
    Q h;
    do h = Q(s.H * 15 / 16 * (s.one_sided ? Q(abs(draw.unit())) : draw.unit())); while (h == 0);
    const ConicAxes& c = axes_at(h);
    Vec3<Q> d;
    if (c.hyperbolic) {
      d = c.across.col(0) + c.inner(draw) * c.across.col(1);
    } else {
      Vec3<Q> v = draw.vec3();
      while (v(0) == 0 && v(1) == 0) v = draw.vec3();
      d = c.across * Eigen::Matrix<Q, 2, 1>(v(0), v(1));
    }
    const std::size_t had = rep.points.size();
    line(h, d);
    cap.apply(rep.points, had, n);
  }
  rep.exhausted = static_cast<int>(rep.points.size()) < n;
  return rep;
}

/// A quadric whose sections along an axis are pairs of parallel lines, or which is one or two
/// parallel planes, drawn along lines in one direction r (across the lines, exactly) through the
/// bases o + h w + t_1 g_1 + t_2 g_2 (g along the lines, |t_i| <= T_i; |h| <= H, or 0 < h <= H): A
/// does not change along g, so each line meets A at the section's lines' distance across, and the
/// stretch's ends, drawn first, are its corners (|h| = H, |t_i| = T_i), the farthest of its points
/// from `middle`:
/// - a parabolic cylinder: w its axis (K's kernel along k_n), g its generators (the kernel across
///   k_n), o its vertex line's point nearest the anchor; 0 < h <= H = 16 f (AxialSections's f), T_1
///   as long (single_line's 16 f);
/// - a pair of planes crossing at a line of centres: g that line, r an axis of its cross-section's
///   line pair (form_axes: the larger quotient's, refined_axis), w = g x K r; H and T_1 so that its far points lie 16
///   `reach` out across and along (it has no length of its own, as a cone);
/// - two parallel planes (a plane of centres): g_1, g_2 along them, h = 0, T_i kPairReach half-widths
///   (a parallel pair's stretch: ParallelPair);
/// - a plane (K = 0): as two, each line meeting it once, T_i 16 `reach`;
/// - a double plane, a real line (x^2 + y^2 = 0): the bases themselves, A's kernel's rational points
///   (on_kernel), T_i 16 `reach` (lines through them only touch A: none was found, the sample was
///   empty, and a B with no real point passed as a matrix; audit 36a F2).
/// Random lines through a point beside them met them as far out as they were near parallel to them:
/// sized 0.3 to 89 by seed for a reflected parabolic cylinder, 0.8 to 18 for a plane pair (audit
/// 35a F2). nullopt where A is none of these.
struct Prism {
  Vec3<Q> origin, middle, across = Vec3<Q>::Zero(), axis = Vec3<Q>::Zero();
  bool on_kernel = false;  ///< the bases are A's points themselves (a double plane, a real line)
  Q H{0};
  bool one_sided = false;
  std::array<Vec3<Q>, 2> along{{Vec3<Q>::Zero(), Vec3<Q>::Zero()}};
  std::array<Q, 2> T{{Q(0), Q(0)}};
  Vec4<Q> base(const Q& h, const Q& t1, const Q& t2) const {
    return finite(Vec3<Q>(origin + h * axis + t1 * along[0] + t2 * along[1]));
  }
};
/// The multiple t of v (not 0) with |t v| = kReachCap `reach`, to 2^-52: how far an object without a
/// length of its own (a plane, a double plane, a line, a plane pair) is sampled along v.
Q reach_along(const Q& reach, const Vec3<Q>& v) { return Q(kReachCap * reach / rough_sqrt(v.squaredNorm())); }
/// (v not 0) Two orthogonal primitive vectors across it (plane_across's).
std::array<Vec3<Q>, 2> primitive_across(const Vec3<Q>& v) {
  const Eigen::Matrix<Q, 3, 2> p = plane_across(v);
  return {{primitive_direction(Vec3<Q>(p.col(0))), primitive_direction(Vec3<Q>(p.col(1)))}};
}
std::optional<Prism> prism(const Mat4<Q>& A, const QuadricCore& core, const Q& reach, const std::optional<Vec3<Q>>& anchor) {
  if (!core.found) return std::nullopt;
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  const Vec3<Q> y = anchor ? core.nearest(*anchor) : core.y;
  Prism out;
  const auto range = [&]() {  // (K of rank 1: its range, a non-zero row)
    for (int i = 0; i < 3; ++i)
      if (!K.row(i).isZero()) return primitive_direction(Vec3<Q>(K.row(i).transpose()));
    return Vec3<Q>(Vec3<Q>::Zero());
  };
  if (core.kernel.cols() == 3) {  // a plane: 2 k . x + A_ww = 0 (none where k = 0: K = 0 too)
    if (core.kn.isZero()) return std::nullopt;
    out.across = primitive_direction(core.kn);
    out.origin = core.vertex(A, y);
    out.along = primitive_across(out.across);
    out.T = {reach_along(reach, out.along[0]), reach_along(reach, out.along[1])};
  } else if (core.kernel.cols() == 2 && !core.kn.isZero()) {  // a parabolic cylinder
    out.across = range();
    out.axis = primitive_direction(core.kn);
    out.along[0] = primitive_direction(Vec3<Q>(out.axis.cross(out.across)));
    out.origin = core.vertex(A, y);
    const Q qr = out.across.dot(K * out.across);
    // (it opens towards h > 0: A(o + h w) = 2 h w . k_n of the sign opposite to r^T K r)
    if ((out.axis.dot(core.kn) > 0) == (qr > 0)) out.axis = -out.axis;
    const Q far2 = sixteen_f_squared(core, K);
    out.H = rough_sqrt(Q(far2 / out.axis.squaredNorm()));
    out.T[0] = rough_sqrt(Q(far2 / out.along[0].squaredNorm()));
    out.one_sided = true;
  } else if (core.kernel.cols() == 2) {  // two parallel planes, or one double plane
    out.across = range();
    out.origin = y;
    out.along = primitive_across(out.across);
    const Q a0 = quadric_value(A, y), qr = out.across.dot(K * out.across);
    if (a0 == 0) {  // a double plane: its points are A's kernel's, rational, 16 `reach` out each way
      out.on_kernel = true;
      out.T = {reach_along(reach, out.along[0]), reach_along(reach, out.along[1])};
      out.across.setZero();
      out.middle = out.origin;
      return out;
    }
    if ((a0 > 0) == (qr > 0)) return std::nullopt;
    const Q half2 = -a0 / qr * out.across.squaredNorm();
    for (int i = 0; i < 2; ++i)
      out.T[static_cast<std::size_t>(i)] = rough_sqrt(Q(kPairReach * kPairReach * half2 / out.along[static_cast<std::size_t>(i)].squaredNorm()));
  } else if (core.line_of_centres() && quadric_value(A, y) == 0) {  // a pair of planes crossing, or a line
    out.along[0] = primitive_direction(Vec3<Q>(core.kernel.col(0)));
    out.origin = y;
    const Eigen::Matrix<Q, 3, 2> plane = plane_across(out.along[0]);
    const Eigen::Matrix<Q, 2, 2> G = plane.transpose() * K * plane;
    if (G.determinant() > 0) {  // complex planes: their one real line, A's kernel, 16 `reach` each way
      out.on_kernel = true;
      out.T[0] = reach_along(reach, out.along[0]);
      out.middle = out.origin;
      return out;
    }
    if (!(G.determinant() < 0)) return std::nullopt;
    const auto f = form_axes<2>(G, Eigen::Matrix<Q, 2, 1>(plane.col(0).squaredNorm(), plane.col(1).squaredNorm()));
    if (!f) return std::nullopt;
    const auto W = semi_axes(*f);
    if (!W) return std::nullopt;
    // r the refined axis of the larger |quotient|, w across the line and K-conjugate to r (w . K r =
    // 0: each line's two points symmetric about its base): w's error is r's times the smaller
    // eigenvalue over the larger (the other way round, nearly parallel planes' w tilted by the ratio)
    const int j = abs(f->rq[0]) >= abs(f->rq[1]) ? 0 : 1;
    out.across = refined_axis(K, Vec3<Q>(plane * Eigen::Matrix<Q, 2, 1>(W->col(j))));
    out.axis = primitive_direction(Vec3<Q>(out.along[0].cross(Vec3<Q>(K * out.across))));
    const Q qw = out.axis.dot(K * out.axis), qr = out.across.dot(K * out.across);
    if (qw == 0 || qr == 0 || (qw > 0) == (qr > 0)) return std::nullopt;
    out.H = Q(kReachCap * reach / rough_sqrt(Q(out.axis.squaredNorm() - qw / qr * out.across.squaredNorm())));
    out.T[0] = reach_along(reach, out.along[0]);
  } else {
    return std::nullopt;
  }
  out.middle = out.one_sided ? Vec3<Q>(out.origin + out.H / 2 * out.axis) : out.origin;
  return out;
}

/// Up to n points of A drawn as a Prism: its corners' lines first (rep.ends points: 2 per line, 1 for
/// a plane), then lines through seeded bases |h| <= 15/16 H, |t_i| <= 15/16 T_i, seeded points
/// farther from the middle than the ends dropped (EndsCap).
SampleReport sample_prism(const Mat4<Q>& A, const Prism& p, int n, Draw& draw) {
  SampleReport rep;
  rep.middle = p.middle;
  Lines lines(A, p.base(0, 0, 0));
  const Vec4<Q> r(p.across(0), p.across(1), p.across(2), Q(0));
  const int per_line = p.on_kernel || Mat3<Q>(A.topLeftCorner<3, 3>()).isZero() ? 1 : 2;
  const auto line = [&](const Q& h, const Q& t1, const Q& t2) {
    ++rep.attempts;
    if (p.on_kernel) {  // (the base is a point of A: A x = 0)
      rep.points.emplace_back(p.base(h, t1, t2), Vec4<Q>::Zero(), Q(0));
      return;
    }
    lines.set_base(p.base(h, t1, t2));
    lines.intersect(r, rep.points, n);
  };
  const auto ends = [](const Q& x, bool both) { return x == 0 ? std::vector<Q>{Q(0)} : both ? std::vector<Q>{x, Q(-x)} : std::vector<Q>{x}; };
  for (const Q& h : ends(p.H, !p.one_sided))
    for (const Q& t1 : ends(p.T[0], true))
      for (const Q& t2 : ends(p.T[1], true)) {
        rep.ends += per_line;
        if (static_cast<int>(rep.points.size()) < n) line(h, t1, t2);
      }
  EndsCap cap(p.middle, rep.ends);
  cap.apply(rep.points, rep.points.size(), n);
  const long long max_attempts = 50LL * n + 50;
  const auto inner = [&](const Q& x) { return Q(x * 15 / 16 * draw.unit()); };
  while (static_cast<int>(rep.points.size()) < n && rep.attempts < max_attempts) {
    Q h(0);
    if (p.H != 0)
      do h = p.one_sided ? Q(abs(inner(p.H))) : inner(p.H); while (h == 0);
    const Q t1 = inner(p.T[0]), t2 = inner(p.T[1]);
    const std::size_t had = rep.points.size();
    line(h, t1, t2);
    cap.apply(rep.points, had, n);
  }
  rep.exhausted = static_cast<int>(rep.points.size()) < n;
  return rep;
}

/// An ellipsoid's longest semi-axis, as a direction (semi_axes, refined: refined_axis). The far point
/// is flat along the ellipsoid, but its deficit is the direction's error squared times the axes'
/// squared ratio: with semi_axes's 40 bits, an ellipsoid 10^9 times longer than wide was sized 4e-9
/// short, by the turn (audit 36a F3). From K's axes f and their semi_axes W (K definite).
Vec3<Q> longest_axis(const Mat3<Q>& K, const FormAxes<3>& f, const Mat3<Q>& W) {
  int j = 0;
  for (int c = 1; c < 3; ++c)
    if (abs(f.rq[static_cast<std::size_t>(c)]) < abs(f.rq[static_cast<std::size_t>(j)])) j = c;
  return refined_axis(K, Vec3<Q>(W.col(j)));
}

}  // namespace

QuadricCore quadric_core(const Mat4<Q>& A) {
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  const Vec3<Q> k = A.topRightCorner<3, 1>();
  QuadricCore core;
  if (K.determinant() != 0) {
    core.kernel.resize(3, 0);
    core.kn.setZero();
    core.y = -(K.inverse() * k);
    core.found = true;
    return core;
  }
  const Eigen::FullPivLU<Mat3<Q>> lu(K);  // exact: Rational's epsilon is 0, so are the pivots' thresholds
  core.kernel = lu.kernel();
  // k_n = N (N^T N)^-1 N^T k, a rational projection (the kernel's basis need not be orthogonal)
  const Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic> G = core.kernel.transpose() * core.kernel;
  core.kn = core.kernel * Eigen::Matrix<Q, Eigen::Dynamic, 1>(G.inverse() * (core.kernel.transpose() * k));
  const Vec3<Q> kr = k - core.kn;
  core.y = lu.solve(Vec3<Q>(-kr));
  core.found = Vec3<Q>(K * core.y + kr).isZero();
  return core;
}

std::optional<Vec3<Q>> centre_of_core(const Mat4<Q>& A, const std::optional<Vec3<Q>>& anchor) {
  const QuadricCore core = quadric_core(A);
  if (!core.found || !core.kn.isZero()) return std::nullopt;
  return anchor ? core.nearest(*anchor) : core.y;  // (K invertible: y, its centre, whatever the anchor)
}

Vec3<Q> QuadricCore::vertex(const Mat4<Q>& A, const Vec3<Q>& p) const {
  return Vec3<Q>(p - quadric_value(A, p) / (2 * kn.squaredNorm()) * kn);
}

Vec3<Q> QuadricCore::nearest(const Vec3<Q>& p) const {
  if (kernel.cols() == 0) return y;
  const Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic> G = kernel.transpose() * kernel;
  return Vec3<Q>(y + kernel * Eigen::Matrix<Q, Eigen::Dynamic, 1>(G.inverse() * (kernel.transpose() * Vec3<Q>(p - y))));
}

Q quadric_value(const Mat4<Q>& A, const Vec3<Q>& y) {
  return y.dot(Mat3<Q>(A.topLeftCorner<3, 3>()) * y) + 2 * Vec3<Q>(A.topRightCorner<3, 1>()).dot(y) + A(3, 3);
}

Vec4<Q> section_base(const Mat4<Q>& A, const Vec4<Q>& pi, const std::optional<Vec3<Q>>& anchor) {
  const Vec3<Q> normal = pi.head<3>();
  const Eigen::Matrix<Q, 4, 3> E = plane_basis<Q>(pi);
  const Mat3<Q> K = E.transpose() * A * E;
  if (K.determinant() != 0) {  // the centre of the section, the pole of its line at infinity
    const Eigen::Matrix<Q, 3, 1> ell = E.transpose() * Vec4<Q>(0, 0, 0, 1);
    const Vec4<Q> c = E * Eigen::Matrix<Q, 3, 1>(adjugate3<Q>(K) * ell);
    if (c(3) != 0) return c / c(3);
  }
  const Vec3<Q> y = core_point(A, anchor);  // else the foot on the plane of A's core point
  return finite(Vec3<Q>(y - (normal.dot(y) + pi(3)) / normal.squaredNorm() * normal));
}

Vec4<Q> quadric_base(const Mat4<Q>& A, const std::optional<Vec3<Q>>& anchor) { return finite(core_point(A, anchor)); }

Q reach_length(const Vec4<Q>& b, const Vec4<Q>& light) {
  if (light(3) != 0) {
    const Q d = max_abs(Vec3<Q>(light.head<3>() / light(3) - b.head<3>() / b(3)));
    if (d > 0) return d;
  }
  return Q(1);
}

SampleReport sample_section(const Mat4<Q>& A, const Vec4<Q>& pi, int n, std::uint64_t seed, const Q& reach,
                            const std::optional<Vec3<Q>>& anchor) {
  if (!(reach > 0)) throw std::invalid_argument("sample_section: reach must be positive");
  SampleReport rep;
  const Vec3<Q> normal = pi.head<3>();
  if (normal.isZero() || n <= 0) {
    rep.exhausted = n > 0;
    return rep;
  }
  Draw draw(seed);
  const Eigen::Matrix<Q, 4, 3> E = plane_basis<Q>(pi);
  const Mat3<Q> K = E.transpose() * A * E;
  auto on_plane = [&](const Eigen::Matrix<Q, 3, 1>& s, std::vector<RootPoint>& out) {
    const Vec4<Q> x = E * s;
    if (x(3) != 0 && !x.isZero()) out.emplace_back(Vec4<Q>(x / x(3)), Vec4<Q>::Zero(), Q(0));
  };
  // A definite section has no real point (a light inside an ellipsoid; the status predicate's own
  // test, core/predicates.hpp): every attempt would be spent, on coordinates that grow with each (a
  // sphere of radius 1e300 with the light 1e-300 inside its surface took 77 s; audit 30a F2).
  if (conic_definite<Q>(K) == Truth::yes) {
    rep.exhausted = true;
    return rep;
  }
  // Singular points of the section (exact, rational).
  const Mat3<Q> adj = adjugate3<Q>(K);
  if (K.determinant() == 0) {
    if (!adj.isZero()) {
      for (int j = 0; j < 3; ++j)
        if (!adj.col(j).isZero()) {
          on_plane(adj.col(j), rep.points);
          break;
        }
    } else if (!K.isZero()) {  // double line r.s = 0
      Eigen::Matrix<Q, 3, 1> r = K.row(0).transpose();
      for (int i = 1; r.isZero() && i < 3; ++i) r = K.row(i).transpose();
      for (int j = 0; j < 3 && static_cast<int>(rep.points.size()) < n; ++j) {
        const Eigen::Matrix<Q, 3, 1> k = r.cross(Eigen::Matrix<Q, 3, 1>::Unit(j));
        if (!k.isZero()) on_plane(k, rep.points);
      }
    }
  }
  // A section of rank 2 is a pair of lines through its singular point: adj(K) = l1 l2 v v^T (v the
  // kernel, l1 l2 the product of the other eigenvalues), so a positive trace is a pair of complex
  // lines, whose one real point is that singular point, found above (a cone lit from inside: its
  // terminator is its apex). No line meets the section elsewhere: every attempt would be spent.
  if (K.determinant() == 0 && adj.trace() > 0) {
    rep.exhausted = static_cast<int>(rep.points.size()) < n;
    return rep;
  }
  Vec4<Q> b = section_base(A, pi, anchor);
  // a central section's middle is its centre (the pole of its line at infinity: section_base), from
  // which an ellipse on a paraboloid is sized, not its points' centroid, which moved with the seed
  // (audit 36b F4); the stretches below set their own
  if (K.determinant() != 0) rep.middle = Vec3<Q>(b.head<3>() / b(3));
  // (from the primitive normal below: the same chords for every positive multiple of A and L)
  const std::optional<ParallelPair> pair = parallel_pair(A, E, K, primitive_normal(normal), b);
  if (pair) {
    b = pair->mid;
    rep.middle = Vec3<Q>(b.head<3>());
    rep.ends = 4;
  }
  const long long max_attempts = 50LL * n + 50;  // (in 64 bits: n may be large)
  Lines lines(A, b);
  int hits = 0;
  // the base's shifts (below) are made with the normal's primitive integer form: the same shifts for
  // every positive multiple of A and L
  const Vec3<Q> shift_normal = primitive_normal(normal);
  bool stepped = false;
  // an elliptic section: in-plane directions shaped by its axes (shaped_directions), in the plane's
  // basis a = n x e_j, n x a, n the normal's primitive integers (the same basis for every positive
  // multiple of A and L, as the shifts below)
  const Eigen::Matrix<Q, 3, 2> in_plane = plane_across(shift_normal);
  if (const std::optional<SingleLine> line = pair ? std::nullopt : single_line(A, in_plane, shift_normal, b)) {
    rep.middle = Vec3<Q>(line->m.head<3>());
    rep.ends = 2;  // (measured from an axis point, one end may be farther than the other)
    Stretch ends;
    ends.inner = kPairReach - 1;
    while (static_cast<int>(rep.points.size()) < n) {
      const Q t = ends.next(draw) / kPairReach * line->reach;
      rep.points.emplace_back(Vec4<Q>(line->m + t * Vec4<Q>(line->d(0), line->d(1), line->d(2), Q(0))), Vec4<Q>::Zero(), Q(0));
      ++rep.attempts;
    }
    return rep;
  }
  // (the basis is orthogonal, its vectors' lengths |a| and |n| |a|: the form's axes in that metric)
  const auto shape = shaped_directions<2>(
      Eigen::Matrix<Q, 2, 2>(in_plane.transpose() * Mat3<Q>(A.topLeftCorner<3, 3>()) * in_plane),
      Eigen::Matrix<Q, 2, 1>(in_plane.col(0).squaredNorm(), in_plane.col(1).squaredNorm()));
  // a hyperbola (a hyperboloid's terminator), b its centre: chords along its axes (conic_axes), the
  // first two the farthest (s = +-ConicAxes::end), their points as far from b; the others short of
  // them (ConicAxes::inner). Random directions met it as far out as they were near its asymptotes, and
  // its size was the seed's.
  const std::optional<ConicAxes> hyperbola = [&]() -> std::optional<ConicAxes> {
    if (pair || shape || K.determinant() == 0) return std::nullopt;
    const Vec4<Q> Ab = A * b;
    for (int j = 0; j < 2; ++j)  // (b is the section's centre: no in-plane direction is conjugate to it)
      if (Vec3<Q>(in_plane.col(j)).dot(Vec3<Q>(Ab.head<3>())) != 0) return std::nullopt;
    auto axes = conic_axes(A, in_plane, Q(b.dot(Ab) / (b(3) * b(3))));
    if (!axes || !axes->hyperbolic) return std::nullopt;
    return axes;
  }();
  if (hyperbola) {
    rep.middle = Vec3<Q>(b.head<3>() / b(3));
    rep.ends = 4;
  }
  const std::optional<ParabolaChords> parabola =
      pair || shape || hyperbola || K.determinant() == 0 ? std::nullopt : parabola_chords(A, in_plane, shift_normal, b);
  if (parabola) {  // (its size from the middle of its stretch of axis where A has no centre: a paraboloid)
    rep.middle = Vec3<Q>(parabola->at(parabola->end / 2).head<3>());
    rep.ends = 2;
  }
  Stretch stretch;  // a parallel pair's chords (ParallelPair)
  int hyperbola_ends = 2;  // (s = +-its end)
  bool parabola_end = true;
  // Measured from a point other than the stretch's middle (A's centre; a cylinder's axis point), a
  // seeded point may lie farther out than the ends (10% farther for a hyperbola on a hyperboloid
  // whose centre is off the section's): such points are dropped (EndsCap). A parabola on a
  // hyperboloid may be farthest from A's centre inside its stretch (its vertex, or between it and the
  // end chord): that point (parabola_far_point) is one of its ends, drawn first.
  const std::optional<Vec3<Q>> size_from = hyperbola || parabola ? centre_of_core(A, anchor) : std::nullopt;
  if (parabola && size_from && rep.points.empty())
    if (const std::optional<Vec4<Q>> far = parabola_far_point(*parabola, *size_from)) {
      rep.points.emplace_back(*far, Vec4<Q>::Zero(), Q(0));
      ++rep.ends;
    }
  EndsCap cap(size_from, rep.ends);
  const auto direction = [&]() -> Vec3<Q> {
    if (pair) return Vec3<Q>(pair->across + stretch.next(draw) * pair->along);
    if (parabola && !stepped) {  // (each chord from its own base on the axis)
      Q u = parabola->end;
      if (!parabola_end) {
        do u = Q(parabola->end * 15 / 16 * abs(draw.unit())); while (u == 0);
      }
      parabola_end = false;
      b = parabola->at(u);
      lines.set_base(b);
      return parabola->across;
    }
    if (hyperbola && !stepped) {
      const Q s = hyperbola_ends > 0 ? Q(hyperbola_ends-- == 2 ? hyperbola->end : -hyperbola->end) : hyperbola->inner(draw);
      return Vec3<Q>(hyperbola->across.col(0) + s * hyperbola->across.col(1));
    }
    if (!shape || stepped) return normal.cross(draw.vec3());
    Vec3<Q> r = draw.vec3();
    while (r(0) == 0 && r(1) == 0) r = draw.vec3();
    return in_plane * (*shape * Eigen::Matrix<Q, 2, 1>(r(0), r(1)));
  };
  while (static_cast<int>(rep.points.size()) < n && rep.attempts < max_attempts) {
    ++rep.attempts;
    const Vec3<Q> d = direction();  // a direction inside the plane
    if (d.isZero()) continue;
    const std::size_t had = rep.points.size();
    hits += lines.intersect(Vec4<Q>(d(0), d(1), d(2), Q(0)), rep.points, n) ? 1 : 0;
    if (stepped) keep_near(rep.points, had, b, reach);
    if (!stepped) cap.apply(rep.points, had, n);
    // no line has met the section yet (the base may be its singular point, a cone's apex, which
    // every line through it only touches): move the base point within the plane
    if (rep.attempts % 8 == 0 && hits == 0) {
      const Vec3<Q> shift = shift_normal.cross(draw.vec3());
      if (shift.isZero()) continue;
      b.head<3>() += scaled_to(shift, reach);
      lines.set_base(b);
      stepped = true;
    }
  }
  rep.exhausted = static_cast<int>(rep.points.size()) < n;
  return rep;
}

bool without_real_points(const Mat4<Q>& A) { return *definiteness<Q, 4>(A) != 0; }

SampleReport sample_quadric(const Mat4<Q>& A, int n, std::uint64_t seed, const Q& reach,
                            const std::optional<Vec3<Q>>& anchor) {
  if (!(reach > 0)) throw std::invalid_argument("sample_quadric: reach must be positive");
  SampleReport rep;
  if (n <= 0) return rep;
  if (without_real_points(A)) {  // (an imaginary ellipsoid): as sample_section
    rep.exhausted = true;
    return rep;
  }
  Draw draw(seed);
  const QuadricCore core = quadric_core(A);
  if (const std::optional<AxialSections> axial = axial_sections(A, core, reach, anchor))
    return sample_axial(A, *axial, n, draw);
  if (const std::optional<Prism> p = prism(A, core, reach, anchor)) return sample_prism(A, *p, n, draw);
  Vec4<Q> b = finite(core_point(A, core, anchor));  // (quadric_base, with the core at hand)
  const long long max_attempts = 50LL * n + 50;  // (in 64 bits: n may be large)
  Lines lines(A, b);
  bool stepped = false;
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  // an ellipsoid (K definite): its axes found once, for the shaped directions (shaped_directions)
  // and for its longest semi-axis, whose ends come first, the farthest points from its centre (b),
  // the sample's size at every seed and count (random directions gave 9.999994 or 10 by seed for
  // semi-axes 1, 2 and 10)
  const std::optional<FormAxes<3>> axes = *definiteness<Q, 3>(K) != 0 ? form_axes<3>(K, Vec3<Q>(1, 1, 1)) : std::nullopt;
  const std::optional<Mat3<Q>> W = axes ? semi_axes(*axes) : std::nullopt;
  const std::optional<Mat3<Q>> shape = W && elongated(*axes) ? W : std::nullopt;
  const std::optional<Vec3<Q>> longest =
      W && quadric_value(A, core.y) != 0 ? std::optional<Vec3<Q>>(longest_axis(K, *axes, *W)) : std::nullopt;
  EndsCap cap(longest ? std::optional<Vec3<Q>>(Vec3<Q>(b.head<3>())) : std::nullopt, longest ? 2 : 0);
  if (longest) {
    rep.ends = 2;
    ++rep.attempts;
    lines.intersect(Vec4<Q>((*longest)(0), (*longest)(1), (*longest)(2), Q(0)), rep.points, n);
    cap.apply(rep.points, rep.points.size(), n);
  }
  // A cylinder (an axis of centres, through b): lines r + t a within kPairReach cross-section radii
  // of b along the axis (cylinder_chords); random directions met it as far out as they were near
  // parallel to the axis (10^9 out for an axis 10^-9 from level). Where its cross-section has no
  // shape (cylinder_chords says where), r random across the axis.
  const std::optional<Vec3<Q>> axis =
      core.line_of_centres() ? std::optional<Vec3<Q>>(primitive_direction(Vec3<Q>(core.kernel.col(0)))) : std::nullopt;
  const std::optional<ConicAxes> chords = axis ? cylinder_chords(A, *axis, Vec3<Q>(b.head<3>())) : std::nullopt;
  Stretch stretch;
  if (chords) stretch.inner = kPairReach - 1;
  const auto across = [&]() -> Vec3<Q> {
    if (!chords) {
      Vec3<Q> r = axis->cross(draw.vec3());  // (not 0 for every draw: the axis is not 0)
      while (r.isZero()) r = axis->cross(draw.vec3());
      return r;
    }
    const bool end = stretch.ends > 0;  // (the stretch's two ends: the same r)
    if (chords->hyperbolic) {
      const Q s = end ? chords->end : chords->inner(draw);
      return Vec3<Q>(chords->across.col(0) + s * chords->across.col(1));
    }
    if (end) return chords->across.col(0);
    Vec3<Q> v = draw.vec3();
    while (v(0) == 0 && v(1) == 0) v = draw.vec3();
    return Vec3<Q>(chords->across * Eigen::Matrix<Q, 2, 1>(v(0), v(1)));
  };
  const auto direction = [&]() -> Vec3<Q> {
    if (axis && !stepped) {
      const Vec3<Q> r = across();
      return Vec3<Q>(r + stretch.next(draw) * rough_sqrt(Q(r.squaredNorm() / axis->squaredNorm())) * *axis);
    }
    return shape && !stepped ? Vec3<Q>(*shape * draw.vec3()) : draw.vec3();
  };
  while (static_cast<int>(rep.points.size()) < n && rep.attempts < max_attempts) {
    ++rep.attempts;
    const Vec3<Q> d = direction();
    const std::size_t had = rep.points.size();
    lines.intersect(Vec4<Q>(d(0), d(1), d(2), Q(0)), rep.points, n);
    if (stepped) keep_near(rep.points, had, b, reach);
    cap.apply(rep.points, had, n);
    if (rep.attempts % 8 == 0 && rep.points.empty()) {  // (e.g. from a cone's apex: every line only touches)
      b.head<3>() += scaled_to(draw.vec3(), reach);
      lines.set_base(b);
      stepped = true;
    }
  }
  rep.exhausted = static_cast<int>(rep.points.size()) < n;
  return rep;
}

}  // namespace qverify
