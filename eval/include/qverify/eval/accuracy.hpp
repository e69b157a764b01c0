#pragma once
/// \file accuracy.hpp
/// The geometric error of a result, the one measure behind `verify`'s verdict,
/// `eval`'s error_bound and the studies' geometric error.
///
/// Exact points are sampled (seeded) on the item's exact geometry: terminator
/// points A ∩ {(A L) . x = 0} for a shadow, points of A reflected exactly by
/// the mirror for a reflection (RootPoints in Q(sqrt d)). For a result quadric
/// Q (plane pi) given in a frame with origin o, each point x is moved exactly
/// into that frame and
///   distance(x) = |x^T Q x| / (|w| 2 |(Q x)_{xyz}|)   (first order; plane: |pi.x| / (|w| |pi_xyz|)),
/// evaluated exactly in Q(sqrt d) and rounded to 80 digits. The geometric
/// error is the largest distance divided by the object size: the largest
/// distance of the (unreflected) points from the centre of A (the centre of
/// its quadratic part, -K^-1 k; where K is singular, the centre on A's axis (plane) of centres nearest
/// the light or mirror, as sampled (a cylinder); where A has no centre, the middle of the stretch
/// its points are drawn on (SampleReport::middle: a parabola's, a paraboloid's, a plane's), else the points'
/// centroid).
/// A far-away point therefore cannot make a wrong result look small.

#include <qverify/batch/items.hpp>
#include <qverify/eval/certified_bound.hpp>
#include <qverify/eval/frames.hpp>
#include <qverify/exact/root_point.hpp>
#include <qverify/exact/sampling.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <functional>
#include <optional>
#include <vector>

namespace qverify {

/// Default accuracy target T (relative to the object size).
inline constexpr double kDefaultAccuracy = 1e-9;
/// Default exact points per item (shared by eval's error bound and verify).
inline constexpr int kDefaultSamples = 64;
/// The most sample points an item may ask for, at every door (CLI, Python, the C++ checks): 10^5
/// points of an item take seconds; far more overflowed the sampler's attempt count (50 n + 50 in an
/// int) and came back with no point, "skipped" (audit 31b F3).
inline constexpr int kMaxSamples = 100000;

/// Frobenius norm of an exact matrix or vector, to 80 digits.
template <int R, int C> Measure frobenius(const Eigen::Matrix<Rational, R, C>& m) {
  Measure s = 0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const Measure v = to_measure(m(i));
    s += v * v;
  }
  return sqrt(s);
}

/// Largest residual |x^T Q x| / (|Q|_F |x|^2) and first-order distance over points.
struct Metric {
  Measure residual = 0, distance = 0;
  bool all_zero = true;  ///< every point exactly on the result
  bool singular = false; ///< a point off the result where its gradient vanishes (distance infinite)
  std::optional<std::size_t> worst;  ///< index of the point farthest from the result (largest distance)
};

