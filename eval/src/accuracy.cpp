#include <qverify/eval/accuracy.hpp>
#include <qverify/exact/integer_point.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/root_enclosure.hpp>
#include <Eigen/LU>

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace qverify {

using Q = Rational;

namespace {

Measure mmax(const Measure& a, const Measure& b) { return a < b ? b : a; }
Measure mmin(const Measure& a, const Measure& b) { return a < b ? a : b; }

/// Cartesian coordinates of x to 80 digits (w != 0 for every sampled point).
Vec3<Measure> cartesian(const RootPoint& x) {
  const IntegerPoint n(x);  // on integers: no gcd per operation
  const Measure w = n.coordinate(3);
  return Vec3<Measure>(n.coordinate(0) / w, n.coordinate(1) / w, n.coordinate(2) / w);
}

using FI = FilterInterval;

FI enclosed(const Q& q) {
  const Interval e = enclose(q);
  return FI(e.inf(), e.sup());
}

bool positive(const FI& x) { return x.inf() > 0 && std::isfinite(x.sup()); }

/// x - c to 80 digits per coordinate, from the exact difference (IntegerPoint::offset).
Vec3<Measure> offset_from(const RootPoint& x, const Vec3<Q>& c) {
  const IntegerPoint n(x);
  return Vec3<Measure>(n.offset(0, c(0)), n.offset(1, c(1)), n.offset(2, c(2)));
}

/// Largest distance of the points from A's centre, to 80 digits, and the centre: `core_centre`
/// where one is given (centre_of_core, or where A has none the sampler's middle of a stretch:
/// SampleReport::middle); where none is, their centroid, rounded to a rational (the distances are
/// measured from that exact point). Each distance from the point's exact offset from the
/// centre (offset_from). With a centre, a filter first: each point's squared distance is enclosed
/// from its coordinates' enclosures, and only the points whose upper bound reaches the largest lower
/// bound (or that the intervals cannot bound) can be the farthest; only those are measured.
std::pair<Measure, Vec3<Q>> object_size(const std::vector<RootPoint>& pts,
                                        const std::optional<Vec3<Q>>& core_centre) {
  if (pts.empty()) return {0, Vec3<Q>::Zero()};
  // (every distance from the exact offset of the point from the centre: the points rounded to 80
  // digits first, a cylinder of radius 1e-100 at 3 from the origin was sized 3e-80, its rounding
  // noise, and a B off by 1.5 radii passed; audit 34a F1)
  if (!core_centre) {
    // the centroid, as offsets from a rational point near the first (exact differences again)
    const Vec3<Measure> x0 = cartesian(pts.front());
    const Vec3<Q> r0(exact_measure(x0(0)), exact_measure(x0(1)), exact_measure(x0(2)));
    // one point (or one point repeated) has no extent: 0, exactly (not the rounding of the centroid's
    // rounding), so that the default sample sizes it (terminator_points)
    const RootPoint& f = pts.front();
    if (std::all_of(pts.begin(), pts.end(),
                    [&](const RootPoint& x) { return x.p() == f.p() && x.q() == f.q() && x.delta() == f.delta(); }))
      return {0, r0};
    Vec3<Measure> m = Vec3<Measure>::Zero();
    for (const RootPoint& x : pts) m += offset_from(x, r0);
    m /= Measure(static_cast<long>(pts.size()));
    const Vec3<Q> cq(r0(0) + exact_measure(m(0)), r0(1) + exact_measure(m(1)), r0(2) + exact_measure(m(2)));
    Measure best = 0;
    for (const RootPoint& x : pts) best = mmax(best, sqrt(offset_from(x, cq).squaredNorm()));
    return {best, cq};
  }
  const Vec3<Q> cq = *core_centre;
  std::vector<FI> d2(pts.size());
  std::vector<char> bounded(pts.size(), 0);
  double floor = 0;
  {
    const FI ce[3] = {enclosed(cq(0)), enclosed(cq(1)), enclosed(cq(2))};
    CGAL::Protect_FPU_rounding<true> guard;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const PointEnclosure& X = pts[k].enclosure();
      if (!positive(CGAL::abs(X[3]))) continue;
      FI s(0);
      for (int i = 0; i < 3; ++i) s += CGAL::square(X[static_cast<std::size_t>(i)] / X[3] - ce[i]);
      if (!std::isfinite(s.sup())) continue;
      d2[k] = s;
      bounded[k] = 1;
      floor = std::max(floor, s.inf());
    }
  }
  Measure best = 0;
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (!bounded[k] || d2[k].sup() >= floor) best = mmax(best, sqrt(offset_from(pts[k], cq).squaredNorm()));
  return {best, cq};
}


/// The certified bounds' unit of length (ShadowBounds, ReflectionBounds, the whole terminator's
/// size): the power of two 2^e <= size < 2^(e + 1) (1 for no size). Their intervals are doubles,
/// and an object 10^-200 (10^200) across squares to 10^-400 (10^400) in world units: its
/// gradients' squares underflowed to 0 (the conic's entries overflowed), and a sphere's accurate
/// results had no bound. In units of 2^e, x = 2^e x', the object is 1 to 2 across, and the
/// relative first-order distance is the same (a distance scales as the coordinates); at ordinary
/// scales every double is the same one times a power of two.
Q length_unit(const Measure& size) { return size > 0 ? exact_pow2(floor_log2(exact_measure(size))) : Q(1); }

/// A quadric in units of u: D X D, D = diag(u, u, u, 1).
Mat4<Q> quadric_in_units(const Mat4<Q>& X, const Q& u) {
  Mat4<Q> D = Mat4<Q>::Identity();
  D.topLeftCorner<3, 3>() *= u;
  return D * X * D;
}
/// The object's quadric in units of u, times the power of two that brings its largest entry near 1
/// (a positive factor: the same quadric; its floors start from a double eigen-decomposition).
Mat4<Q> object_in_units(const Mat4<Q>& A, const Q& u) {
  const Mat4<Q> Au = quadric_in_units(A, u);
  const Q big = max_abs(Au);
  return big == 0 ? Au : Mat4<Q>(Au * exact_pow2(-floor_log2(big)));
}
Vec4<Q> plane_in_units(const Vec4<Q>& p, const Q& u) { return Vec4<Q>(p(0) * u, p(1) * u, p(2) * u, p(3)); }
Vec4<Q> point_in_units(const Vec4<Q>& x, const Q& u) { return Vec4<Q>(x(0) / u, x(1) / u, x(2) / u, x(3)); }
/// A map of points (the mirror) in units of u: D^-1 M D.
Mat4<Q> map_in_units(const Mat4<Q>& M, const Q& u) {
  Mat4<Q> D = Mat4<Q>::Identity(), Dinv = Mat4<Q>::Identity();
  D.topLeftCorner<3, 3>() *= u;
  Dinv.topLeftCorner<3, 3>() /= u;
  return Dinv * M * D;
}
Ball ball_in_units(const Ball& b, const Q& u) {
  return {Vec3<Q>(b.centre / u), Q(b.reach / u), b.half ? std::optional<Vec3<Q>>(Vec3<Q>(*b.half / u)) : std::nullopt};
}
std::optional<Vec3<Q>> origin_in_units(const std::optional<Vec3<Q>>& o, const Q& u) {
  return o ? std::optional<Vec3<Q>>(Vec3<Q>(*o / u)) : std::nullopt;
}
/// A size (what a bound divides by) in units of u, rounded down.
double size_in_units(double size, const Q& u) { return size_down(Measure(Measure(size) / to_measure(u))); }

/// The ball of the points counted (certified_bound.hpp, Ball): about the centre, with a reach of
/// (at least) the size and a margin (2^-64 of it) for the last of its 80 digits.
Ball counted_ball(const Vec3<Q>& centre, const Measure& reach) {
  const Q s = exact_measure(reach);
  return {centre, Q(s + s / Q(BigInt(1) << 64)), std::nullopt};
}

/// The offsets rho of the generator points (ItemPoints::generator_offsets): x + rho d,
/// d = L_xyz - L_w x (Cartesian x), for rho = tau * scale with tau = 1/2, -1/2, 1/4 and one
/// scale for the item, min(size / max |d|, 1 / |L_w|) over (at most 8 of) the terminator
/// points, rounded to a double: offsets up to half the object's size along the generators,
/// and at most half way to the apex (rho L_w = 1), where the cone's gradient vanishes. One
/// scale per item, not per point, so that the points of one offset are the terminator of one
/// quadric (generator_map).
std::vector<Q> generator_offsets(const std::vector<RootPoint>& terminator, const Vec4<Q>& L, const Measure& size) {
  if (!(size > 0)) return {};
  Measure dmax = 0;
  for (std::size_t i = 0; i < terminator.size() && i < 8; ++i) {
    const auto c = terminator[i].coords();
    const Measure w = to_measure(c[3]);
    Measure d2 = 0;  // |L_xyz - L_w p|^2, p the Cartesian point
    for (int k = 0; k < 3; ++k) {
      const Measure dk = to_measure(L(k)) - to_measure(L(3)) * to_measure(c[k]) / w;
      d2 += dk * dk;
    }
    dmax = mmax(dmax, sqrt(d2));
  }
  if (!(dmax > 0)) return {};
  Measure s = size / dmax;
  if (L(3) != 0) {
    const Measure apex = 1 / abs(to_measure(L(3)));
    if (apex < s) s = apex;
  }
  const double scale = s.convert_to<double>();
  if (!std::isfinite(scale) || scale == 0) return {};
  const Q sq = to_rational(scale);
  return {Q(1, 2) * sq, Q(-1, 2) * sq, Q(1, 4) * sq};
}

/// The indices of the points where every form of `rows` vanishes exactly (row . x = 0). Filtered: a
/// point whose enclosure, times a row's entries enclosed, leaves that row's value certainly non-zero is
/// not one; only the others are decided exactly, in Q(sqrt d). (Deciding every point exactly cost
/// verify 9% of its speed at 4096 points a pair.)
std::vector<std::size_t> common_zeros(const std::vector<RootPoint>& pts, const std::vector<Vec4<Q>>& rows) {
  std::vector<std::size_t> out;
  std::vector<std::array<FI, 4>> a(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int j = 0; j < 4; ++j) a[i][static_cast<std::size_t>(j)] = enclosed(rows[i](j));
  for (std::size_t k = 0; k < pts.size(); ++k) {
    bool maybe = true;
    {
      CGAL::Protect_FPU_rounding<true> guard;
      const PointEnclosure& X = pts[k].enclosure();
      for (std::size_t i = 0; i < rows.size() && maybe; ++i) {
        FI v(0);
        for (std::size_t j = 0; j < 4; ++j) v += a[i][j] * X[j];
        maybe = !(v.inf() > 0 || v.sup() < 0);  // (a NaN bound leaves it in doubt)
      }
    }
    if (maybe && std::all_of(rows.begin(), rows.end(), [&](const Vec4<Q>& r) { return CGAL::is_zero(pts[k].linear(r)); }))
      out.push_back(k);
  }
  return out;
}

/// The indices of the points where A x = 0 (ItemPoints::singular: a cone's apex, and hardly any other).
std::vector<std::size_t> singular_points(const std::vector<RootPoint>& pts, const Mat4<Q>& A) {
  std::vector<Vec4<Q>> rows;
  for (int i = 0; i < 4; ++i) rows.emplace_back(A.row(i).transpose());
  return common_zeros(pts, rows);
}

/// `local` without the points whose indices (sorted) are `skip`.
std::vector<RootPoint> without(const std::vector<RootPoint>& local, const std::vector<std::size_t>& skip) {
  if (skip.empty()) return local;
  std::vector<RootPoint> out;
  out.reserve(local.size());
  for (std::size_t i = 0; i < local.size(); ++i)
    if (!std::binary_search(skip.begin(), skip.end(), i)) out.push_back(local[i]);
  return out;
}

/// Points on the generator lines of the cone through (at most 8 of) the terminator points, at
/// each offset: x mapped by generator_map, a linear map, so the point stays in x's field. Not
/// through a singular point of A (the apex of a cone lit from outside, sampled as the terminator's
/// singular point): there P = (L^T A L) A - (A L)(A L)^T has a vanishing gradient all along the
/// generator line (P y = (1 - rho L_w) s A x = 0), so a first-order distance from a rounded P means
/// nothing there (it is about |y| / 2 whatever the rounding). `singular`: those points' indices,
/// sorted (singular_points).
std::vector<RootPoint> generator_points(const std::vector<RootPoint>& terminator, const std::vector<std::size_t>& singular,
                                        const Vec4<Q>& L, const std::vector<Q>& offsets) {
  std::vector<RootPoint> out;
  std::size_t used = 0;
  for (std::size_t i = 0; i < terminator.size() && used < 8; ++i) {
    if (std::binary_search(singular.begin(), singular.end(), i)) continue;
    ++used;
    for (const Q& rho : offsets) out.push_back(terminator[i].mapped(generator_map(L, rho)));
  }
  return out;
}

/// Rational points of the polar plane inside the terminator: the rational parts p
/// (chord midpoints) of terminator points x = p + sqrt(d) q, and p + q, where
/// both lie on the plane. Where q's w is 0 (the sampler's points) and p's is
/// not, both lie on the chord from p - sqrt(d) q to p + sqrt(d) q (the radicand
/// d is an integer >= 1): inside the disc that terminator_quadric_bound covers. Not on R's second
/// plane h (ItemPoints::crossing: there R's gradient vanishes; a point light level with a sphere's
/// centre puts every chord's midpoint on h).
std::vector<RootPoint> plane_points(const std::vector<RootPoint>& terminator, const Vec4<Q>& pi, const Vec4<Q>& h) {
  std::vector<RootPoint> out;
  const auto add = [&](const Vec4<Q>& y) {
    if (h.dot(y) != 0) out.emplace_back(y, Vec4<Q>::Zero(), Q(0));
  };
  for (const RootPoint& x : terminator) {
    if (out.size() >= 16) break;
    if (pi.dot(x.p()) != 0 || pi.dot(x.q()) != 0 || x.p()(3) == 0 || x.q()(3) != 0) continue;
    add(x.p());
    if (!x.q().isZero()) add(Vec4<Q>(x.p() + x.q()));
  }
  return out;
}

}  // namespace