/// Exact points of one item and the size of its object.
struct ItemPoints {
  std::vector<RootPoint> points;  ///< world frame
  /// Shadow items (world frame): points of the generator lines of the cone from L through the
  /// terminator (every quadric of the pencil alpha A + beta (AL)(AL)^T vanishes on the
  /// terminator; only the cone P vanishes on these), and rational points of the polar plane
  /// inside the object (R, the plane pair through it, vanishes there; A does not).
  std::vector<RootPoint> generators, plane;
  /// Shadow items: the indices in `points` of A's singular points (A x = 0: a cone's apex, sampled
  /// as the singular point of the line pair a cone lit from outside has as its terminator). P is not
  /// measured there (P_points): P_ref = (L^T A L) A - (A L)(A L)^T has P_ref x = s A x = 0, its
  /// gradient vanishes, and a rounded P's first-order distance there is about half the point's
  /// distance from the frame's origin however accurate P is (every floating P of a cone lit from
  /// outside failed, by 1e-4 to 1e-2 of the object's size). P's certified bound covers the apex's
  /// neighbourhood, by the Euclidean distance (second order: ball_quadric_bound).
  std::vector<std::size_t> singular;
  /// Shadow items of a point light: the indices in `points` of the terminator's points on R's second
  /// plane h (h . x = 0; the terminator lies on the polar plane pi). R is not measured there
  /// (R_points): R_ref = pi h^T + h pi^T has R_ref x = 0 on the line where its planes cross, so a
  /// rounded R's first-order distance there is a quotient of roundings, of order 1 in any precision
  /// (a sphere lit level with its centre at a height of 0.1 failed by 0.67, at mpfr:128 by 0.19).
  /// R's certified bound covers that line's neighbourhood by the Euclidean distance
  /// (ball_plane_pair_bound). `plane` holds no point of h either.
  std::vector<std::size_t> crossing;
  /// The offsets rho of `generators` (x + rho (L_xyz - L_w x), one scale for the item; accuracy.cpp):
  /// at each, the points are the terminator of one quadric (generator_map). Of L in its canonical form
  /// (canonical_light: w = +-1, or a primitive direction), which the points' map uses.
  std::vector<Rational> generator_offsets;
  /// Largest distance of the object's points from A's centre: over all of them where A is an
  /// ellipsoid or the terminator a real ellipse (terminator_size, ellipsoid_size: a certified lower
  /// bound within 2^-19), else over the sampled points. (64 random chords of a terminator 1400 times
  /// longer than wide reached 7 units of its 10^4, before the chords were shaped by its axes
  /// (sampling.cpp, shaped_directions): a size from the samples alone made every relative error 1400
  /// times too large.)
  Measure size = 0;
  /// A's centre (object_size's: a cylinder's axis point its sample is drawn about; where A has no
  /// centre, its stretch's middle, else the points' centroid) and a reach of at least `size`: the
  /// points a ball bound covers where the geometry is not a real ellipse (certified_bound.hpp, Ball;
  /// an ellipse's R is bounded in ShadowGeometry::R_ball, about all of it).
  /// For a reflection, about A's points before the mirror.
  Ball ball{Vec3<Rational>::Zero(), Rational(0), std::nullopt};
  bool exhausted = false;         ///< fewer real points than asked
};

/// The sampler's seed of one item of a kind (1 shadow, 2 reflection): of the run's seed and of the
/// item's exact inputs, A and L (the light) or the mirror's plane, each up to a positive factor (the
/// same quadric, light or plane), taken about a point that moves with the item (the point light, else
/// a point of A's core: accuracy.cpp, hash_origin), and not of where the item stands in a scene nor of
/// where the scene stands (translated exactly, its items get the same seeds, so the same points
/// moved with it). So an item gets the same
/// points, and the same object size and verdict where these come from the points, alone or among
/// others, from `verify` of a scene, check_shadow, a batch or Python (with the index, a cone
/// measured 6.6e-10 in one scene and 1.26e-9, flagged and failed, as a scene's only request); and
/// eval's bound and verify sample the same points for the same (seed, samples).
std::uint64_t item_seed(std::uint64_t seed, int kind, const Mat4<Rational>& A, const Vec4<Rational>& other);

/// One representative of all positive multiples (the same quadric, light or mirror plane): A's
/// primitive integer matrix; a point light scaled to w = +-1, a direction (w = 0) to its primitive
/// integer vector. The points, sizes and bounds of an item are computed from these, so that 3 A, or
/// a light written as (15, 0, 0, 3), gives the very numbers A and (5, 0, 0, 1) give.
Mat4<Rational> canonical_quadric(const Mat4<Rational>& A);
Vec4<Rational> canonical_light(const Vec4<Rational>& L);

/// Terminator points of the exact (A, L), with the points of its generator lines and its plane.
ItemPoints terminator_points(const Mat4<Rational>& A, const Vec4<Rational>& L, int n, std::uint64_t seed);
/// Points of A reflected by the exact mirror matrix M (size measured on A's points).
ItemPoints reflected_points(const Mat4<Rational>& A, const Mat4<Rational>& M, int n, std::uint64_t seed);

/// The object size rounded down to a double (a lower bound of the true size, as the sampled one is):
/// what a certified bound divides by. Below the 80-digit value by at least its possible error, not
/// only by the rounding to double.
double size_down(const Measure& size);

/// `local` (the item's points, moved into a frame) without A's singular points (ItemPoints::singular):
/// the terminator points P is measured on.
std::vector<RootPoint> P_points(const std::vector<RootPoint>& local, const ItemPoints& pts);
/// `local` without the points on R's second plane (ItemPoints::crossing): the terminator points R is
/// measured on.
std::vector<RootPoint> R_points(const std::vector<RootPoint>& local, const ItemPoints& pts);

/// The points moved exactly into the frame with origin o (x_local = x - o).
std::vector<RootPoint> in_frame(const std::vector<RootPoint>& pts, const std::optional<Vec3<Rational>>& origin);

/// Metric of a quadric / a plane over points already in its frame: the
/// largest relative residual |x^T Q x| / (|Q|_F |x|^2) and the largest
/// first-order distance |x^T Q x| / (|w| 2 |(Q x)_xyz|) (plane:
/// |pi.x| / (|w| |pi_xyz|)) over the points, both to 80 digits, the worst point,
/// and whether every point is exactly on Q.
///
/// Filtered, with the same result as measuring every point exactly: each
/// point's residual and distance are first enclosed in interval arithmetic
/// (from the point's RootPoint::enclosure and Q's entries enclosed); the
/// points those enclosures leave in doubt (they could reach the largest lower
/// bound of the others, or cannot be told from zero or from a vanishing
/// gradient or w: against a double result, nearly every point, since the
/// point's double enclosure loses about as much as the result's residual) are
/// evaluated exactly on integers and those values enclosed at 128 bits
/// (exact/root_enclosure.hpp). Only the points that can still be the worst,
/// or that stay uncertain, are rounded to 80 digits (usually one or two). The
/// others are certainly off Q and certainly not the worst, which is all the
/// metric says about them.
Metric measure_quadric(const std::vector<RootPoint>& pts, const Mat4<Rational>& Q);
Metric measure_plane(const std::vector<RootPoint>& pts, const Vec4<Rational>& pi);

/// The geometric error of a metric: distance / size; 0 when every point is
/// exactly on the result; infinite when a point lies off it where its gradient
/// vanishes. A terminator that is a single real point (a cone lit along its
/// axis: the apex) has no size to measure distances against, and the result's
/// gradient vanishes there: its error is the relative residual
/// |x^T Q x| / (|Q|_F |x|^2) instead.
Measure relative(const Metric& m, const Measure& size);

/// Geometric errors of one shadow item's results (relative to the object size).
struct ShadowError {
  Metric P, polar, R;  ///< on the terminator
  /// The geometric error (cli.md): the largest of the three. (The checks of the results' shapes, P on
  /// its generator lines and R on the polar plane and h, are verify's, beyond it: ShadowBounds.)
  Measure geometric = 0;
};
ShadowError shadow_error(const ItemPoints& pts, const std::optional<Vec3<Rational>>& origin, const Mat4<Rational>& P,
                         const Vec4<Rational>& polar, const Mat4<Rational>& R);

struct ReflectionError {
  Metric B;
  Measure geometric = 0;
};
ReflectionError reflection_error(const ItemPoints& pts, const std::optional<Vec3<Rational>>& origin,
                                 const Mat4<Rational>& B);

/// The exact reflection in the plane n.x + d = 0, written out here (not the
/// core's mirror_matrix, which is under test): x - 2 (n.x + d) n / (n.n).
Mat4<Rational> reference_mirror(const Vec4<Rational>& plane);

/// Which of a shadow item's results a certified bound covers (the others are measured on samples).
struct ShadowCover {
  bool P = false, polar = false, R = false;
};