namespace {
/// 64-bit FNV-1a over the decimal digits of integers (the same value on every platform and compiler).
struct DigitHash {
  std::uint64_t h = 14695981039346656037ull;
  void add(const std::string& s) {
    for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    h = (h ^ static_cast<unsigned char>(',')) * 1099511628211ull;
  }
  template <std::size_t N> void add_all(const std::array<BigInt, N>& v) {
    for (const BigInt& x : v) add(x.str());
    h = (h ^ static_cast<unsigned char>(';')) * 1099511628211ull;
  }
};
}  // namespace

Mat4<Q> canonical_quadric(const Mat4<Q>& A) {
  std::array<BigInt, 16> a;
  primitive_integers(A, a);
  Mat4<Q> out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out(i, j) = Q(a[static_cast<std::size_t>(4 * i + j)]);
  return out;
}

Vec4<Q> canonical_light(const Vec4<Q>& L) {
  if (L(3) != 0) return Vec4<Q>(L / abs(L(3)));
  std::array<BigInt, 4> v;
  primitive_integers(L, v);
  return Vec4<Q>(Q(v[0]), Q(v[1]), Q(v[2]), Q(v[3]));
}

namespace {
/// Where an item's sampling base is taken along a core of A that is a line or a plane (a cylinder's
/// axis: exact/sampling.hpp, section_base and quadric_base take its point nearest this anchor), so
/// that the points move with the item when the scene is translated (a factorisation's particular
/// solution, taken before, slides along the axis: audit 31a F4). Kind 1 (shadow): a point light;
/// a parallel light, which like A does not change along the axis, gives no point of it, and the
/// world origin is taken (the same item placed elsewhere along its axis is then sampled elsewhere
/// along it). Kind 2 (reflection, `other` the mirror's plane): the core's point on the mirror, moved
/// there along the directions D in which A does not change (K w = 0, k_n . w = 0); where the plane is
/// parallel to D, the world origin again (A and the plane are the same about every such point, but
/// the points are not). A plane (K = 0) moves from its own point (the world origin's foot), not from
/// the sampler's base |k_n| off it: from there it reached the mirror |k_n| cot(angle) from the line
/// where they meet, 7e5 units off for a plane of small integers moved by 1e-6, 2.7e17 for one of
/// 17-digit decimals, where its stretch was drawn (audit 36a F1).
Vec3<Q> item_anchor(int kind, const Mat4<Q>& A, const Vec4<Q>& other) {
  if (kind == 1) return other(3) != 0 ? Vec3<Q>(other.head<3>() / other(3)) : Vec3<Q>(Vec3<Q>::Zero());
  const QuadricCore core = quadric_core(A);
  const bool plane = Mat3<Q>(A.topLeftCorner<3, 3>()).isZero() && !core.kn.isZero();
  // (a plane of centres, a double plane's or parallel planes', from the world origin's foot too: a
  // factorisation's particular solution lay anywhere along it, and so did the point on the mirror)
  const Vec3<Q> zero = Vec3<Q>::Zero();
  const Vec3<Q> b0 = plane ? core.vertex(A, zero)
                     : core.kernel.cols() >= 2 && core.kn.isZero() ? core.nearest(zero)
                                                                   : Vec3<Q>(quadric_base(A).head<3>());
  if (core.kernel.cols() == 0) return b0;
  const Eigen::Matrix<Q, 1, Eigen::Dynamic> along = core.kn.transpose() * core.kernel;
  const Eigen::FullPivLU<Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic>> lu(along);
  const Eigen::Matrix<Q, 3, Eigen::Dynamic> D = core.kernel * lu.kernel();
  const Vec3<Q> n = other.head<3>();
  const Eigen::Matrix<Q, Eigen::Dynamic, 1> w = D.transpose() * n;
  if (w.isZero()) return Vec3<Q>::Zero();  // (parallel: as for a parallel light, the world origin)
  // along n's orthogonal projection on D's span, D (D^T D)^-1 D^T n: along D w, D's basis not
  // orthonormal, the point slid along the line where a plane meets the mirror by an amount that grew
  // with the scene's move towards the mirror, and a plane's verdict changed when moved (audit 36b F2)
  const Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic> DtD = D.transpose() * D;
  const Vec3<Q> u = D * Eigen::Matrix<Q, Eigen::Dynamic, 1>(DtD.inverse() * w);
  return Vec3<Q>(b0 - (n.dot(b0) + other(3)) / n.dot(u) * u);
}

}  // namespace

Vec3<Q> item_base(int kind, const Mat4<Q>& A, const Vec4<Q>& other) {
  return quadric_base(A, item_anchor(kind, A, other)).head<3>();
}

namespace {
/// The point an item's seed hashes A and the light or plane about: a point light, else the base the
/// sampler takes (A's core point nearest item_anchor). A and the light or plane about it are the same
/// matrices wherever the item stands (A is the same about every point of its core; a parallel light
/// is a direction; the mirror's plane passes through the point, or is parallel to the core).
Vec3<Q> hash_origin(int kind, const Mat4<Q>& A, const Vec4<Q>& other) {
  if (kind == 1 && other(3) != 0) return Vec3<Q>(other.head<3>() / other(3));
  return item_base(kind, A, other);
}

/// The mirror's plane p of a reflection matrix M = I - 2 n p^T / |n|^2 (n = (p_xyz, 0)): p^T M = -p^T,
/// so p spans the kernel of M^T + I (up to a factor, which item_anchor does not see).
Vec4<Q> mirror_plane(const Mat4<Q>& M) {
  const Eigen::FullPivLU<Mat4<Q>> lu(Mat4<Q>(M.transpose() + Mat4<Q>::Identity()));
  const auto k = lu.kernel();
  return k.cols() == 1 ? Vec4<Q>(k.col(0)) : Vec4<Q>(1, 0, 0, 0);  // (M a reflection: rank 1)
}
}  // namespace

std::uint64_t item_seed(std::uint64_t seed, int kind, const Mat4<Q>& A_given, const Vec4<Q>& other_given) {
  // of A and the light or plane about hash_origin (the same seed wherever the item stands: points that
  // move with it, and so the same object size and verdict; audit 31a F4: a cylinder's sampled size was
  // 42.9 at the origin and 12.1 moved by 10^6, and a candidate 2.5e-8 off passed at one and failed at
  // the other) and of their primitive integer forms (the same for every positive multiple)
  const Vec3<Q> o = hash_origin(kind, A_given, other_given);
  Mat4<Q> T = Mat4<Q>::Identity();
  T.topRightCorner<3, 1>() = o;
  const Mat4<Q> A = T.transpose() * A_given * T;
  Vec4<Q> other = other_given;  // a plane (x -> x + o: its offset grows by n . o) or a point (moves by -o)
  if (kind == 2) {
    other(3) += Vec3<Q>(other_given.head<3>()).dot(o);
    // (p and -p are the same mirror: its first non-zero entry made positive)
    for (int i = 0; i < 4; ++i)
      if (other(i) != 0) {
        if (other(i) < 0) other = -other;
        break;
      }
  } else {
    other.head<3>() -= other_given(3) * o;
  }
  DigitHash f;
  std::array<BigInt, 16> a;
  primitive_integers(A, a);
  f.add_all(a);
  std::array<BigInt, 4> x;
  primitive_integers(other, x);
  f.add_all(x);
  return seed * 1000003ull + static_cast<std::uint64_t>(kind) * 7919ull + f.h;
}

namespace {
/// The points an item's size is measured on where its own sample (fewer than the default count:
/// `--samples 1`) has none, being one point, or is a parallel pair's without its stretch's four ends
/// (the first two chords' roots, the farthest points: fewer than 4 points), and was not exhausted (a
/// terminator of one point, a cone lit from inside, exhausts any larger count, and its default sample
/// spends 3250 attempts): the default count with a seed of its own, as single_point takes, and its
/// own points (which the ball must cover), so that a cylinder's size does not fall to 0 (and every
/// relative error, every bound, to infinity) nor change with the number of samples; a terminator
/// that is one point keeps 0.
std::vector<RootPoint> unsized_sample(const Mat4<Q>& A, const Vec4<Q>& L, const std::vector<RootPoint>& own) {
  std::vector<RootPoint> more = terminator_points(A, L, kDefaultSamples, item_seed(1, 1, A, L)).points;
  more.insert(more.end(), own.begin(), own.end());
  return more;
}
}  // namespace