/// The certified bound of some of an item's results, and their names ("P", "polar_plane", "R", "B").
struct CoveredBound {
  CertifiedBound bound;
  std::vector<std::string> certified;
  /// The same part by part (one bound may cover two results: "P" and "polar_plane" on an ellipse).
  struct Part {
    std::vector<std::string> names;
    CertifiedBound bound;
  };
  std::vector<Part> parts;
  /// Throws std::logic_error where a part's first-order bound is below the error sampled on one of
  /// its results, `sampled(name)` (a bug in the bound); a part whose bound is Euclidean somewhere
  /// (CertifiedBound::euclidean: second order near a cone's apex; R as a plane pair, always) may be,
  /// where a first-order distance means nothing.
  void check(const std::function<Measure(const std::string&)>& sampled) const;
};

/// The certified bounds of one shadow item's results over every point of the contract's geometry,
/// the terminator, built once per item from its points (eval's meter and verify's check use the same):
///  - where the terminator is a real ellipse, over the whole of it by branch and bound: P and the
///    polar plane (shadow_bound), R on the terminator and the polar plane inside it where h does not
///    meet the terminator (terminator_quadric_bound), and where it does, in a ball about the
///    whole terminator (ShadowGeometry::R_ball; as a plane pair, second order near the line where
///    R's planes cross);
///  - elsewhere (a hyperbola, a parabola, a line pair) over every point within the object size of
///    A's centre (ItemPoints::ball) by ball bounds (certified_bound.hpp): the polar plane; P where
///    A's gradient has a floor on the terminator there (terminator_gradient_floor: A's own, its
///    section's, a cone's on its section's lines), or P is indefinite (a cone's plane pair: second
///    order near its apex, in shells split while the innermost ball bounds the most); R where the
///    line h . x = 0 of the polar plane misses the terminator in the ball (a floor of |h . x| on
///    it, terminator_h_floor with the ball), where h misses the ball, or where R's planes cross
///    (second order near their line).
/// P on its generator lines, R on the polar plane inside the object and on h are not bounded: they
/// are verify's checks of the results' shapes (that P is the cone from L, R the plane pair), beyond
/// the geometric error, measured on samples. Bounded, they flagged correctly rounded results: a
/// cone's P under a parallel light is a plane pair, a rounded one truly sqrt(eps) rho off along the
/// line where its planes cross, the apex's generator line, while 5e-17 off on the terminator (audit
/// 31a F1); R likewise near the line where h crosses the polar plane, off the terminator (F2).
/// Nothing where the terminator has too few points to sample (ItemPoints::exhausted).
class ShadowBounds {
 public:
  ShadowBounds(const Mat4<Rational>& A, const Vec4<Rational>& L, const ItemPoints& pts);
  /// What a bound covers, of the results that are given.
  const ShadowCover& cover() const { return cover_; }
  /// The bound of the given results (nullptr: not given), in the frame with `origin`, relative to
  /// `size`; `target` steers the branch and bound only.
  CoveredBound operator()(const std::optional<Vec3<Rational>>& origin, const Mat4<Rational>* P,
                          const Vec4<Rational>* polar, const Mat4<Rational>* R, double size, double target) const;