ItemPoints terminator_points(const Mat4<Q>& A_given, const Vec4<Q>& L_given, int n, std::uint64_t seed) {
  const Mat4<Q> A = canonical_quadric(A_given);
  const Vec4<Q> L = canonical_light(L_given);
  const Vec4<Q> pi = A * L;
  // (no section where pi has no normal: A L = 0, or pi the plane at infinity) The step is rounded down
  // to a power of two: the exact lamp distance has the base's long denominators, and a cone lit from
  // inside, whose sampler spends its every attempt stepping, took seconds on them (a fuzz seed's 1e89
  // apex); a power of two keeps the steps short, and the points still scale with the scene by powers
  // of two exactly, by other factors within 2.
  const std::optional<Vec3<Q>> anchor = item_anchor(1, A, L);
  const Q base_reach =
      pi.head<3>().isZero() ? Q(1) : exact_pow2(floor_log2(reach_length(section_base(A, pi, anchor), L)));
  const SampleReport s = sample_section(A, pi, n, seed, base_reach, anchor);
  ItemPoints out;
  out.points = s.points;
  out.exhausted = s.exhausted;
  Vec3<Q> centre;
  // (where A has no centre, the middle of a stretch the sampler draws: a parabolic cylinder's parallel
  // pair, a parabola, a single line; about it the sample is symmetric or its ends are the farthest,
  // not the sample's centroid, which moved with the seed and count)
  std::optional<Vec3<Q>> core_centre = centre_of_core(A, anchor);
  if (!core_centre) core_centre = s.middle;
  std::tie(out.size, centre) = object_size(out.points, core_centre);
  // one point (no extent), or fewer points than the sample's farthest ends (a parallel pair's four,
  // a hyperbola's two): sized with the default sample as well (unsized_sample)
  if ((out.size == 0 || n < s.ends) && !out.points.empty() && !s.exhausted && n < kDefaultSamples)
    std::tie(out.size, centre) = object_size(unsized_sample(A, L, out.points), core_centre);
  if (!out.points.empty()) {
    const Q u = length_unit(out.size);  // (in units of the sampled size, as the bounds)
    if (const auto whole = terminator_size(object_in_units(A, u), point_in_units(L, u), Vec3<Q>(centre / u)))
      out.size = std::max(out.size, Measure(Measure(*whole) * to_measure(u)));
  }
  out.singular = singular_points(out.points, A);
  out.generator_offsets = generator_offsets(out.points, L, out.size);
  out.generators = generator_points(out.points, out.singular, L, out.generator_offsets);
  const Vec4<Q> h = reference_second_plane(L);
  if (L(3) != 0) out.crossing = common_zeros(out.points, {h});  // (a parallel light's h is the plane at infinity)
  out.plane = plane_points(out.points, Vec4<Q>(A * L), h);
  // (the geometric error is the terminator's alone: R on the polar plane's points is a check of R's
  // shape, measured but not bounded, so the ball need not reach them)
  out.ball = counted_ball(centre, out.size);
  return out;
}

ItemPoints reflected_points(const Mat4<Q>& A_given, const Mat4<Q>& M, int n, std::uint64_t seed) {
  const Mat4<Q> A = canonical_quadric(A_given);
  const Vec4<Q> plane = mirror_plane(M);
  const Vec3<Q> anchor = item_anchor(2, A, plane);
  // (a quadric whose base no line meets, a cone's apex, has no length of its own, and the mirror's
  // distance is not one of A's: unit steps: sampling.hpp, reach_length, says why)
  const SampleReport s = sample_quadric(A, n, seed, Q(1), anchor);
  ItemPoints out;
  out.exhausted = s.exhausted;
  Vec3<Q> centre;
  // (where A has no centre, the middle of the stretch the sampler draws: a paraboloid's, a parabolic
  // cylinder's, a plane's, about which its ends are the farthest points, not the sample's centroid,
  // which moved with the seed)
  std::optional<Vec3<Q>> core_centre = centre_of_core(A, anchor);
  if (!core_centre) core_centre = s.middle;
  std::tie(out.size, centre) = object_size(s.points, core_centre);
  if ((out.size == 0 || n < s.ends) && !s.points.empty() && !s.exhausted && n < kDefaultSamples) {  // (as in terminator_points)
    std::vector<RootPoint> more =
        sample_quadric(A, kDefaultSamples, item_seed(1, 2, A, plane), Q(1), anchor).points;
    more.insert(more.end(), s.points.begin(), s.points.end());
    std::tie(out.size, centre) = object_size(more, core_centre);
  }
  if (!s.points.empty()) {
    const Q u = length_unit(out.size);
    if (const auto whole = ellipsoid_size(object_in_units(A, u))) out.size = std::max(out.size, Measure(Measure(*whole) * to_measure(u)));
  }
  out.ball = counted_ball(centre, out.size);  // of A's points, not yet reflected
  out.points = RootPoint::mapped(s.points, M);
  return out;
}

std::vector<RootPoint> P_points(const std::vector<RootPoint>& local, const ItemPoints& pts) {
  return without(local, pts.singular);
}

std::vector<RootPoint> R_points(const std::vector<RootPoint>& local, const ItemPoints& pts) {
  return without(local, pts.crossing);
}

std::vector<RootPoint> in_frame(const std::vector<RootPoint>& pts, const std::optional<Vec3<Q>>& origin) {
  if (!origin) return pts;
  return RootPoint::mapped(pts, translation<Q>(Vec3<Q>(-*origin)));
}

/// Point k's first-order distance d into the metric; nullopt: the result's gradient vanishes at
/// the point (it lies off the result there: no distance, the metric is singular). A singular
/// point stays the worst.
void add_distance(Metric& m, std::size_t k, const std::optional<Measure>& d) {
  if (d) {
    m.distance = mmax(m.distance, *d);
    if (!m.singular && *d == m.distance) m.worst = k;
  } else {
    if (!m.singular) m.worst = k;
    m.singular = true;
  }
}

namespace {

/// The filter of measure_quadric / measure_plane, in two stages, each only for
/// the points the one before leaves in doubt:
///  1. `certain(k, ...)` from the points' double enclosures (the caller's first
///     loop): cheap, but a point enclosed in doubles loses about as much as a
///     double result's whole residual, so against such a result it rarely
///     certifies anything;
///  2. `refine(k)`: the point's values from its exact integers, enclosed at
///     kRefineBits (root_enclosure.hpp): a few units of the last place of a
///     double wide, enough to tell which points can be the worst.
/// A point is then certain (its distance and residual lie in `dist` and `res`,
/// and it is certainly off the result, with a non-zero gradient and w), exactly
/// on the result, or uncertain. `measure(k)`, the exact measurement rounded to
/// 80 digits, is called in increasing k for the uncertain points and those that
/// can be the worst by distance or by residual; the result equals measuring
/// every point (tests/eval/test_accuracy.cpp).
struct PointFilter {
  enum State : char { certain_off, uncertain, exactly_on };
  std::vector<char> state;
  std::vector<FI> dist, res;
  bool with_residual;
  double dist_floor = -1, res_floor = -1;  ///< largest lower bounds over the certain points

  PointFilter(std::size_t n, bool residual) : state(n, uncertain), dist(n), res(n), with_residual(residual) {}

  /// Point k is certainly off the result (f != 0, the denominators positive) when d and r say so.
  void certain(std::size_t k, const FI& d, const FI& r) {
    if (!positive(d) || (with_residual && !positive(r))) return;
    state[k] = certain_off;
    dist[k] = d, res[k] = r;
    dist_floor = std::max(dist_floor, d.inf());
    if (with_residual) res_floor = std::max(res_floor, r.inf());
  }

  bool in_doubt(std::size_t k) const {
    return state[k] == uncertain ||
           (state[k] == certain_off && (dist[k].sup() >= dist_floor || (with_residual && res[k].sup() >= res_floor)));
  }

  /// Stage 2: refine(k) for every point in doubt; it calls certain(k, ...) or on_result(k), or leaves k uncertain.
  template <class R> void refine(R&& refine) {
    for (std::size_t k = 0; k < state.size(); ++k)
      if (in_doubt(k)) refine(k);
  }
  void on_result(std::size_t k) { state[k] = exactly_on; }

  template <class F> void finish(Metric& m, F&& measure) const {
    for (std::size_t k = 0; k < state.size(); ++k) {
      if (state[k] == exactly_on) continue;  // exactly on it: no distance, no residual
      if (in_doubt(k)) {
        measure(k);
        continue;
      }
      m.all_zero = false;  // certainly off the result, and certainly not the worst
    }
  }
};

/// The precision of the filter's second stage: the direct difference of a value's two parts
/// (root_enclosure.hpp) stays tight unless they agree to about 2^-96 of themselves (a value
/// that nearly vanishes as a number of Q(sqrt d)), so the exact norm, two products of the
/// big integers, is rarely needed.
constexpr mpfr_prec_t kRefineBits = 128;

/// MPFR intervals of the second stage (one set per thread).
struct RefineScratch {
  static constexpr int kCount = 6;
  mpfr_t lo[kCount], hi[kCount];
  BigInt g0, g1, nu, nv, w0, w1;
  RefineScratch() {
    for (int i = 0; i < kCount; ++i) mpfr_init2(lo[i], kRefineBits), mpfr_init2(hi[i], kRefineBits);
  }
  ~RefineScratch() {
    for (int i = 0; i < kCount; ++i) mpfr_clear(lo[i]), mpfr_clear(hi[i]);
  }
  RefineScratch(const RefineScratch&) = delete;
  RefineScratch& operator=(const RefineScratch&) = delete;
  static RefineScratch& get() {
    thread_local RefineScratch s;
    return s;
  }
  /// [lo[i], hi[i]] as a double interval, rounded outwards.
  FI interval(int i) const { return FI(mpfr_get_d(lo[i], MPFR_RNDD), mpfr_get_d(hi[i], MPFR_RNDU)); }
  /// slot i = slot j / slot k (non-negative intervals; i differs from j and k), outwards.
  void quotient(int i, int j, int k) {
    mpfr_div(lo[i], lo[j], hi[k], MPFR_RNDD);
    mpfr_div(hi[i], hi[j], lo[k], MPFR_RNDU);
  }
  /// slot i *= slot j (non-negative intervals), outwards.
  void multiply(int i, int j) {
    mpfr_mul(lo[i], lo[i], lo[j], MPFR_RNDD);
    mpfr_mul(hi[i], hi[i], hi[j], MPFR_RNDU);
  }
  /// A point's first values: |F| = |f0 + f1 sqrt(delta)| into slot 0 and |W| = |x_3| (times
  /// Dp Dv) into slot 1; the enclosure is returned with the point's radicand set, for the rest.
  RootEnclosure& start(const IntegerPoint& x, const BigInt& f0, const BigInt& f1) {
    RootEnclosure& e = thread_root_enclosure(kRefineBits);
    const bool root = !x.rational;
    if (root) e.set_radicand(x.d);
    e.enclose(lo[0], hi[0], f0, f1, root);
    w0 = x.u(3);
    w1 = x.v(3);
    e.enclose(lo[1], hi[1], w0, w1, root);
    return e;
  }
};

/// |x|^2 = (N0 + N1 sqrt(delta)) / (Dp Dv)^2 with N0 = Dv^2 sum P_i^2 + delta Dp^2 sum V_i^2,
/// N1 = 2 Dp Dv sum P_i V_i.
void norm2_parts(const IntegerPoint& x, BigInt& n0, BigInt& n1) {
  BigInt pp, vv, pv;
  for (std::size_t i = 0; i < 4; ++i) {
    pp += x.P[i] * x.P[i];
    if (!x.rational) vv += x.V[i] * x.V[i], pv += x.P[i] * x.V[i];
  }
  n0 = pp * x.Dv * x.Dv + x.d * vv * x.Dp * x.Dp;
  n1 = 2 * pv * x.den();
}

/// |x|^2 to 80 digits: one rounding of an exact value, not four squares of rounded coordinates.
Measure norm2(const IntegerPoint& x) {
  BigInt n0, n1;
  norm2_parts(x, n0, n1);
  const BigInt den = x.den();
  return root_magnitude(n0, n1, x.d, x.root(), BigInt(den * den));
}

FI norm2(const PointEnclosure& X) {
  return CGAL::square(X[0]) + CGAL::square(X[1]) + CGAL::square(X[2]) + CGAL::square(X[3]);
}

/// A point's exact values against an integer matrix Qi (Q = Qi / DQ; integer_point.hpp):
/// x^T Q x = (f0 + f1 sqrt(delta)) / (Dp^2 Dv^2 DQ), (Q x)_i = (y_i Dv + z_i Dp sqrt(delta)) / (Dp Dv DQ).
struct QuadricValues {
  IntegerPoint x;
  BigInt y[4], z[4], f0, f1;
  bool zero;  ///< x^T Q x == 0 exactly