 private:
  /// The unit of length of everything below and of the bounds (accuracy.cpp, length_unit): a power
  /// of two near the object's size, so that the bounds' doubles neither overflow nor underflow.
  Rational unit_{1};
  ShadowCover cover_;
  std::optional<ShadowGeometry> geo_;
  // the ball bounds, where geo_ is empty
  Ball ball_{Vec3<Rational>::Zero(), Rational(0), std::nullopt};
  Mat4<Rational> P_ref_, R_ref_;
  Vec4<Rational> pi_ref_, h_;
  ShellFloor P_floor_;  ///< terminator_gradient_floor: P_ref's gradient on the terminator
  std::optional<SaddleSlopes> P_slopes_;  ///< terminator_saddle_slopes: P_ref's slopes along its saddle directions
  Measure R_floor_ = 0;  ///< terminator_h_floor times |pi_xyz|: R_ref's gradient on the terminator
  std::optional<CrossingSplit> split_;  ///< where h . x = 0 meets the terminator in the ball
  Measure split_floor_ = 0;  ///< split_'s floor of |h . x| outside its balls, times |pi_xyz|
  /// R in the ball as a plane pair (ball_plane_pair_bound: the terminator from R's first plane, then
  /// R from that plane's points); where h misses the ball also against R_ref in one step, and where
  /// R_floor_ > 0 against R_ref with that floor (over the terminator only), the smallest.
  CertifiedBound R_ball_bound(const Mat4<Rational>& R, const std::optional<Vec3<Rational>>& origin, double size) const;
};

/// The same for a reflection item's B: over the whole of A reflected where A is an ellipsoid
/// (reflection_bound), else over A's points within the object size of its centre, reflected
/// (a ball bound, where A's gradient has a floor there or B is indefinite: second order near a
/// cone's apex).
class ReflectionBounds {
 public:
  ReflectionBounds(const Mat4<Rational>& A, const Mat4<Rational>& M, const ItemPoints& pts);
  bool covers() const { return geo_.has_value() || floored_; }
  CoveredBound operator()(const std::optional<Vec3<Rational>>& origin, const Mat4<Rational>& B, double size,
                          double target) const;

 private:
  Rational unit_{1};  ///< as ShadowBounds::unit_
  std::optional<ReflectionGeometry> geo_;
  Mat4<Rational> B_ref_;
  Ball ball_{Vec3<Rational>::Zero(), Rational(0), std::nullopt};  ///< reflected
  GradientFloor floor_;
  bool floored_ = false;
  /// Where A is an elliptic cylinder: the ball turned to its axes (cylinder_turn), and B_ref there.
  std::optional<TurnedBall> turned_;
  Mat4<Rational> B_ref_turned_;
};

/// error_bound of eval: what ShadowBounds / ReflectionBounds cover is bounded over every point of
/// its geometry (certified_bound.hpp); what is measured on samples only (what no bound covers: a
/// semi-definite reference with no gradient floor) counts twice its largest sampled error
/// (kBoundMargin), a margin for the points between the samples that is not a proof.
inline constexpr int kBoundMargin = 2;


/// What eval says of an item's accuracy (cli.md, "Accuracy"): a bound of its
/// geometric error (accuracy.hpp) and whether that may exceed the target.
struct ItemAccuracy {
  std::optional<double> bound;  ///< error_bound; nullopt with a reason where none can be given
  std::string reason;
  bool inaccurate = false;
  /// The results whose part of the bound is certified over every point of their geometry
  /// (certified_bound.hpp: "P", "polar_plane" and "R" on the terminator, "B"; ShadowBounds,
  /// ReflectionBounds); the other parts are measured on samples.
  std::vector<std::string> certified;
  /// A geometric error the result is known to reach (a lower bound of its true error, at most
  /// `bound`): the largest measured on the exact sample points, or, where the bound is certified,
  /// the distance the branch and bound certifies as attained, whichever is larger. The studies
  /// judge a result by it (a sample alone may miss where the error is). The branch and bound's is a
  /// first-order distance, as its bound is: where that exceeds the point's second-order distance
  /// (a result off by more than about its own size, or near a vanishing gradient) it is above what
  /// verify measures at a sampled point (the stress report's item_geometric_error next to its
  /// geometric_error).
  double attained = 0;
};