  QuadricValues(const RootPoint& p, const std::array<BigInt, 16>& Qi) : x(p) {
    BigInt a, b, c;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const BigInt& q = Qi[static_cast<std::size_t>(4 * i + j)];
        y[i] += q * x.P[static_cast<std::size_t>(j)];
        if (!x.rational) z[i] += q * x.V[static_cast<std::size_t>(j)];
      }
    }
    for (int i = 0; i < 4; ++i) {  // c = P^T Q V + V^T Q P (Q need not be symmetric)
      const auto u = static_cast<std::size_t>(i);
      a += x.P[u] * y[i];
      if (!x.rational) b += x.V[u] * z[i], c += x.P[u] * z[i] + x.V[u] * y[i];
    }
    f0 = a * x.Dv * x.Dv + x.d * b * x.Dp * x.Dp;
    f1 = c * x.den();
    zero = root_is_zero(f0, f1, x.d, x.square);
  }
};

/// A plane's exact value at a point: pi . x = (f0 + f1 sqrt(delta)) / (Dp Dv Dpi).
struct PlaneValues {
  IntegerPoint x;
  BigInt f0, f1;
  bool zero;

  PlaneValues(const RootPoint& p, const std::array<BigInt, 4>& Pi) : x(p) {
    BigInt a, b;
    for (std::size_t i = 0; i < 4; ++i) {
      a += Pi[i] * x.P[i];
      if (!x.rational) b += Pi[i] * x.V[i];
    }
    f0 = a * x.Dv;
    f1 = b * x.Dp;
    zero = root_is_zero(f0, f1, x.d, x.square);
  }
};

/// Encloses sqrt(v_0^2 + ... + v_{count-1}^2) of integers into slot i of s.
void integer_norm(RefineScratch& s, int i, const BigInt* v, std::size_t count) {
  BigInt sum;
  for (std::size_t j = 0; j < count; ++j) sum += v[j] * v[j];
  enclose_sqrt(s.lo[i], s.hi[i], sum);
}

/// The largest curvatures of a quadric's spatial part K (spatial_part) found upward and downward:
/// u^T K u / |u|^2 over K's eigenvectors (eigen_directions: any direction will do, the values are
/// exact) and the axes; 0 where none curves that way.
struct Curvatures {
  Measure up = 0, down = 0;
};
Curvatures curvatures_of(const Mat4<Q>& Qm) {
  const Mat3<Q> K = spatial_part(Qm);
  std::vector<Vec3<Q>> dirs = {Vec3<Q>(1, 0, 0), Vec3<Q>(0, 1, 0), Vec3<Q>(0, 0, 1)};
  Measure big = 0;  // (scaled to entries near 1 in double, neither overflowing nor underflowing)
  for (Eigen::Index i = 0; i < 9; ++i) big = mmax(big, abs(to_measure(K(i))));
  if (!(big > 0)) return {};
  if (const auto eig = eigen_directions(K.unaryExpr([&](const Q& q) { return Measure(to_measure(q) / big).convert_to<double>(); })))
    for (const Vec3<Q>& u : *eig)
      if (!u.isZero()) dirs.push_back(u);
  Curvatures out;
  for (const Vec3<Q>& u : dirs) {
    const Q c = u.dot(K * u) / u.squaredNorm();
    if (c > 0) out.up = mmax(out.up, to_measure(c));
    if (c < 0) out.down = mmax(out.down, to_measure(Q(-c)));
  }
  return out;
}

/// A point's distances from the quadric, to 80 digits (Metric): the first-order one, none where the
/// gradient or w vanishes; and the second-order one, none where Q does not curve towards it.
struct PointDistances {
  bool zero = false;  ///< on the quadric exactly
  std::optional<Measure> first, second;
  std::optional<Measure> distance() const {
    if (first && second) return mmin(*first, *second);
    return first ? first : second;
  }
};
/// |x^T Q x|, |(Q x)_xyz|^2 and |w| of a point, to 80 digits, from its exact values (Q = Qi / DQ).
struct PointMagnitudes {
  Measure f, g2, w;
};
PointMagnitudes magnitudes(const QuadricValues& v, const BigInt& DQ) {
  const IntegerPoint& x = v.x;
  const BigInt DpDv = x.den();
  PointMagnitudes out;
  out.f = root_magnitude(v.f0, v.f1, x.d, x.root(), BigInt(DpDv * DpDv * DQ));
  const BigInt den = DpDv * DQ;
  out.g2 = 0;
  for (int i = 0; i < 3; ++i) {
    const Measure gi = root_magnitude(BigInt(v.y[i] * x.Dv), BigInt(v.z[i] * x.Dp), x.d, x.root(), den);
    out.g2 += gi * gi;
  }
  out.w = x.magnitude(3);
  return out;
}

PointDistances point_distances(const RootPoint& p, const std::array<BigInt, 16>& Qi, const BigInt& DQ,
                               const Curvatures& k) {
  PointDistances out;
  const QuadricValues v(p, Qi);
  if (v.zero) {
    out.zero = true;
    return out;
  }
  const PointMagnitudes a = magnitudes(v, DQ);
  if (!(a.w > 0)) return out;
  if (a.g2 > 0) out.first = a.f / (a.w * 2 * sqrt(a.g2));
  // Along a unit u with u^T K u = c, Q at the Cartesian point X / w + t u is f + 2 b t + c t^2 (f = x^T Q x
  // / w^2): where c > 0 >= f (or c < 0 <= f) it has a root with |t| <= sqrt(|f| / |c|), whatever b
  const Measure kappa = root_sign(v.f0, v.f1, v.x.d) < 0 ? k.up : k.down;
  if (kappa > 0) out.second = sqrt(a.f / kappa) / a.w;
  return out;
}

/// The metric with each point's distance the smaller of its first- and second-order ones
/// (measure_quadric). The first-order metric `m` is kept where its worst point's second-order distance
/// is not below its first-order one: every other point's smaller distance is then at most the worst's
/// (almost every item: one point evaluated again). Else (a point near where the result's gradient
/// vanishes: a cone's apex, the line where a plane pair crosses, a double plane) every point is
/// measured again, exactly, to 80 digits.
Metric second_order(const Metric& m, const std::vector<RootPoint>& pts, const Mat4<Q>& Qm,
                    const std::array<BigInt, 16>& Qi, const BigInt& DQ) {
  if (m.all_zero || !m.worst || (!m.singular && m.distance == 0)) return m;
  const Curvatures k = curvatures_of(Qm);
  if (!(k.up > 0) && !(k.down > 0)) return m;
  const PointDistances worst = point_distances(pts[*m.worst], Qi, DQ, k);
  if (!m.singular && !(worst.second && *worst.second < m.distance)) return m;
  Metric out;
  out.residual = m.residual;
  out.all_zero = m.all_zero;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const PointDistances d = point_distances(pts[i], Qi, DQ, k);
    if (!d.zero) add_distance(out, i, d.distance());
  }
  return out;
}

}  // namespace

Metric measure_quadric(const std::vector<RootPoint>& pts, const Mat4<Q>& Q_given) {
  // The surface x^T Q x = 0 and its gradient are the symmetric part's: measured with Q x as given, an
  // antisymmetric part (which verify accepts within the target) added S x to the "gradient", and a
  // line's B with no real point passed with its off-diagonal entries moved by 3e-10 (audit 36b F1).
  const Mat4<Q> Qm = symmetric_part(Q_given);
  Metric m;
  const Measure qnorm = frobenius(Qm);
  const bool with_residual = qnorm > 0;
  FI Qe[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) Qe[i][j] = enclosed(Qm(i, j));
  PointFilter filter(pts.size(), with_residual);
  {
    CGAL::Protect_FPU_rounding<true> guard;
    FI q2(0);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) q2 += CGAL::square(Qe[i][j]);
    const FI qn = CGAL::sqrt(q2);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const PointEnclosure& X = pts[k].enclosure();
      FI y[4];
      for (int i = 0; i < 4; ++i) y[i] = Qe[i][0] * X[0] + Qe[i][1] * X[1] + Qe[i][2] * X[2] + Qe[i][3] * X[3];
      const FI f = CGAL::abs(X[0] * y[0] + X[1] * y[1] + X[2] * y[2] + X[3] * y[3]);
      const FI g = CGAL::sqrt(CGAL::square(y[0]) + CGAL::square(y[1]) + CGAL::square(y[2]));
      const FI w = CGAL::abs(X[3]);
      if (!positive(f) || !positive(g) || !positive(w)) continue;
      const FI nx = norm2(X);
      filter.certain(k, f / (w * g * 2), with_residual && positive(nx) ? f / (qn * nx) : FI(0));
    }
  }
  std::array<BigInt, 16> Qi;
  BigInt DQ;
  clear_denominators(Qm, Qi, DQ);
  // Stage 2. With F = f0 + f1 sqrt(delta), W = u_3 + v_3 sqrt(delta), G_i = y_i Dv + z_i Dp sqrt(delta)
  // and N = |x|^2 (Dp Dv)^2 the denominators cancel: distance |F| / (2 |W| |G|), residual |F| / (|Qi| N).
  RefineScratch& s = RefineScratch::get();
  integer_norm(s, 4, Qi.data(), 16);  // |Qi|
  filter.refine([&](std::size_t k) {
    const QuadricValues v(pts[k], Qi);
    if (v.zero) return filter.on_result(k);
    const IntegerPoint& x = v.x;
    const bool root = !x.rational;
    RootEnclosure& e = s.start(x, v.f0, v.f1);  // |F|, |W|
    mpfr_set_ui(s.lo[2], 0, MPFR_RNDD);         // |G|^2
    mpfr_set_ui(s.hi[2], 0, MPFR_RNDU);
    for (int i = 0; i < 3; ++i) {
      s.g0 = v.y[i] * x.Dv;
      if (root) s.g1 = v.z[i] * x.Dp;
      e.add_square(s.lo[2], s.hi[2], s.g0, s.g1, root);
    }
    if (mpfr_zero_p(s.lo[1]) || mpfr_zero_p(s.lo[2]) || mpfr_zero_p(s.lo[0])) return;  // left to the measure
    mpfr_sqrt(s.lo[2], s.lo[2], MPFR_RNDD);
    mpfr_sqrt(s.hi[2], s.hi[2], MPFR_RNDU);
    s.multiply(2, 1);
    mpfr_mul_2si(s.lo[2], s.lo[2], 1, MPFR_RNDD);  // 2 |W| |G|
    mpfr_mul_2si(s.hi[2], s.hi[2], 1, MPFR_RNDU);
    s.quotient(1, 0, 2);  // the distance |F| / (2 |W| |G|)
    if (with_residual) {
      norm2_parts(x, s.nu, s.nv);
      e.enclose(s.lo[3], s.hi[3], s.nu, s.nv, root);  // N
      s.multiply(3, 4);                               // |Qi| N
      s.quotient(5, 0, 3);                            // the residual |F| / (|Qi| N)
    }
    filter.certain(k, s.interval(1), with_residual ? s.interval(5) : FI(0));
  });
  Measure worst_f = 0, worst_g2 = 0;  // |f| and |grad|^2 at the worst point
  filter.finish(m, [&](std::size_t k) {
    const QuadricValues v(pts[k], Qi);
    if (v.zero) return;
    m.all_zero = false;
    const PointMagnitudes a = magnitudes(v, DQ);
    if (with_residual) m.residual = mmax(m.residual, Measure(a.f / (qnorm * norm2(v.x))));
    add_distance(m, k, a.g2 > 0 && a.w > 0 ? std::optional<Measure>(a.f / (a.w * 2 * sqrt(a.g2))) : std::nullopt);
    if (m.worst == k) worst_f = a.f, worst_g2 = a.g2;
  });
  // The second order can beat the first at the worst point only where 4 |grad|^2 < |f| kappa, and every
  // kappa is at most |K|_F: not so at almost every item's worst point, whose measure then stands as it is
  // (the filtered verifier's stage 3 measures one point at a time: a curvature per point cost its
  // reflection row 3.7x)
  if (!m.singular && m.worst && Measure(4 * worst_g2) >= worst_f * frobenius(spatial_part(Qm))) return m;
  return second_order(m, pts, Qm, Qi, DQ);
}

Metric measure_plane(const std::vector<RootPoint>& pts, const Vec4<Q>& pi) {
  Metric m;
  const Measure pn = frobenius(pi), pxyz = frobenius(Vec3<Q>(pi.head<3>()));
  const bool with_residual = pn > 0;
  FI pe[4];
  for (int i = 0; i < 4; ++i) pe[i] = enclosed(pi(i));
  PointFilter filter(pts.size(), with_residual);
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const FI nxyz = CGAL::sqrt(CGAL::square(pe[0]) + CGAL::square(pe[1]) + CGAL::square(pe[2]));
    const FI n = CGAL::sqrt(CGAL::square(pe[0]) + CGAL::square(pe[1]) + CGAL::square(pe[2]) + CGAL::square(pe[3]));
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const PointEnclosure& X = pts[k].enclosure();
      const FI f = CGAL::abs(pe[0] * X[0] + pe[1] * X[1] + pe[2] * X[2] + pe[3] * X[3]);
      const FI w = CGAL::abs(X[3]);
      if (!positive(f) || !positive(nxyz) || !positive(w)) continue;
      const FI nx = CGAL::sqrt(norm2(X));
      filter.certain(k, f / (w * nxyz), with_residual && positive(nx) ? f / (n * nx) : FI(0));
    }
  }
  std::array<BigInt, 4> Pi;
  BigInt Dpi;
  clear_denominators(pi, Pi, Dpi);
  // Stage 2, the denominators cancelled (as in measure_quadric): distance |F| / (|W| |Pi_xyz|),
  // residual |F| / (|Pi| sqrt(N)).
  RefineScratch& s = RefineScratch::get();
  integer_norm(s, 4, Pi.data(), 3);  // |Pi_xyz|
  integer_norm(s, 3, Pi.data(), 4);  // |Pi|
  filter.refine([&](std::size_t k) {
    const PlaneValues v(pts[k], Pi);
    if (v.zero) return filter.on_result(k);
    const IntegerPoint& x = v.x;
    const bool root = !x.rational;
    RootEnclosure& e = s.start(x, v.f0, v.f1);  // |F|, |W|
    if (mpfr_zero_p(s.lo[0]) || mpfr_zero_p(s.lo[1]) || mpfr_zero_p(s.lo[4])) return;  // left to the measure
    s.multiply(1, 4);
    s.quotient(2, 0, 1);  // the distance
    if (with_residual) {
      norm2_parts(x, s.nu, s.nv);
      e.enclose(s.lo[1], s.hi[1], s.nu, s.nv, root);  // N, then sqrt(N) |Pi|
      mpfr_sqrt(s.lo[1], s.lo[1], MPFR_RNDD);
      mpfr_sqrt(s.hi[1], s.hi[1], MPFR_RNDU);
      s.multiply(1, 3);
      s.quotient(5, 0, 1);  // the residual
    }
    filter.certain(k, s.interval(2), with_residual ? s.interval(5) : FI(0));
  });
  filter.finish(m, [&](std::size_t k) {
    const PlaneValues v(pts[k], Pi);
    if (v.zero) return;
    const IntegerPoint& x = v.x;
    m.all_zero = false;
    const Measure fm = root_magnitude(v.f0, v.f1, x.d, x.root(), BigInt(x.den() * Dpi));
    if (with_residual) m.residual = mmax(m.residual, Measure(fm / (pn * sqrt(norm2(x)))));
    const Measure w = x.magnitude(3);
    add_distance(m, k, pxyz > 0 && w > 0 ? std::optional<Measure>(fm / (w * pxyz)) : std::nullopt);
  });
  return m;
}

Measure relative(const Metric& m, const Measure& size) {
  if (m.all_zero) return 0;
  if (!(size > 0)) return m.residual;
  if (m.singular) return std::numeric_limits<Measure>::infinity();
  return m.distance / size;
}

ShadowError shadow_error(const ItemPoints& pts, const std::optional<Vec3<Q>>& origin, const Mat4<Q>& P,
                         const Vec4<Q>& polar, const Mat4<Q>& R) {
  const std::vector<RootPoint> local = in_frame(pts.points, origin);
  ShadowError e;
  e.P = measure_quadric(P_points(local, pts), P);
  e.polar = measure_plane(local, polar);
  e.R = measure_quadric(R_points(local, pts), R);
  for (const Metric* m : {&e.P, &e.polar, &e.R}) e.geometric = mmax(e.geometric, relative(*m, pts.size));
  return e;
}

ReflectionError reflection_error(const ItemPoints& pts, const std::optional<Vec3<Q>>& origin, const Mat4<Q>& B) {
  ReflectionError e;
  e.B = measure_quadric(in_frame(pts.points, origin), B);
  e.geometric = relative(e.B, pts.size);
  return e;
}

Mat4<Q> reference_mirror(const Vec4<Q>& plane) {
  const Q nn = plane(0) * plane(0) + plane(1) * plane(1) + plane(2) * plane(2);
  Mat4<Q> M = Mat4<Q>::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) M(i, j) -= 2 * plane(i) * plane(j) / nn;
  return M;
}


namespace {
double up_to_double(const Measure& e);
}  // namespace

ItemAccuracy item_accuracy(const Measure& geometric, bool has_points, double target) {
  ItemAccuracy acc;
  if (!has_points) {
    acc.reason = "no real point to measure the result on";
  } else if (!(geometric < std::numeric_limits<Measure>::infinity())) {
    acc.reason = "a sampled point lies off the result where its gradient vanishes: no distance of either order";
    acc.inaccurate = true;
  } else {
    acc.bound = up_to_double(Measure(geometric * kBoundMargin));  // (up: a bound stays a bound)
    acc.inaccurate = *acc.bound > target;
    acc.attained = geometric.convert_to<double>();
  }
  return acc;
}

ItemAccuracy non_finite_accuracy() {
  ItemAccuracy acc;
  acc.reason = "non-finite result";
  acc.inaccurate = true;
  return acc;
}

namespace {

/// The meters' rule: the error on the item's points; in the gray zone also on the denser points (sampled once,
/// on first need, and kept); the larger counts.
template <class Error, class Dense>
ItemAccuracy refined_accuracy(const ItemPoints& pts, std::optional<ItemPoints>& dense, const AccuracyOptions& opt,
                              Error error, Dense sample_dense) {
  Measure g = error(pts);
  if (in_gray_zone(g, opt.target)) {  // near the target: measured again on more points
    if (!dense) dense = sample_dense();
    const Measure h = error(*dense);
    if (g < h) g = h;
  }
  return item_accuracy(g, !pts.points.empty(), opt.target);
}

}  // namespace

namespace {
/// How far a Measure may be from the value it stands for, relatively: it is the result of a few
/// 80-digit operations (a square root, quotients, each rounded to nearest), 10^-78 or so. A double
/// within this of a Measure is not known to lie on the safe side of the value, so the roundings
/// below step one more unit in the last place there (an exactly representable size or error loses
/// an ulp it need not: a bound stays a bound).
const Measure kMeasureSlack("1e-70");
}  // namespace

double size_down(const Measure& size) {
  const double d = size.convert_to<double>();
  return Measure(d) > Measure(size * (1 - kMeasureSlack)) ? std::nextafter(d, 0.0) : d;
}

namespace {
/// An error rounded up to a double (a bound stays a bound): size_down's twin.
double up_to_double(const Measure& e) {
  const double d = e.convert_to<double>();
  return Measure(d) < Measure(e * (1 + kMeasureSlack)) ? std::nextafter(d, std::numeric_limits<double>::infinity()) : d;
}

/// Combines a certified bound with the largest sampled error of the same results (the larger counts:
/// CoveredBound::check has checked a first-order bound against them), as it is, and the sampled error
/// of the results it does not cover (times the margin).
ItemAccuracy combined_accuracy(const CertifiedBound& cb, const Measure& sampled_covered, const Measure& sampled_other,
                               std::vector<std::string> certified, double target) {
  // (checked part by part before, CoveredBound::check; a bound of the Euclidean distance near a point
  // where the reference's gradient vanishes may be below a first-order distance sampled there, which
  // means nothing: both count)
  ItemAccuracy acc;
  acc.certified = std::move(certified);
  acc.attained = std::max({Measure(cb.attained), sampled_covered, sampled_other}).convert_to<double>();
  const Measure bound = std::max({Measure(cb.upper), sampled_covered, Measure(sampled_other * kBoundMargin)});
  if (!(bound < std::numeric_limits<Measure>::infinity())) {
    std::ostringstream r;
    r << "no finite bound: near its geometry the result's gradient may vanish (a first-order distance of "
      << std::setprecision(3) << cb.attained << " of the object's size is attained)";
    acc.reason = r.str();
    acc.inaccurate = true;
    return acc;
  }
  acc.bound = up_to_double(bound);
  acc.inaccurate = *acc.bound > target;
  return acc;
}

}  // namespace

namespace {
/// Does the plane h meet the ball (|h . (c, 1)| <= reach |h_xyz|, exactly)?
bool crosses(const Vec4<Q>& h, const Ball& b) {
  const Q at = Vec3<Q>(h.head<3>()).dot(b.centre) + h(3);
  return at * at <= b.reach * b.reach * Q(h.head<3>().squaredNorm());
}
}  // namespace

ShadowBounds::ShadowBounds(const Mat4<Q>& A_world, const Vec4<Q>& L_world, const ItemPoints& pts)
    : unit_(length_unit(pts.size)) {
  if (pts.points.empty() || pts.exhausted) return;
  // in units of the object's size (length_unit), as the results are bounded (operator()); the
  // generator offsets rho are the same there (x + rho (L_xyz - L_w x) scales as x)
  const Mat4<Q> A = object_in_units(canonical_quadric(A_world), unit_);
  const Vec4<Q> L = point_in_units(canonical_light(L_world), unit_);
  pi_ref_ = A * L;
  const Measure pi_norm = sqrt(to_measure(Q(pi_ref_.head<3>().squaredNorm())));
  h_ = reference_second_plane(L);
  R_ref_ = reference_plane_pair(A, L);
  // where h crosses a ball, R's planes cross there, and R is bounded as a plane pair (R_ball_bound)
  const bool R_crossing = saddle_directions(R_ref_).has_value();
  geo_ = shadow_geometry(A, L);
  const auto split_in_ball = [&] {
    split_ = crossing_split(A, L, ball_);
    if (split_) split_floor_ = split_->floor * pi_norm;
  };
  if (geo_) {
    if (geo_->R_ball) ball_ = *geo_->R_ball;  // (the whole terminator: not the sampled points' ball)
    cover_ = {true, true, geo_->R_floor > 0 || (geo_->R_ball && (!crosses(h_, *geo_->R_ball) || R_crossing))};
    if (geo_->R_ball && crosses(h_, ball_)) split_in_ball();
    return;
  }
  ball_ = ball_in_units(pts.ball, unit_);
  const Measure reach = to_measure(ball_.reach);
  const Q s = L.dot(pi_ref_);
  P_ref_ = reference_cone(A, L);
  // on the terminator (P_ref x)_xyz = s (A x)_xyz
  P_floor_ = terminator_gradient_floor(A, pi_ref_, ball_, s);
  P_slopes_ = terminator_saddle_slopes(A, pi_ref_, ball_, s, P_ref_);
  // on the terminator (R_ref x)_xyz = (h . x) pi_xyz. (Under a parallel light h . x = 1 at every
  // point, the constant floor plane_pair_floor gives R_ball_bound's one step as well: not taken twice.)
  const std::optional<Measure> hf = L(3) != 0 ? terminator_h_floor(A, L, &ball_) : std::nullopt;
  if (hf) R_floor_ = *hf * pi_norm;
  if (!hf && crosses(h_, ball_)) split_in_ball();
  cover_ = {P_floor_(0, reach) > 0 || saddle_directions(P_ref_).has_value(), true,
            !crosses(h_, ball_) || R_crossing || R_floor_ > 0};
}