/// Signs (cli.md: P and B up to a *positive* factor, the polar plane A L up to
/// a positive factor). A geometric error cannot see them: -P has P's zero set.
/// Judged exactly, against references computed from the exact inputs, the
/// same way by eval (a result of the wrong sign is flagged) and verify.
///
/// Test points e_i and e_i +- e_j: for a non-zero symmetric X one of them has
/// |y^T X y| >= |X|_max, so the sign there is robust to errors of X below a
/// quarter of its largest entry.
const std::vector<Vec4<Rational>>& sign_probes();
/// y^T X y.
inline Rational form(const Mat4<Rational>& X, const Vec4<Rational>& y) { return y.dot(X * y); }
/// Does `got` have the sign of the reference quadratic form `ref` (y -> y^T Ref y)? Judged at the
/// probe where |ref| is largest; true when ref vanishes at every probe.
bool same_sign_as(const Mat4<Rational>& got, const std::function<Rational(const Vec4<Rational>&)>& ref);
/// The sign of a plane's (or a matrix's) entry at the pivot (largest entry) of the reference.
template <int R, int C>
bool same_orientation(const Eigen::Matrix<Rational, R, C>& X, const Eigen::Matrix<Rational, R, C>& ref) {
  const Eigen::Index p = pivot_index(ref);
  return sign_of<Rational>(X(p)) == sign_of<Rational>(ref(p));
}
/// P against (L^T A L) A - (A L)(A L)^T and the polar plane against A L, A and L in the results'
/// frame: a problem for each that has the wrong sign (or vanishes where the reference does not);
/// none when right (a result not given is not judged).
std::vector<std::string> shadow_sign_problems(const Mat4<Rational>& A, const Vec4<Rational>& L, const Mat4<Rational>* P,
                                              const Vec4<Rational>* polar);
/// B against M^T A M (B_ref, in B's frame): the problem, or "".
std::string reflection_sign_problem(const Mat4<Rational>& B, const Mat4<Rational>& B_ref);
/// P, the polar plane and R against the exact ones' vanishing: where the exact P (a degenerate
/// quadric, a light at a cone's apex), polar plane or R (A L = 0: a cylinder lit along its axis) is
/// zero, any other result is wrong whatever its size (and a zero result where the exact one is not);
/// a problem for each, none when right. A and L in the results' frame; a result not given is not
/// judged. No point can see it, nor a cross residual against a zero reference: verify judges it, and
/// eval flags it, also where there is no point to sample (a polar plane z = 5 where A L = 0 was
/// judged nowhere: audit 31b F2).
std::vector<std::string> shadow_zero_problems(const Mat4<Rational>& A, const Vec4<Rational>& L, const Mat4<Rational>* P,
                                              const Vec4<Rational>* polar, const Mat4<Rational>* R);
/// The same for B (zero exactly when A is): the problem, or "".
std::string reflection_zero_problem(const Mat4<Rational>& A, const Mat4<Rational>& B);
/// A quadric without real points (A definite, hence M^T A M too: the image of the empty set is empty):
/// B must have none either, its symmetric part definite (exactly: its leading minors). A B with real
/// points is wrong whatever its size, and no sampled distance sees it, as there is no exact point to
/// measure from: a rounded image of an imaginary sphere 3e7 from the origin came back a real sphere of
/// radius 5000, unflagged, and verify skipped it (audit 38a F1). The problem, or "".
std::string reflection_real_points_problem(const Mat4<Rational>& A, const Mat4<Rational>& B);
/// M's error against the exact reflection M_ref (in M's frame), as verify judges it (M_error) and eval
/// counts it (error_bound): the largest entry of M - M_ref over the larger of 1 and M_ref's largest
/// entry. Exact: M is not sampled, so this part of the bound is certified.
Measure mirror_error(const Mat4<Rational>& M, const Mat4<Rational>& M_ref);

/// Is the terminator of A and L (world frame) one real point (a cone lit along its axis or from
/// inside, a point sphere, a light on a sphere)? Exactly: every sampled point rational (no sqrt
/// part) and proportional to the first, in `terminator` when it holds at least kDefaultSamples
/// points, else in a sample of that many with a seed of its own (the answer does not depend on
/// --samples or --seed: one sample of a cone lit from outside is its apex). There the terminator says nothing of the shape of P, of the polar plane's
/// orientation or of R (P and R are singular at that point, so a first-order distance there
/// means nothing, and a second-order one about the square root of the rounding), and the results
/// are judged as matrices instead (shadow_matrix_error).
bool single_point(const Mat4<Rational>& A, const Vec4<Rational>& L, const std::vector<RootPoint>& terminator);
/// The largest relative cross residual (core/projective.hpp, cross_residual: zero exactly when
/// proportional) of P, the polar plane and R, each when given, against (L^T A L) A - (A L)(A L)^T,
/// A L and the plane pair R of (A, L), A and L in the results' frame, all taken to the item's own
/// frame first (about `base`, item_base in the results' frame, in units of the light's L-infinity
/// distance from it; the scene's unit for a parallel light or a lamp at the base), so that the
/// measure does not move with the scene's placement: the error of a shadow item
/// whose terminator is a single point, measured exactly (signs are judged by shadow_sign_problems).
Measure shadow_matrix_error(const Mat4<Rational>& A, const Vec4<Rational>& L, const Mat4<Rational>* P,
                            const Vec4<Rational>* polar, const Mat4<Rational>* R, const Vec3<Rational>& base);
/// The same for a reflection whose real points all lie at infinity: B's relative cross residual
/// against B_ref = M^T A M, both about `base` (reflected_item_base, in the results' frame).
Measure reflection_matrix_error(const Mat4<Rational>& B, const Mat4<Rational>& B_ref, const Vec3<Rational>& base);

/// The point of A's core an item's samples are drawn about (world frame; kind 1 shadow, `other` the
/// light; kind 2 reflection, `other` the mirror's plane): A's centre or apex, a point inside a
/// paraboloid on its axis; on a line of centres (a cylinder), its point nearest a point light, or on
/// the mirror, else nearest the world origin. It moves with the item when the scene is translated
/// (but for a cylinder under a parallel light, or beside a mirror parallel to its axis, which slide
/// along the axis), and eval's frames, the seeds and the matrices' measure are all about it.
Vec3<Rational> item_base(int kind, const Mat4<Rational>& A, const Vec4<Rational>& other);
/// item_base(2, A, plane) reflected in the mirror, in the frame with the given origin.
Vec3<Rational> reflected_item_base(const Mat4<Rational>& A, const Vec4<Rational>& plane,
                                   const std::optional<Vec3<Rational>>& origin);

/// R's second plane h (the plane the paper's frame sends to infinity: z = l_z for a point light, the
/// plane at infinity for a parallel one): R must vanish on it. Measured by verify
/// (R_on_second_plane, a check of R's shape judged against the target, not in the geometric error), at exact
/// points of h, A and L in the result's frame, `local` the item's terminator points in that frame
/// (none finite: nothing is measured) and `size` the object size. h's points are taken above
/// `inside`, section_base(A, A L) (exact/sampling.hpp): a point of A and L alone, so that where the
/// object size does not depend on the samples (a real ellipse's) neither does the measure. (Other
/// terminators' sizes are measured over the sampled points: ItemPoints::size.) Point light: the
/// first-order distance of each point of h divided by the larger of the object size and the point's distance from `inside` (h may pass far
/// from the object: an angle, not a length). The points keep away from the line where h crosses the
/// polar plane pi, where R's gradient (pi . y) h vanishes and a first-order distance means nothing,
/// by a step that grows with their distance from `inside` (see accuracy.cpp). Parallel light: h is
/// the plane at infinity, and the measure its angle as the point light's, |R3|_F size / (2 min_x
/// |(R_s x)_xyz|), R_s R's symmetric part, R3 its spatial block, x over `local`'s finite points (for
/// R = pi h'^T + h' pi^T, h' = (e, 1), about size |e|: h' 1 / |e| away); a terminator of one point
/// (size 0) has no length, and unit steps stand for it, as for a point light. `all_zero`: R vanishes
/// exactly at every point (R3 = 0 for a parallel light; 0 is returned, also where no point of
/// `local` is finite).
Measure second_plane_error(const std::vector<RootPoint>& local, const Measure& size, const Mat4<Rational>& A,
                           const Vec4<Rational>& L, const Mat4<Rational>& R, bool& all_zero);