CoveredBound ShadowBounds::operator()(const std::optional<Vec3<Q>>& origin_world, const Mat4<Q>* P_world,
                                      const Vec4<Q>* polar_world, const Mat4<Q>* R_world, double size_world,
                                      double target) const {
  // the results, their frame and the size in the constructor's units (length_unit)
  const std::optional<Vec3<Q>> origin = origin_in_units(origin_world, unit_);
  const auto in_units = [&](const Mat4<Q>* X) { return X ? std::optional<Mat4<Q>>(quadric_in_units(*X, unit_)) : std::nullopt; };
  const std::optional<Mat4<Q>> P_units = in_units(P_world), R_units = in_units(R_world);
  const std::optional<Vec4<Q>> polar_units =
      polar_world ? std::optional<Vec4<Q>>(plane_in_units(*polar_world, unit_)) : std::nullopt;
  const Mat4<Q>* P = P_units ? &*P_units : nullptr;
  const Mat4<Q>* R = R_units ? &*R_units : nullptr;
  const Vec4<Q>* polar = polar_units ? &*polar_units : nullptr;
  const double size = size_in_units(size_world, unit_);
  CoveredBound out;
  const auto add = [&](const CertifiedBound& b, const char* name) {
    out.bound = combined(out.bound, b);
    out.certified.emplace_back(name);
    out.parts.push_back({{name}, b});
  };
  if (geo_) {
    if (P || polar) {
      out.bound = shadow_bound(*geo_, origin, P, polar, size, target);
      out.parts.push_back({{}, out.bound});
    }
    if (P) out.certified.emplace_back("P"), out.parts.back().names.emplace_back("P");
    if (polar) out.certified.emplace_back("polar_plane"), out.parts.back().names.emplace_back("polar_plane");
    // where h meets the terminator, R in the ball about the whole of it (ShadowGeometry::R_ball)
    if (R && cover_.R)
      add(geo_->R_floor > 0 ? *terminator_quadric_bound(*geo_, origin, *R, size, target) : R_ball_bound(*R, origin, size),
          "R");
    return out;
  }
  if (P && cover_.P)
    add(ball_quadric_bound(*P, P_ref_, ball_, origin, P_floor_, size, false, &pi_ref_, P_slopes_ ? &*P_slopes_ : nullptr),
        "P");
  if (polar && cover_.polar) add(ball_plane_bound(*polar, pi_ref_, ball_, origin, size), "polar_plane");
  if (R && cover_.R) add(R_ball_bound(*R, origin, size), "R");
  return out;
}

CertifiedBound ShadowBounds::R_ball_bound(const Mat4<Q>& R, const std::optional<Vec3<Q>>& origin, double size) const {
  // Each bound holds over the terminator in the ball (the one and two steps over all of the polar plane
  // in it); the smallest counts.
  const auto smaller = [](const CertifiedBound& a, const CertifiedBound& b) { return b.upper < a.upper ? b : a; };
  std::optional<CertifiedBound> best;
  const auto take = [&](const CertifiedBound& b) { best = best ? smaller(*best, b) : b; };
  // R against R_ref in one step, to first order, with a constant floor of R_ref's gradient
  const auto one_step = [&](const Measure& floor) {
    return ball_quadric_bound(R, R_ref_, ball_, origin, [floor](const Measure&, const Measure&) { return floor; }, size,
                              false, &pi_ref_);
  };
  // Where h . x keeps away from 0 on the terminator, R_ref's gradient there does too (R_floor_): the
  // line where R's planes cross may pass through the ball, off the terminator, where a rounded R is
  // truly about sqrt(eps) off, but no terminator point is near it (a hyperbolic paraboloid's R was
  // flagged at 6.7e-9 there, 1.3e-16 off on the terminator: audit 31a F2).
  if (R_floor_ > 0) take(one_step(R_floor_));
  // As a plane pair in two steps, a bound of the Euclidean distance (which the line where R's planes
  // cross, in the ball, needs: no first-order distance is bounded near it).
  const CertifiedBound pair = ball_plane_pair_bound(R, pi_ref_, h_, ball_, origin, size);
  // Where h . x = 0 meets the terminator in the ball: first order outside small balls about those
  // points (|h . x| has a floor there), as a plane pair inside each, about its crossing point
  if (split_) {
    CertifiedBound b = one_step(split_floor_);
    for (const Ball& near : split_->near) b = combined(b, ball_plane_pair_bound(R, pi_ref_, h_, near, origin, size));
    take(b);
  }
  if (crosses(h_, ball_)) {
    take(pair);
    return *best;
  }
  // h misses the ball: R's reference gradient on the polar plane is (h . x) pi_xyz, and R is bounded
  // against R_ref in one step, to first order, with a floor G of |(hat x)_xyz| on the terminator in the
  // ball. The two steps' Euclidean delta is tighter where h passes near the ball (the one step divides
  // the value's largest over a shell by the gradient's smallest, and |h . x| spans 0 to the ball's
  // width there: a cylinder's R moved by 3e-10 of its size was bounded at 1.2e-9), and it bounds the
  // first-order distance too, once made one: with y a point of hat's zero set within delta of x,
  // f(x) = grad f(x) . v - v^T H v (v = x - y, grad f = 2 (hat x)_xyz), so |f(x)| / |grad f(x)| <=
  // delta + |H|_F delta^2 / (2 |(hat x)_xyz|), the one step's floor of |(hat x)_xyz| / |H|_F giving the
  // last (CertifiedBound::gradient). (Taken as it was, a Euclidean bound where the first-order
  // distance exists let that exceed it: review of session 31.)
  const CertifiedBound one = ball_quadric_bound(R, R_ref_, ball_, origin, plane_pair_floor(pi_ref_, h_, ball_), size,
                                                false, &pi_ref_);
  take(one);
  if (one.gradient > 0 && std::isfinite(pair.upper) && size > 0) {
    CertifiedBound first = pair;
    first.euclidean = false;
    const Measure d = Measure(pair.upper) * Measure(size);  // (relative bounds: times the size, a length)
    const Measure g = std::isfinite(one.gradient) ? Measure(one.gradient) : Measure(0);
    const Measure grown = g > 0 ? Measure(d + d * d / (2 * g)) : d;
    first.upper = up_to_double(Measure(grown / Measure(size)) * (1 + kMeasureSlack));
    take(first);
  }
  return *best;
}

namespace {
/// A quadric in coordinates x' with x = turn x' (a rotation): T^T X T, T = diag(turn, 1).
Mat4<Q> turned(const Mat4<Q>& X, const Mat3<Q>& turn) {
  Mat4<Q> T = Mat4<Q>::Identity();
  T.topLeftCorner<3, 3>() = turn;
  return T.transpose() * X * T;
}
}  // namespace

ReflectionBounds::ReflectionBounds(const Mat4<Q>& A_world, const Mat4<Q>& M_world, const ItemPoints& pts)
    : unit_(length_unit(pts.size)) {
  if (pts.points.empty() || pts.exhausted) return;
  // in units of the object's size (length_unit), as B is bounded (operator())
  const Mat4<Q> A = object_in_units(canonical_quadric(A_world), unit_), M = map_in_units(M_world, unit_);
  const Ball ball = ball_in_units(pts.ball, unit_);
  geo_ = reflection_geometry(A, M);
  if (geo_) return;
  B_ref_ = M.transpose() * A * M;
  // (B_ref M x)_xyz = H^T (A x)_xyz with H, M's linear part, orthogonal: A's floor in its ball holds
  // for B in the reflected ball
  floor_ = GradientFloor(A, ball);
  floored_ = floor_(0, to_measure(ball.reach)) > 0 || saddle_directions(B_ref_).has_value();
  // (the mirror turns the axes: a box, where the ball had one, is not carried)
  ball_ = {Vec3<Q>(Vec4<Q>(M * Vec4<Q>(ball.centre(0), ball.centre(1), ball.centre(2), Q(1))).head<3>()), ball.reach, std::nullopt};
  turned_ = cylinder_turn(B_ref_, ball_);
  if (turned_) B_ref_turned_ = turned(B_ref_, turned_->turn);
}

CoveredBound ReflectionBounds::operator()(const std::optional<Vec3<Q>>& origin_world, const Mat4<Q>& B_world,
                                          double size_world, double target) const {
  CoveredBound out;
  if (!covers()) return out;
  // B, its frame and the size in the constructor's units (length_unit)
  const std::optional<Vec3<Q>> origin = origin_in_units(origin_world, unit_);
  const Mat4<Q> B = quadric_in_units(B_world, unit_);
  const double size = size_in_units(size_world, unit_);
  if (geo_)
    out.bound = reflection_bound(*geo_, origin, B, size, target);
  else if (turned_)  // (x = turn x': the frame's origin o is turn o' there)
    out.bound = ball_quadric_bound(turned(B, turned_->turn), B_ref_turned_, turned_->ball,
                                   origin ? std::optional<Vec3<Q>>(Vec3<Q>(turned_->turn.transpose() * *origin)) : std::nullopt,
                                   floor_, size);
  else
    out.bound = ball_quadric_bound(B, B_ref_, ball_, origin, floor_, size);
  out.certified = {"B"};
  out.parts = {{{"B"}, out.bound}};
  return out;
}

void CoveredBound::check(const std::function<Measure(const std::string&)>& sampled) const {
  for (const Part& p : parts) {
    if (p.bound.euclidean) continue;
    for (const std::string& n : p.names)
      if (sampled(n) > Measure(p.bound.upper))
        throw std::logic_error("certified error bound " + Measure(p.bound.upper).str(6) + " of " + n +
                               " below an error measured on an exact point (" + sampled(n).str(6) +
                               "): a bug in the bound");
  }
}

const std::vector<Vec4<Q>>& sign_probes() {
  static const std::vector<Vec4<Q>> ys = [] {
    std::vector<Vec4<Q>> out;
    for (int i = 0; i < 4; ++i) {
      out.push_back(Vec4<Q>::Unit(i));
      for (int j = i + 1; j < 4; ++j) {
        out.push_back(Vec4<Q>(Vec4<Q>::Unit(i) + Vec4<Q>::Unit(j)));
        out.push_back(Vec4<Q>(Vec4<Q>::Unit(i) - Vec4<Q>::Unit(j)));
      }
    }
    return out;
  }();
  return ys;
}