/// Options of the accuracy assessment (cli.md "Accuracy"; below).
struct AccuracyOptions {
  double target = kDefaultAccuracy;
  int samples = kDefaultSamples;
  std::uint64_t seed = 1;
  /// Threads over the items (0: one per logical processor); the results do not depend on it.
  int threads = 0;
  /// Called after each item is measured with (items done, items in all), one call at a time.
  ItemProgress progress = nullptr;
};

/// error_bound of an item from its geometric error measured on the sampled
/// points (times the margin kBoundMargin), and `inaccurate` when it may exceed
/// the target; no bound (with the reason) when there is nothing to measure on.
ItemAccuracy item_accuracy(const Measure& geometric, bool has_points, double target);

/// Items whose error measured on the sample points is within a factor 100 below
/// the target (where a sample's underestimate could hide an error beyond it)
/// are measured again on kRefineFactor times as many other points.
inline constexpr int kRefineFactor = 8;
inline bool in_gray_zone(const Measure& geometric, double target) {
  return geometric * kBoundMargin <= target && geometric * 100 > target;
}

/// The rule of error_bound and `inaccurate` in words, for the documents.
std::string error_bound_rule(const AccuracyOptions& accuracy);

/// The accuracy of a result that has non-finite entries: no bound, inaccurate.
ItemAccuracy non_finite_accuracy();

/// eval's error_bound and `inaccurate` of one shadow item (index k): what ShadowBounds covers
/// bounded over every point of its geometry (the whole terminator where it is a real ellipse, the
/// part within the object size of A's centre elsewhere), the rest measured on the item's seeded
/// sample points (shadow_error) and, in
/// the gray zone, again on kRefineFactor times as many other points, the larger
/// measure counting, times kBoundMargin. A sampled error above the certified
/// bound is a bug and throws std::logic_error. The points are sampled once per
/// meter and kept, so a result measured again (after escalation) is measured on
/// the same points. Used by eval's accuracy assessment and by its adaptive mode alike.
class ShadowMeter {
 public:
  ShadowMeter(const Mat4<Rational>& A, const Vec4<Rational>& L, const AccuracyOptions& opt);
  ItemAccuracy operator()(const std::optional<Vec3<Rational>>& origin, const Mat4<Rational>& P,
                          const Vec4<Rational>& polar, const Mat4<Rational>& R);

 private:
  Mat4<Rational> A_;
  Vec4<Rational> L_;
  AccuracyOptions opt_;
  ItemPoints pts_;
  std::optional<ItemPoints> dense_;
  ShadowBounds bounds_;
};

/// The same for one reflection item: B bounded over A reflected by the exact mirror of `plane`
/// where ReflectionBounds covers it (the whole of an ellipsoid; other quadrics within the object
/// size of their centre, not a cone), else measured on its sampled points (reflection_error); and,
/// when the item's M is given, M's error (mirror_error, exact: "M" in `certified`), which verify
/// judges against the same target (a float M of the plane x + y + z = 0 is 2e-8 off: flagged).
class ReflectionMeter {
 public:
  ReflectionMeter(const Mat4<Rational>& A, const Vec4<Rational>& plane, const AccuracyOptions& opt);
  ItemAccuracy operator()(const std::optional<Vec3<Rational>>& origin, const Mat4<Rational>& B,
                          const Mat4<Rational>* M = nullptr);

 private:
  ItemAccuracy B_accuracy(const std::optional<Vec3<Rational>>& origin, const Mat4<Rational>& B);
  Mat4<Rational> A_, M_;
  Vec4<Rational> plane_;
  AccuracyOptions opt_;
  ItemPoints pts_;
  std::optional<ItemPoints> dense_;
  ReflectionBounds bounds_;
};

}  // namespace qverify