bool same_sign_as(const Mat4<Q>& got, const std::function<Q(const Vec4<Q>&)>& ref) {
  Q best = 0;
  Vec4<Q> at = Vec4<Q>::Zero();
  for (const Vec4<Q>& y : sign_probes()) {
    const Q r = ref(y);
    if (abs_of<Q>(r) > abs_of<Q>(best)) best = r, at = y;
  }
  if (best == 0) return true;
  return sign_of<Q>(form(got, at)) == sign_of<Q>(best);
}

std::vector<std::string> shadow_sign_problems(const Mat4<Q>& A, const Vec4<Q>& L, const Mat4<Q>* P, const Vec4<Q>* polar) {
  std::vector<std::string> out;
  const Vec4<Q> pi = A * L;
  const Q s = L.dot(pi);
  if (P && !same_sign_as(*P, [&](const Vec4<Q>& y) { const Q t = pi.dot(y); return Q(s * form(A, y) - t * t); }))
    out.emplace_back("P has the wrong sign or vanishes where (L^T A L) A - (A L)(A L)^T does not (the contract fixes "
                     "that matrix up to a positive factor)");
  if (polar && !pi.isZero() && !same_orientation(*polar, pi))
    out.emplace_back("polar_plane has the wrong orientation (must be A L up to a positive factor)");
  return out;
}

Measure mirror_error(const Mat4<Q>& M, const Mat4<Q>& M_ref) {
  return to_measure(max_abs(Mat4<Q>(M - M_ref))) / mmax(Measure(1), to_measure(max_abs(M_ref)));
}

Measure second_plane_error(const std::vector<RootPoint>& local, const Measure& size, const Mat4<Q>& A, const Vec4<Q>& L,
                           const Mat4<Q>& R, bool& all_zero) {
  all_zero = true;
  const Vec4<Q> pi = A * L;
  if (pi.head<3>().isZero() ||
      std::none_of(local.begin(), local.end(), [](const RootPoint& x) { return x.p()(3) != 0; }))
    return 0;
  Q step = to_rational(size.convert_to<double>());
  if (step == 0) step = 1;  // a terminator of one point (size 0): unit steps, each distance over the point's own
  const Measure inf = std::numeric_limits<Measure>::infinity();
  if (L(3) == 0) {
    // A parallel light: h is the plane at infinity, where R is its spatial block R3 (of its symmetric
    // part Rs: an antisymmetric one is no quadric's). A plane pair pi h'^T + h' pi^T with h' = (e, 1)
    // has R3 = n e^T + e n^T (pi = (n, d)) and, at a point x of the terminator (on pi), a gradient
    // (Rs x)_xyz = (h' . x) n: h' lies about 1 / |e| away, an angle of size |e| seen from an object of
    // that size, as the point light's measure with its points at infinity. So |R3|_F size / (2
    // min_x |(Rs x)_xyz|) over the sampled terminator points x: the same in any units, placement and
    // turn (the relative residual |d^T R d| / (|R|_F |d|^2) it replaced went as 1 / scale^2: an R 0.8
    // targets off failed scaled by 1e-4, one with h' 1e3 away passed scaled by 1e4; audit 37a F1). (Not
    // at `inside`: under a parallel light that point is the core's nearest the frame's origin, which a
    // candidate chooses: a cylinder's R with h' through the terminator passed with its origin 1e12 up
    // the axis; review of 29fa6a5: nor computed here.) A terminator of one point has no length:
    // `step`, unit steps, as for a point light.
    const Mat4<Q> Rs = symmetric_part(R);
    const Mat3<Q> R3 = Rs.topLeftCorner<3, 3>();
    if (R3.isZero()) return 0;
    all_zero = false;
    Mat4<Measure> Rm;
    for (Eigen::Index i = 0; i < 16; ++i) Rm(i) = to_measure(Rs(i));
    std::optional<Measure> least;
    for (const RootPoint& x : local) {
      if (IntegerPoint(x).coordinate(3) == 0) continue;  // (at infinity)
      const Vec3<Measure> c = cartesian(x);
      const Measure gn = sqrt(Vec4<Measure>(Rm * Vec4<Measure>(c(0), c(1), c(2), Measure(1))).head<3>().squaredNorm());
      if (!least || gn < *least) least = gn;
    }
    if (!least || *least == 0) return inf;
    return sqrt(to_measure(Q((R3 * R3).trace()))) * to_measure(step) / (2 * *least);
  }
  // A rational point at the object, of A and L alone, not of the samples: the section's centre, where
  // the sampler's chords all cross (sampling.hpp), else a point of the polar plane at A's core (a
  // parallel pair's chords cross at its middle, on the same midline for a cylinder). (The
  // first chord's midpoint, taken before, moved with the seed for a parabola's terminator; `size` still
  // does where the terminator is not a real ellipse.)
  const Vec4<Q> inside = section_base(A, pi, item_anchor(1, A, L));
  const Vec3<Q> at_inside = Vec3<Q>(inside.head<3>()) / inside(3);
  Measure worst = 0;
  std::vector<Vec4<Q>> ys;
  const Vec4<Q> base(at_inside(0), at_inside(1), L(2) / L(3), 1);
  // Each distance is divided by the point's distance from `inside` (an angle), so the step, which
  // keeps the points off the line where R's planes cross and spreads them over h, must grow with
  // it: never below the height of h over `inside`, nor below the distance of `base` from that line
  // (|pi . base| / |n|_max). With the object size alone, a light 4e29 away put the points 5 units
  // from the line, 1e-29 of their distance: a correctly rounded double R measured 0.77 there.
  step = std::max(step, abs_of<Q>(Q(base(2) - at_inside(2))));
  const Q nx = pi(0), ny = pi(1), nn = nx * nx + ny * ny;
  if (nn == 0) {
    ys = {base, Vec4<Q>(base + Vec4<Q>(step, 0, 0, 0)), Vec4<Q>(base + Vec4<Q>(0, step, 0, 0))};
  } else {
    // With step >= |pi . base| / nmax the points lie at least step / sqrt(2) from the line and at most
    // about 4.5 steps from `inside`: a fixed fraction of their distance, whatever the light's.
    const Q nmax = std::max(abs_of<Q>(nx), abs_of<Q>(ny)), at = pi.dot(base);
    step = std::max(step, Q(abs_of<Q>(at) / nmax));
    for (const Q& target : {Q(step * nmax), Q(-step * nmax)}) {
      const Q t = (target - at) / nn;  // pi . (base + t (n, 0)) = target
      ys.push_back(Vec4<Q>(base + t * Vec4<Q>(nx, ny, 0, 0)));
    }
    ys.push_back(Vec4<Q>(ys[0] + (step / nmax) * Vec4<Q>(-ny, nx, 0, 0)));  // along the line: pi . y unchanged
  }
  const Curvatures k = curvatures_of(R);
  for (const Vec4<Q>& y : ys) {
    const Q f = form(R, y);
    if (f == 0) continue;
    all_zero = false;
    const Measure fm = abs(to_measure(f));
    // the distance as the geometric error takes it: first-order, or second-order sqrt(|f| / kappa)
    // where smaller (near where R's gradient vanishes a first-order quotient is no distance: a light
    // on a sphere's surface 1e12 away measured 2.39; audit 31b F5)
    const Vec4<Q> g = R * y;
    const Measure gn = sqrt(to_measure(Q(g.head<3>().squaredNorm())));
    const Measure kappa = f < 0 ? k.up : k.down;
    Measure d = gn > 0 ? Measure(fm / (2 * gn)) : inf;
    if (kappa > 0) d = mmin(d, sqrt(fm / kappa));
    const Measure dist = sqrt(to_measure(Q((Vec3<Q>(y.head<3>()) - at_inside).squaredNorm())));
    worst = mmax(worst, d == inf ? inf : Measure(d / mmax(size, dist)));
  }
  return worst;
}

std::string reflection_sign_problem(const Mat4<Q>& B, const Mat4<Q>& B_ref) {
  if (same_sign_as(B, [&](const Vec4<Q>& y) { return form(B_ref, y); })) return "";
  return "B has the wrong sign or vanishes where M^T A M does not (must be M^T A M up to a positive factor)";
}

namespace {
/// Every point rational and proportional to the first (false for none).
bool all_one_point(const std::vector<RootPoint>& xs) {
  if (xs.empty()) return false;
  for (const RootPoint& x : xs)
    if ((x.delta() != 0 && !x.q().isZero()) || cross_residual(x.p(), xs.front().p()) != 0) return false;
  return true;
}
}  // namespace

bool single_point(const Mat4<Q>& A, const Vec4<Q>& L, const std::vector<RootPoint>& terminator) {
  if (!all_one_point(terminator)) return false;  // (two points, or an irrational one: decided)
  if (terminator.size() >= static_cast<std::size_t>(kDefaultSamples)) return true;
  // Fewer samples (verify --samples 1 found a cone's apex first, where its terminator is a line pair):
  // the default count, with a seed of its own, so that the answer does not depend on --samples or --seed.
  return all_one_point(terminator_points(A, L, kDefaultSamples, item_seed(1, 1, A, L)).points);
}

Vec3<Q> reflected_item_base(const Mat4<Q>& A, const Vec4<Q>& plane, const std::optional<Vec3<Q>>& origin) {
  Vec4<Q> b;
  b << item_base(2, A, plane), Q(1);
  return Vec3<Q>(Vec4<Q>(reference_mirror(plane) * b).head<3>() - (origin ? *origin : Vec3<Q>::Zero()));
}

namespace {
/// Results and their references in the frame x = o + l y (own_frame), compared there up to scale
/// (cross_residual).
struct ItemFrame {
  Mat4<Q> T;
  ItemFrame(const Vec3<Q>& o, const Q& l) : T(own_frame(o, l)) {}
  Measure error(const Mat4<Q>& hat, const Mat4<Q>& ref) const {
    return to_measure(cross_residual(Mat4<Q>(T.transpose() * hat * T), Mat4<Q>(T.transpose() * ref * T)));
  }
  Measure error(const Vec4<Q>& hat, const Vec4<Q>& ref) const {
    return to_measure(cross_residual(Vec4<Q>(T.transpose() * hat), Vec4<Q>(T.transpose() * ref)));
  }
};
}  // namespace

Measure reflection_matrix_error(const Mat4<Q>& B, const Mat4<Q>& B_ref, const Vec3<Q>& base) {
  return ItemFrame(base, Q(1)).error(B, B_ref);  // about the item's base point (shadow_matrix_error says why)
}

Measure shadow_matrix_error(const Mat4<Q>& A, const Vec4<Q>& L, const Mat4<Q>* P, const Vec4<Q>* polar, const Mat4<Q>* R,
                            const Vec3<Q>& base) {
  // In the item's own frame, x = o + l y: o the item's base point (item_base, in the results' frame),
  // l the light's L-infinity distance from it (1, the scene's unit, for a parallel light or a lamp
  // at the base). Relative to the largest entry in the results' frame, the residual shrank with the
  // scene's distance from the origin (entries growing with its square): a cone's P 0.01 off at its
  // apex failed at 8.3e-3 at the origin and passed at 1.4e-15 moved by 10^6 (audit 32a F2).
  const std::optional<Vec3<Q>> light = L(3) != 0 ? std::optional<Vec3<Q>>(Vec3<Q>(L.head<3>() / L(3))) : std::nullopt;
  const Vec3<Q>& o = base;
  Q l = light ? max_abs(Vec3<Q>(*light - o)) : Q(1);
  if (l == 0) l = 1;
  const ItemFrame frame(o, l);
  Measure e = 0;
  if (P) e = mmax(e, frame.error(*P, reference_cone(A, L)));
  if (polar) e = mmax(e, frame.error(*polar, Vec4<Q>(A * L)));
  if (R) e = mmax(e, frame.error(*R, reference_plane_pair(A, L)));
  return e;
}

std::vector<std::string> shadow_zero_problems(const Mat4<Q>& A, const Vec4<Q>& L, const Mat4<Q>* P, const Vec4<Q>* polar,
                                              const Mat4<Q>* R) {
  std::vector<std::string> out;
  const Vec4<Q> pi = A * L;
  if (P && P->isZero() != reference_cone(A, L).isZero())
    out.emplace_back("P is zero where it should not be (or the converse)");
  if (polar && polar->isZero() != pi.isZero())
    out.emplace_back("the polar plane is zero where it should not be (or the converse)");
  if (R && R->isZero() != pi.isZero())  // R = pi h^T + h pi^T, h != 0
    out.emplace_back("R is zero where it should not be (or the converse)");
  return out;
}

std::string reflection_zero_problem(const Mat4<Q>& A, const Mat4<Q>& B) {
  return B.isZero() != A.isZero() ? "B is zero where it should not be (or the converse)" : "";
}

std::string reflection_real_points_problem(const Mat4<Q>& A, const Mat4<Q>& B) {
  if (!without_real_points(A) || without_real_points(symmetric_part(B))) return "";
  return "B has real points, where M^T A M has none (the quadric has no real point)";
}

namespace {
/// A result of the wrong sign or wrongly zero: wrong whatever its geometric error (which sees neither).
ItemAccuracy wrong_result(const std::string& problem) {
  ItemAccuracy acc;
  acc.reason = problem + ": no error bound is given";
  acc.inaccurate = true;
  return acc;
}

/// An error measured exactly (shadow_matrix_error) as the item's bound, rounded up to a double.
ItemAccuracy measured_exactly(const Measure& e, std::vector<std::string> certified, double target) {
  ItemAccuracy acc;
  acc.certified = std::move(certified);
  acc.attained = e.convert_to<double>();
  acc.bound = up_to_double(e);
  acc.inaccurate = *acc.bound > target;
  return acc;
}
}  // namespace

ShadowMeter::ShadowMeter(const Mat4<Q>& A, const Vec4<Q>& L, const AccuracyOptions& opt)
    : A_(A), L_(L), opt_(opt), pts_(terminator_points(A, L, opt.samples, item_seed(opt.seed, 1, A, L))),
      bounds_(A, L, pts_) {}

ItemAccuracy ShadowMeter::operator()(const std::optional<Vec3<Q>>& origin, const Mat4<Q>& P, const Vec4<Q>& polar,
                                     const Mat4<Q>& R) {
  const Vec3<Q> o = origin ? *origin : Vec3<Q>::Zero();
  const Mat4<Q> Ae = quadric_to_local(A_, o);
  const Vec4<Q> Le = point_to_local(L_, o);
  if (const auto sign = shadow_sign_problems(Ae, Le, &P, &polar); !sign.empty()) return wrong_result(sign.front());
  if (const auto zero = shadow_zero_problems(Ae, Le, &P, &polar, &R); !zero.empty()) return wrong_result(zero.front());
  // Measured against the exact ones as matrices (their largest cross residual): a terminator of one
  // point, which says nothing of their shapes, and one whose real points all lie at infinity (a
  // cylinder lit from inside: its axis's direction; an imaginary cylinder's), with no finite point to
  // measure a distance at, so that a result far off is flagged there too (a paper-route polar plane
  // z = 158.6 for the plane y = 1e15 + 4 had no bound and no flag: audit 30a F3). A terminator without
  // any real point keeps none (no-real-silhouette). (R's error on h, which the cross residual, relative
  // to the largest entry, may not see (a cone lit from 1e12 along its axis: h 2e-8 of its height off in
  // float), is verify's check of R's shape, R_on_second_plane, not counted here.)
  if ((pts_.points.empty() && silhouette_empty<Q>(A_, L_) == Truth::no) || single_point(A_, L_, pts_.points))
    return measured_exactly(shadow_matrix_error(Ae, Le, &P, &polar, &R, Vec3<Q>(item_base(1, A_, L_) - o)),
                            {"P", "polar_plane", "R"}, opt_.target);
  // The geometric error of P, the polar plane and R on the terminator (cli.md), not verify's checks of
  // their shapes beyond it (P on its generator lines, R on the polar plane and on h: ShadowBounds).
  auto dense = [&] { return terminator_points(A_, L_, opt_.samples * kRefineFactor, item_seed(opt_.seed + 1, 1, A_, L_)); };
  const ShadowCover& c = bounds_.cover();
  if (!c.P && !c.polar && !c.R)
    return refined_accuracy(pts_, dense_, opt_,
                            [&](const ItemPoints& p) { return shadow_error(p, origin, P, polar, R).geometric; }, dense);
  const ShadowError e = shadow_error(pts_, origin, P, polar, R);  // once: both parts are read from it
  const auto sampled = [](const ShadowError& err, const Measure& size) {
    return [p = &err, size](const std::string& name) {  // (err: the caller's, alive while this is used)
      if (name == "P") return relative(p->P, size);
      if (name == "polar_plane") return relative(p->polar, size);
      return relative(p->R, size);  // "R"
    };
  };
  // (a part whose bound is not finite, a result so far off that its gradient bound is swamped, leaves
  // the item without a bound: flagged, with a reason)
  const CoveredBound b = bounds_(origin, &P, &polar, &R, size_down(pts_.size), opt_.target);
  b.check(sampled(e, pts_.size));
  const auto has = [&](const char* n) { return std::find(b.certified.begin(), b.certified.end(), n) != b.certified.end(); };
  // What a bound covers counts its certified bound and its sampled errors; the rest its errors on samples.
  const auto uncovered = [&](const ShadowError& err, const Measure& size) {
    const auto at = sampled(err, size);
    Measure r = 0;
    for (const char* n : {"P", "polar_plane", "R"})
      if (!has(n)) r = std::max(r, at(n));
    return r;
  };
  Measure covered = 0;
  for (const std::string& n : b.certified) covered = std::max(covered, sampled(e, pts_.size)(n));
  Measure other = uncovered(e, pts_.size);
  if (in_gray_zone(other, opt_.target)) {
    if (!dense_) dense_ = dense();
    const ShadowError d = shadow_error(*dense_, origin, P, polar, R);
    other = std::max(other, uncovered(d, dense_->size));
  }
  return combined_accuracy(b.bound, covered, other, b.certified, opt_.target);
}

ReflectionMeter::ReflectionMeter(const Mat4<Q>& A, const Vec4<Q>& plane, const AccuracyOptions& opt)
    : A_(A), M_(reference_mirror(plane)), plane_(plane), opt_(opt),
      pts_(reflected_points(A, M_, opt.samples, item_seed(opt.seed, 2, A, plane))), bounds_(A, M_, pts_) {}

ItemAccuracy ReflectionMeter::operator()(const std::optional<Vec3<Q>>& origin, const Mat4<Q>& B, const Mat4<Q>* M) {
  ItemAccuracy acc = B_accuracy(origin, B);
  if (!M) return acc;
  // M against the exact reflection in the item's frame (M_local = T^-1 M T), as verify judges it
  const Vec3<Q> o = origin ? *origin : Vec3<Q>::Zero();
  const Measure e = mirror_error(*M, Mat4<Q>(translation<Q>(Vec3<Q>(-o)) * M_ * translation<Q>(o)));
  const double up = up_to_double(e);
  if (acc.bound) acc.certified.emplace_back("M");
  acc.attained = std::max(acc.attained, e.convert_to<double>());
  if (acc.bound) acc.bound = std::max(*acc.bound, up);
  acc.inaccurate = acc.inaccurate || up > opt_.target;
  return acc;
}

ItemAccuracy ReflectionMeter::B_accuracy(const std::optional<Vec3<Q>>& origin, const Mat4<Q>& B) {
  const Mat4<Q> B_ref = quadric_to_local(Mat4<Q>(M_.transpose() * A_ * M_), origin ? *origin : Vec3<Q>::Zero());
  if (const std::string sign = reflection_sign_problem(B, B_ref); !sign.empty()) return wrong_result(sign);
  if (const std::string zero = reflection_zero_problem(A_, B); !zero.empty()) return wrong_result(zero);
  if (const std::string real = reflection_real_points_problem(A_, B); !real.empty()) return wrong_result(real);
  // real points at infinity only (an imaginary cylinder): B against the exact one as a matrix, as a
  // shadow's terminator at infinity (ShadowMeter)
  if (pts_.points.empty() && !without_real_points(A_))
    return measured_exactly(reflection_matrix_error(B, B_ref, reflected_item_base(A_, plane_, origin)), {"B"}, opt_.target);
  if (!bounds_.covers())
    return refined_accuracy(
        pts_, dense_, opt_, [&](const ItemPoints& p) { return reflection_error(p, origin, B).geometric; },
        [&] { return reflected_points(A_, M_, opt_.samples * kRefineFactor, item_seed(opt_.seed + 1, 2, A_, plane_)); });
  const CoveredBound b = bounds_(origin, B, size_down(pts_.size), opt_.target);
  const Measure sampled = reflection_error(pts_, origin, B).geometric;
  b.check([&](const std::string&) { return sampled; });
  return combined_accuracy(b.bound, sampled, 0, b.certified, opt_.target);
}

std::string error_bound_rule(const AccuracyOptions& accuracy) {
  return "error_bound: the geometric error (largest distance, first-order |x^T Q x| / |grad| or second-order "
      "sqrt(|x^T Q x| / kappa) where smaller, of exact points of the terminator from the returned P, polar plane and "
      "R, or of A reflected from B, in the item's frame, divided by the object size, the largest distance of those "
      "points from A's centre). Where the terminator is a real ellipse, P, the polar plane and R on the terminator "
      "(R also on the polar plane inside it where h does not meet the terminator), and, where A is an ellipsoid, B "
      "are bounded over every point of their geometry by interval branch and bound; other terminators (hyperbolas, "
      "parabolas, line pairs) and other quadrics reflected are unbounded, and there the object size is the largest "
      "distance of the sampled points from A's centre (a cylinder's axis point they are drawn about; where A has no "
      "centre, the middle of a parallel pair's, a hyperbola's, a parabola's or a single line's stretch, else their "
      "centroid) and "
      "the same results are "
      "bounded over every point of their geometry within that distance of the centre, by interval bounds over shells "
      "of that ball. Where the reference's gradient vanishes on the geometry (a cone's apex; R where its plane h "
      "crosses the terminator) a first-order distance means nothing: there the shells bound the Euclidean distance to "
      "the result, by second order (sqrt(|x^T Q x| / c), c the result's curvature along a direction where it curves "
      "the other way), of the order of the square root of the rounding, and the distances measured at the " +
      std::to_string(accuracy.samples) + " seeded exact sample points (the points of verify --seed " +
      std::to_string(accuracy.seed) + ") count as well; certified_for names what is bounded. What no bound covers (a "
      "terminator with too few real points) is measured on those points (near the target again on " +
      std::to_string(kRefineFactor) + " times as many) and counted " + std::to_string(kBoundMargin) +
      " times, a margin that is not a proof. Where the terminator is a single real point, P, the polar plane and R are "
      "measured as matrices instead, their largest relative cross residual against the exact ones, exactly (verify's "
      "as_matrices), and likewise where its real points all lie at infinity. For a reflection, M's error (its largest entry off the exact reflection, relative "
      "to the larger of 1 and the reflection's largest entry) is counted exactly (certified_for M). verify's checks of "
      "the results' shapes beyond the geometric error (P on its generator lines, R on the polar plane and on h) are "
      "not counted. Flag inaccurate when error_bound > accuracy";
}

}  // namespace qverify
