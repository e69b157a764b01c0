#pragma once
/// \file certified_bound.hpp
/// A certified upper bound of a result's geometric error over *every* exact
/// point of its geometry, not only over sampled ones: interval branch and bound.
///
/// Where the terminator is a real ellipse (A an ellipsoid, K definite with real
/// points; or a hyperboloid or paraboloid cut so by the polar plane), and for a
/// reflection where A is an ellipsoid, the geometry of an item is
/// the image of the unit circle or sphere, u = v / |v| with v on the faces of
/// the square or cube [-1, 1]^k, so that its pieces are boxes of parameters:
///  - the terminator A ∩ {pi . x = 0}, pi = A L, an ellipse: in plane
///    coordinates (s, t), x = p0 + s e1 + t e2, the section is the conic
///    (s t 1) C (s t 1)^T, C = G^T A G; with its centre m and S = C2 / (-C(m))
///    = R^T R (Cholesky, in intervals), x = c + y0 + [e1 e2] R^-1 u;
///  - A reflected: x = c + R3^-1 u with K / (-A(c)) = R3^T R3, carried by the
///    exact mirror M (the reflected point minus M c is H R3^-1 u);
///  - the polar plane inside the terminator: the same map of the unit disc
///    (|u| <= 1, u = r v / |v|, r in [0, 1] a second parameter), where R vanishes.
///
/// For a returned quadric Q^ (in the frame with origin o) and an exact quadric
/// Q that vanishes on the geometry (the reference, computed from A and L or the
/// mirror by the formulas of the paper, not by the functions under test), every
/// lambda gives, on the geometry,
///   x^T Q^ x = x^T E x,   E = Q^ - lambda Q_o            (Q_o: Q in the frame)
///   (Q^ x)_xyz = lambda (Q3 (p - e) + (Q (e, 1))_xyz) + (E x)_xyz,
/// p the Cartesian world point and e an exact expansion point near the object.
/// With p - e = y0 + B R u (y0, B exact; R the inverse Cholesky factor, in
/// intervals) both are polynomials in u,
///   x^T E x = a + b . u + u^T C u,   (Q^ x)_xyz = g0 + G u,
/// whose coefficients are exact rationals (times R), computed exactly and only
/// then enclosed: nothing cancels inside the intervals, so a result 10^12 from
/// its object, or a needle 10^10 long, is bounded as tightly as a ball at the
/// origin (P_ref = (L^T A L) A - (A L)(A L)^T, eq. (3), vanishes on the plane's
/// directions e1, e2 exactly, which its enclosure alone would not). On a box of parameters
/// the first-order distance |x^T E x| / (2 |grad|) (plane: |eps . x| / |pi^_xyz|)
/// is bounded above by interval arithmetic (CGAL Interval_nt, rounding upward;
/// on the terminator also by the mean-value form in the circle's parameter,
/// whose overestimate shrinks with the square of the box: a terminator 10^6
/// times longer than wide is otherwise not bounded within any budget), the
/// gradient also from below by a floor that holds on the whole geometry (on A,
/// |K (x - c)| >= sqrt(mu |A(c)|), mu <= the smallest eigenvalue of +-K, proved
/// exactly; P on the terminator is (L^T A L) times A's gradient there; R on the
/// polar plane is (h . x) pi_xyz, and |h . x| >= |a0| - |c| on the disc), so that
/// a thin object's wide boxes, whose gradient enclosure contains 0, are still
/// bounded; and below at the box's centre (a point of the geometry lies in the
/// thin box evaluated there). The box with the largest upper bound is bisected until the
/// bound is within a factor 2 of a distance attained, or below a thousandth of
/// the target, or a budget of boxes is spent; the bound is the largest upper
/// bound left, divided by the object size (a lower bound of the true size, so
/// the quotient bounds the relative error above).

#include <qverify/core/scalar.hpp>
#include <qverify/exact/root_point.hpp>
#include <qverify/exact/scalars.hpp>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace qverify {

/// The certified bound of one or more results over one piece of geometry.
struct CertifiedBound {
  double upper = 0;     ///< sup of the relative first-order distance over the geometry <= upper (may be inf)
  double attained = 0;  ///< a relative first-order distance attained at a point of the geometry (sup >= attained)
  int boxes = 0;        ///< boxes evaluated
  /// Somewhere (near a point where the reference's gradient vanishes: a cone's apex, the line of a
  /// plane pair) `upper` bounds the Euclidean distance to the result, by second order or the root
  /// bound V / G (ball_quadric_bound; ball_plane_pair_bound always), not the first-order one, which
  /// is unbounded there: a sampled point's first-order distance may then exceed `upper`.
  bool euclidean = false;
  /// Ball bounds bounded to first order in every shell: a lower bound of |(hat z)_xyz| / |H|_F over
  /// the geometry they cover (H the symmetric part of hat_xyz,xyz; a length, whatever hat's scale),
  /// infinite where H = 0; 0 where none (a shell took the second order, or not a ball bound). With it
  /// a Euclidean distance delta bounds the first-order one: delta + delta^2 / (2 gradient).
  double gradient = 0;
};

/// One returned result with its exact reference, ready for interval evaluation.
class BoundedResult;

/// A parametrised piece of an item's geometry (the terminator, A reflected).
class Geometry;

/// Where the geometry is not a real ellipse (an unbounded terminator, a quadric other than an
/// ellipsoid reflected) its points do not all count: the object size is the largest distance of
/// the sampled points from A's centre (accuracy.hpp), and a bound covers every point of the
/// geometry within that distance of the centre, the ball below (exact: `reach` is at least the
/// size).
struct Ball {
  Vec3<Rational> centre;
  Rational reach;
  /// Where known, half-widths of a box about the centre that holds the geometry too (upper bounds,
  /// per axis): the bounds below use, on each shell, the smaller of the ball's and the box's
  /// enclosures. A thin object 10^8 long (a needle ellipsoid's terminator, as the ball about it
  /// holds 10^8 in every direction) had its cross terms, the error x z of an entry of R, bounded
  /// with |x| <= 10^8 where |x| <= 1: a world-frame R accurate to 10^-13 of the object's size
  /// was bounded at 8e-9 and failed (audit 30b F1).
  std::optional<Vec3<Rational>> half;
};

/// The geometry of a shadow item where the terminator is a real ellipse (any quadric; A's
/// gradient floor, and with it grad_floor, is known where A is an ellipsoid only, 0 elsewhere);
/// nullopt otherwise (the error is then bounded in a ball: ball_quadric_bound, ShadowBounds).
struct ShadowGeometry {
  std::shared_ptr<const Geometry> terminator;
  std::shared_ptr<const Geometry> polar_disc;  ///< the polar plane inside the terminator
  Mat4<Rational> P_ref;  ///< (L^T A L) A - (A L)(A L)^T, world frame
  Vec4<Rational> pi_ref; ///< A L
  /// A lower bound of |(P_ref x)_xyz| on the terminator (0: none known).
  Measure grad_floor = 0;
  /// pi h^T + h pi^T, h the plane the paper's frame sends to infinity (z = l_z for a point
  /// light, the plane at infinity for a parallel one), world frame.
  Mat4<Rational> R_ref;
  /// A lower bound of |(R_ref x)_xyz| = |h . x| |pi_xyz| on the terminator and on the polar plane
  /// inside it; 0 where h meets the terminator (R's gradient vanishes there: no first-order bound
  /// of a rounded R exists) or misses it by less than the enclosures can tell.
  Measure R_floor = 0;
  /// Where R_floor is 0: a ball about the terminator's expansion point that holds all of it and the
  /// polar plane inside it (reach: the largest offset from above), where R is bounded as a plane pair
  /// (ball_plane_pair_bound).
  std::optional<Ball> R_ball;
};
std::optional<ShadowGeometry> shadow_geometry(const Mat4<Rational>& A, const Vec4<Rational>& L);

/// h, R's second plane, written out here (not the core's frame_plane, which is under test): the
/// plane the paper's frame sends to infinity, z = l_z for a point light, the plane at infinity
/// (0, 0, 0, 1) for a parallel one.
Vec4<Rational> reference_second_plane(const Vec4<Rational>& L);

/// The references, written out here (not the core's functions, which are under test): P_ref =
/// (L^T A L) A - (A L)(A L)^T, eq. (3), and R_ref = pi h^T + h pi^T, pi = A L, h = reference_second_plane(L).
Mat4<Rational> reference_cone(const Mat4<Rational>& A, const Vec4<Rational>& L);
Mat4<Rational> reference_plane_pair(const Mat4<Rational>& A, const Vec4<Rational>& L);

/// A lower bound t0 > 0 of |h . x| over the terminator's finite real points x = (p, 1) (h =
/// reference_second_plane(L): R_ref's gradient there is (h . x) pi_xyz), whatever its shape; nullopt
/// where none is found (the line h . x = 0 of the polar plane meets or touches the terminator, or the
/// lines of the polar plane along h are asymptotic to A). Where h is parallel to the polar plane, h . x
/// is one number on it, exactly; where h is the plane at infinity (0, 0, 0, h_w), as under a parallel
/// light, it is h_w at every finite point. Exactly: on
/// the lines x = p0 + t w + s u of the polar plane (pi . x = 0, h . x = t, u along both planes),
/// A(x) = alpha s^2 + 2 beta(t) s + gamma(t), beta linear and gamma quadratic in t, alpha =
/// u^T K u != 0; such a line meets A where D(t) = beta^2 - alpha gamma = a t^2 + b t + c >= 0. With
/// c = D(0) < 0 the line h . x = 0 misses the terminator, and the t of the terminator's points
/// nearest 0 is D's root of least magnitude, 2 |c| / (|b| + sqrt(b^2 - 4 a c)) (for either sign of
/// a; the whole line family misses where b^2 < 4 a c), enclosed from below.
///
/// With a `ball`, the floor over the terminator's points in the ball only, where larger: the least
/// |t| of those points, bounded from below by interval bisection of t outward from 0 (a piece of t
/// is cleared where its lines miss A, or meet it outside the ball only). Where h . x = 0 meets the
/// terminator outside the ball, R's planes cross there, not in the ball, and R_ref's gradient on the
/// terminator in the ball keeps away from 0 (audit 39a F1: without it, R was bounded by second
/// order, as where its planes cross, at 1e7 times its true error).
std::optional<Measure> terminator_h_floor(const Mat4<Rational>& A, const Vec4<Rational>& L, const Ball* ball = nullptr);
/// The same for any plane h against the terminator of the polar plane pi (terminator_h_floor is it
/// with pi = A L and h = reference_second_plane(L)).
std::optional<Measure> terminator_plane_floor(const Mat4<Rational>& A, const Vec4<Rational>& pi, const Vec4<Rational>& h,
                                              const Ball* ball = nullptr);
/// The terminator's points on the plane h (pi . x = 0 = h . x, A(x) = 0), rationals computed in 80
/// digits: none where h is parallel to pi, at infinity, or its line on pi misses A or lies on it.
std::vector<Vec3<Rational>> terminator_crossings(const Mat4<Rational>& A, const Vec4<Rational>& pi, const Vec4<Rational>& h);

/// Where h . x = 0 meets the terminator in the ball (R's planes cross there, and a rounded R is about
/// sqrt(eps) off at those points, a distance only the second order bounds): balls `near` of radius
/// reach / 2^16 about the crossing points (rational points computed in 80 digits), and `floor`, a
/// floor of |h . x| over the terminator's points in the ball outside them (terminator_h_floor's
/// bisection). R is then bounded to first order against R_ref with floor |pi_xyz| outside, and as a
/// plane pair in each near ball, about its crossing point, where the value's sign is known and the
/// curvature against it counts: the plane pair's bound about the ball's centre took the smaller
/// curvature over shells through the crossing points, 13 times the true distance there (audit 39a,
/// audit 37a F3). nullopt where no crossing point is in the ball, or no floor is found.
struct CrossingSplit {
  std::vector<Ball> near;
  Measure floor = 0;
};
std::optional<CrossingSplit> crossing_split(const Mat4<Rational>& A, const Vec4<Rational>& L, const Ball& ball);

/// The map of points x = c + s y into an item's or a geometry's own frame (c its centre, s > 0 its
/// length, in the results' frame): quadrics go to T^T X T, planes to T^T p.
Mat4<Rational> own_frame(const Vec3<Rational>& c, const Rational& s);

/// The geometry of a reflection item where A is an ellipsoid; nullopt otherwise.
struct ReflectionGeometry {
  std::shared_ptr<const Geometry> surface;
  Mat4<Rational> B_ref;  ///< M^T A M, world frame
  Measure grad_floor = 0; ///< a lower bound of |(B_ref x)_xyz| on A reflected (0: none known)
};
std::optional<ReflectionGeometry> reflection_geometry(const Mat4<Rational>& A, const Mat4<Rational>& M);

/// The object size (docs/json-documents.md, accuracy): the largest distance from A's centre of
/// the terminator's points (shadow) or of A's points (reflection), over all of
/// them, from below and within a relative 2^-19 of the truth, where A is an
/// ellipsoid; nullopt otherwise. terminator_size also where the terminator is a real ellipse on
/// another quadric (a hyperboloid's, a paraboloid's: a bounded curve), from `centre` there
/// (object_size's: A's centre, or the sampled points' centroid where A has no centre): sampled, the
/// size of such a terminator 10^12 long came out 10^6 at 8 samples and 10^12 at 64, and every
/// relative error with it.
std::optional<double> terminator_size(const Mat4<Rational>& A, const Vec4<Rational>& L, const Vec3<Rational>& centre);
std::optional<double> ellipsoid_size(const Mat4<Rational>& A);

/// The certified bound of the returned P and polar plane (in the frame with
/// `origin`; either may be absent) over the terminator. `target` (relative)
/// steers the bisection only: it goes on while the bound is above the target
/// and the distance attained below it.
CertifiedBound shadow_bound(const ShadowGeometry& g, const std::optional<Vec3<Rational>>& origin,
                            const Mat4<Rational>* P, const Vec4<Rational>* polar, double size, double target);

/// The certified bound of the returned R over the terminator and over the polar plane inside it
/// (where R_ref, the plane pair, vanishes too), where h does not meet the terminator
/// (R_floor > 0); nullopt where it does (R is then measured on samples: accuracy.hpp).
std::optional<CertifiedBound> terminator_quadric_bound(const ShadowGeometry& g,
                                                       const std::optional<Vec3<Rational>>& origin,
                                                       const Mat4<Rational>& R, double size, double target);

/// The map of a shadow item's terminator onto the generator lines of its cone P at offset
/// rho: x = (X, w) -> (X + rho (w L_xyz - L_w X), w), i.e. M = (1 - rho L_w) I + rho L e_4^T,
/// the homothety centred at L of ratio 1 - rho L_w for a point light, the translation by
/// rho L_xyz for a parallel one. M L = L.
Mat4<Rational> generator_map(const Vec4<Rational>& L, const Rational& rho);

/// The bound of an item's results over two pieces of geometry: the larger upper bound and
/// distance attained, the boxes of both.
CertifiedBound combined(const CertifiedBound& a, const CertifiedBound& b);

/// The certified bound of the returned B over A reflected.
CertifiedBound reflection_bound(const ReflectionGeometry& g, const std::optional<Vec3<Rational>>& origin,
                                const Mat4<Rational>& B, double size, double target);


/// Lower bounds of |(A (x, 1))_xyz| over the points x of A in a shell of a ball, inner <= |x - c| <=
/// outer; 0 where none is known (A's gradient vanishes there: the apex of a cone; or A is the zero
/// matrix). With K = A_xyz,xyz, k = A_xyz,w, mu <= the smallest non-zero eigenvalue of K^2 and
/// sigma = |K|_F >= its largest singular value (both proved exactly):
///  - K y0 = -k has a rational solution (A's centre, or any point of its axis of centres) and
///    r = A(y0): on A, y^T K y = -r for y = x - y0, so (Cauchy-Schwarz) |K y| >= |r| / |y| >=
///    |r| / (|c - y0| + outer), and |K y|^2 >= lambda |r| >= sqrt(mu) |r| (lambda the least |l_i|
///    of the eigenvalues l_i of K of the sign of -r: in K's eigenvectors -r = sum l_i y_i^2, whose
///    terms of that sign sum to at least |r|, and each |l_i| y_i^2 <= l_i^2 y_i^2 / lambda; with
///    tau <= lambda proved exactly, positive_eigen_floor, else lambda >= sqrt(mu));
///    where K is invertible also |K y| >= sqrt(mu) |y| >= sqrt(mu) (inner - |c - y0|), a cone's too
///    away from its apex;
///  - it has none (a paraboloid, a parabolic cylinder): with k_n, k's part in K's kernel, and y0 with
///    K y0 = -(k - k_n), K x + k = K y + k_n, so |K x + k|^2 >= mu |Py|^2 + |k_n|^2; for a
///    paraboloid (kernel = span k_n), A = 0 gives |k_n . y| <= (sigma |Py|^2 + |A(y0)|) / 2, so that
///    |y| >= inner - |c - y0| bounds |Py| from below; and so does |y| >= max(inner - |c - v|,
///    |c - v| - outer) about its vertex v (y0 = v, A(v) = 0), on whichever side of v the shell lies.
///  - K invertible, by the S-lemma: |K y|^2 = y^T (K^2 - tau K) y + tau y^T K y >= gamma |y|^2 - tau r
///    on A wherever K^2 - tau K - gamma I is positive semidefinite (proved exactly, tau at the
///    breakpoints of K's eigenvalues): a flat hyperboloid, y1^2 + y2^2 - 10^6 y3^2 = 1, has
///    |K y| >= 1000 sqrt(|y|^2 - 1) + ... where the least |eigenvalue| and |r| gave |y| and 1 (its
///    points at |y| keep y3 near |y| / 1000: audit 39a F1, P under a sun bounded at 6e4 times its error).
/// `scale` multiplies every floor (P's reference on the terminator is (L^T A L) A's gradient).
class GradientFloor {
 public:
  GradientFloor() = default;  ///< none: 0
  GradientFloor(const Mat4<Rational>& A, const Ball& ball, const Rational& scale = Rational(1));
  Measure operator()(const Measure& inner, const Measure& outer) const;

 private:
  enum class Kind { none, centre, paraboloid } kind_ = Kind::none;
  Measure scale_ = 0, d0_ = 0;                   ///< |scale|, |c - y0|
  Measure r_ = 0, steady_ = 0, linear_ = 0;      ///< centre: |r|, sqrt(lambda |r|), sqrt(mu) (K invertible)
  Measure kn_ = 0, a0_ = 0, sigma_ = 0, mu_ = 0; ///< paraboloid: |k_n|, |A(y0)|, sigma, mu
  Measure dv_ = 0;                               ///< paraboloid: |c - its vertex|
  /// centre (K invertible): (gamma, c) with |K y|^2 >= gamma |y|^2 + c on A (the S-lemma, header)
  std::vector<std::pair<Measure, Measure>> certificates_;
  bool grows_ = false;                           ///< a paraboloid (the kernel is k_n's line)
  bool flat_ = false;                            ///< a parabolic cylinder (the kernel a plane, k_n in it)
};

/// The floor over the whole ball: GradientFloor(A, ball)(0, reach).
Measure gradient_floor(const Mat4<Rational>& A, const Ball& ball);

/// Directions (Cartesian, exact) along which the spatial part K of a quadric curves up and down:
/// up^T K up > 0 > down^T K down, K = ref_xyz,xyz (symmetrised). They exist exactly where K is
/// indefinite: a cone, a plane pair whose planes cross, a hyperboloid. (Found from a floating
/// eigen-decomposition, the signs proved on the exact K.)
struct SaddleDirections {
  Vec3<Rational> up, down;
};
/// A candidate's symmetric part (Q + Q^T) / 2 (Q itself where symmetric): its surface x^T Q x = 0, and
/// the gradient of that (measure_quadric, the certified bounds measure it).
Mat4<Rational> symmetric_part(const Mat4<Rational>& Q);
/// The symmetrised spatial part (Q_xyz,xyz + its transpose) / 2 of a quadric: x^T Q x's quadratic part.
Mat3<Rational> spatial_part(const Mat4<Rational>& Q);
/// Eigenvectors of a floating symmetric matrix (a spatial part, scaled by the caller into double's
/// range), by increasing eigenvalue, made exact: directions to try, whose curvatures are then computed
/// exactly (saddle_directions; measure_quadric's second-order distance). None where it fails.
std::optional<std::array<Vec3<Rational>, 3>> eigen_directions(const Eigen::Matrix3d& K);
std::optional<SaddleDirections> saddle_directions(const Mat4<Rational>& ref);

/// min(up^T H up / |up|^2, -down^T H down / |down|^2) for H = hat_xyz,xyz (symmetrised), where both
/// are positive; 0 otherwise. Along the line x + t u, u = (up, 0), hat's form is exactly
/// a + 2 b t + c t^2, a = x^T hat x, c = up^T H up: where a <= 0 < c it has a root with
/// |t| |up| <= sqrt(|a| / (c / |up|^2)), and with `down` where a >= 0. So every point x is within
/// sqrt(|x^T hat x| / curvature) of hat's zero set (Euclidean distance), gradient or not.
Measure saddle_curvature(const Mat4<Rational>& hat, const SaddleDirections& d);
/// Both of saddle_curvature's curvatures, up^T H up / |up|^2 and -down^T H down / |down|^2, each 0
/// where not positive: where x^T hat x < 0 the first alone bounds the distance (the root along
/// `up`), where it is > 0 the second alone.
struct SaddleCurvatures {
  Measure up = 0, down = 0;
};
SaddleCurvatures saddle_curvatures(const Mat4<Rational>& hat, const SaddleDirections& d);

/// A floor of a reference's gradient over the zero set in a shell of a ball: (inner, outer) -> floor.
using ShellFloor = std::function<Measure(const Measure& inner, const Measure& outer)>;

/// Floors, over the geometry in a ball, of the reference's slope along its saddle directions:
/// |(ref x)_xyz . up| / |up| and |(ref x)_xyz . down| / |down| (0: none). Along a unit w the form of a
/// result hat near ref is a + 2 b t + c t^2 with c its exact curvature along w, so where a < 0 < c
/// along `up` (a > 0 > c along `down`) a root of hat lies within |a| / (2 |b|), whatever the
/// curvature along the gradient (ball_quadric_bound).
struct SaddleSlopes {
  SaddleDirections directions;
  Measure up = 0, down = 0;
};
/// For P_ref = s A - pi pi^T on the terminator (pi . x = 0), where (P_ref x)_xyz = s (A x)_xyz:
/// |s| times terminator_plane_floor of the plane A (w, 0) over |w|, for P_ref's saddle directions
/// w; nullopt where P_ref has none or neither slope has a floor.
std::optional<SaddleSlopes> terminator_saddle_slopes(const Mat4<Rational>& A, const Vec4<Rational>& pi, const Ball& ball,
                                                     const Rational& s, const Mat4<Rational>& P_ref);

/// The section's own quadric: C = Pr^T A Pr + nu pi pi^T, Pr the orthogonal projection onto the plane
/// pi (x -> x - n (n . x + pi_w) / |n|^2, n = pi_xyz) and nu |n|^2 a power of 2 near |A_xyz,xyz|_F.
/// At a point x of the section A ∩ pi, C(x) = A(x) = 0 and (C x)_xyz = Pr_xyz (A x)_xyz, the part of
/// A's gradient along the plane: |(C x)_xyz| <= |(A x)_xyz|. C is the section's conic extruded along
/// n, with n an eigenvector of C's spatial part (eigenvalue nu |n|^2): its spatial part is invertible
/// where the conic's is, so a GradientFloor of C sees the conic's own curvature, not A's.
Mat4<Rational> section_quadric(const Mat4<Rational>& A, const Vec4<Rational>& pi);

/// gamma >= 0 with |K y|^2 >= gamma |y|^2 for every y on the cone y^T K y = 0 in the plane n . y = 0
/// (K symmetric), proved exactly by the S-lemma's certificate: S = K^2 - tau K - mu n n^T - gamma I
/// positive definite (Sylvester, exact) gives y^T K^2 y = y^T S y + tau y^T K y + mu (n . y)^2 +
/// gamma |y|^2 >= gamma |y|^2 there. tau from a floating maximisation of the least eigenvalue of
/// K^2 - tau K on the plane, mu negative enough; 0 where no certificate is found (a direction of
/// the plane on the cone where K y = 0).
Rational cone_section_floor(const Mat3<Rational>& K, const Vec3<Rational>& n);

/// A floor of |scale (A x)_xyz| over the terminator's points x (A ∩ pi) in a shell of the ball: the
/// larger of GradientFloor(A) and GradientFloor(section_quadric(A, pi)) (both hold there), and for a
/// cone whose apex V lies on pi, sqrt(cone_section_floor(K, pi_xyz)) (inner - |c - V|). A's own
/// floor is over all of A in the shell: a nearly flat cone (eigenvalues -1, 1e-6, 1) lit along its
/// flat direction had a floor 1e6 below its gradient on the terminator (500 below with A's S-lemma
/// floor), and P was bounded at 8e-6 where its error was 7e-12 (audit 39a F1); on the section's
/// lines, which are not flat, the gradient is 0.58 |x - V| and more.
ShellFloor terminator_gradient_floor(const Mat4<Rational>& A, const Vec4<Rational>& pi, const Ball& ball,
                                     const Rational& scale);

/// Ball bounds: the first-order distance of the returned `hat` (frame with `origin`) over every
/// point x of the ball where the exact reference `ref` vanishes, relative to `size`. With lambda
/// (the scale of hat nearest ref), E = hat - lambda ref_o and z = z0 + (y, 0), z0 = (c - o, 1), on
/// each shell r_in <= |y| <= r_out of the ball (radii reach (3/4)^j, and 0):
///   |z^T E z| <= |z0^T E z0| + 2 r_out |(E z0)_xyz| + r_out^2 |E_xyz,xyz|_F,
///   |(hat z)_xyz| >= |lambda| floor(r_in, r_out) - |(E z0)_xyz| - r_out |E_xyz,xyz|_F,
/// and the distance there is at most the first over twice the second; or, second order, where the
/// reference is indefinite (saddle_directions), at most sqrt(first / saddle_curvature(hat)), the
/// Euclidean distance (on the reference's zero set x^T hat x = z^T E z): the smaller counts, and the
/// bound is the largest over the shells (a plane: (|eps . z0| + reach |eps_xyz|) / |hat_xyz|, eps =
/// hat - lambda ref_o). The second order is what bounds the shells around a point where the
/// reference's gradient vanishes (a cone's apex, where a rounded cone is a hyperboloid about
/// sqrt(eps) away; the crossing of R's planes), and flags the result `euclidean`.
/// Infinite where a shell has neither. Coarser than the branch and bound (no
/// parameters), the shells keep it within a small factor of a rounded result's error where the
/// reference's gradient grows with the distance (hyperboloids, paraboloids).
/// `euclidean_only` (`ref` symmetric): every shell bounds the Euclidean distance (ball_plane_pair_bound
/// adds it to one): first order where the gradient bound G of the symmetrised form and h =
/// |(hat + hat^T)_xyz,xyz / 2|_F give G^2 >= V h (V the value's
/// bound; then a root lies within V / G along the gradient: along a unit u the form is a + 2 b t +
/// c t^2, |c| <= h, b >= G), else second order.
/// `within`: a plane (world frame) that holds every point of the geometry (the terminator's polar
/// plane): the value is bounded from E less its part w e^T + e w^T (plane_pair_part), which
/// vanishes on the plane; the gradient from E whole.
/// The motion part (not `euclidean_only`, ref symmetric): E = lambda (ref V + V^T ref) + E_m, V an
/// infinitesimal affine motion (last row 0; least squares in the ball's frame); on the geometry
/// z^T hat z = z^T E_m z + 2 lambda (ref z)_xyz . (V z)_xyz, so with F the floor and e >= |(E z)_xyz|
/// the first-order distance is also at most |z^T E_m z| / (2 (F - e)) + |(V z)_xyz| F / (F - e): a
/// result moved or turned a little is bounded by how far its points moved; and, second order where
/// the reference is indefinite, at most |(V z)_xyz| + sqrt(|hat(z - V z)| / saddle_curvature(hat)),
/// hat(z - V z) = z^T E_m z - 2 (E z)_xyz . (V z)_xyz + (V z)_xyz^T hat_xyz (V z)_xyz (a plane pair
/// or a cone moved, where its gradient vanishes). The smallest counts.
/// `slopes` (for the reference's saddle_directions): with a root along a saddle direction w from the
/// linear term too (SaddleSlopes), where the value may have the sign w serves.
CertifiedBound ball_quadric_bound(const Mat4<Rational>& hat, const Mat4<Rational>& ref, const Ball& ball,
                                  const std::optional<Vec3<Rational>>& origin, const ShellFloor& floor, double size,
                                  bool euclidean_only = false, const Vec4<Rational>* within = nullptr,
                                  const SaddleSlopes* slopes = nullptr);
/// The e of E's part w e^T + e w^T nearest E (Frobenius), exact: e = (E w - w (w.E w) / (2 w.w)) / w.w.
Vec4<Rational> plane_pair_part(const Mat4<Rational>& E, const Vec4<Rational>& w);
CertifiedBound ball_plane_bound(const Vec4<Rational>& hat, const Vec4<Rational>& ref, const Ball& ball,
                                const std::optional<Vec3<Rational>>& origin, double size);

/// A ball about an elliptic cylinder seen in coordinates turned to its axes, for ball_quadric_bound:
/// world x = turn x', turn an exact rotation (rational, from a quaternion of 30-bit components
/// near the one of a floating eigen-decomposition of K, so orthogonal exactly: distances and
/// gradients' lengths are the same in both), and `ball` (turned) with a box (Ball::half) of the
/// cylinder's part in it: along each turned axis u, |u . (x - c)| <= |u . (y0 - c)| + reach |u . a|
/// / |a| + sqrt(|r| u^T K^+ u) for the cylinder's points x = y0 + y + t a (y0 its axis point nearest
/// the centre c, y across the axis a with y^T K y = -r, |t a| <= reach), K^+ = (K + a a^T / |a|^2)^-1
/// - a a^T / |a|^2 exactly. In world axes a box did not help a turned cylinder, and the ball's
/// cross terms counted the whole ball where the cylinder is thin: a reflection of a cylinder of
/// semi-axes 1 and 100, sampled 1600 out along its axis, was bounded at 300 times its largest
/// error (audit 33a F3). nullopt where `ref` is not an elliptic cylinder with real points.
struct TurnedBall {
  Mat3<Rational> turn;
  Ball ball;
};
std::optional<TurnedBall> cylinder_turn(const Mat4<Rational>& ref, const Ball& ball);

/// The floor of a plane pair p q^T + q p^T's gradient on p in the shells of a ball: there it is
/// (q . x) p_xyz, and |q . x| >= |q . (c, 1)| - outer |q_xyz| (0 where q crosses the shell).
ShellFloor plane_pair_floor(const Vec4<Rational>& p, const Vec4<Rational>& q, const Ball& ball);

/// A result hat whose reference is a plane pair p q^T + q p^T (R = pi h^T + h pi^T) whose planes cross
/// in the ball, over the points of p in it, in two steps. A rounded plane pair is a hyperboloid about
/// sqrt(eps) from the line where the planes cross, but hat = p' q^T + q p'^T + F, p' = lambda p + e,
/// is one whose error is mostly e (a rounded p), and F small: with q exact in its frame (h = (0, 0,
/// 1, 0) in a frame at the light's height) F is of the order of eps^2. So, with R' = p' q^T + q p'^T
/// (exact, e from E = hat - lambda pq's part of that form): a point x of p is within
/// d1 = |p' . x| / |p'_xyz| of p', on R' (ball_plane_bound), and that point of p' within d2 of hat
/// (ball_quadric_bound against R' in the ball grown by d1: first order where (q . y) p'_xyz has a
/// floor, second order, sqrt(|F| ...), near the line); the bound is (d1 + d2) / size, `euclidean`.
/// Also the other split, hat = p q'^T + q' p^T + F', q' = lambda q + f (a second plane tilted: R
/// made with a second plane off h), in one step (the points lie on p, a plane of it); the smaller
/// bound counts. hat's symmetric part is bounded (an antisymmetric one is no quadric's).
CertifiedBound ball_plane_pair_bound(const Mat4<Rational>& hat, const Vec4<Rational>& p, const Vec4<Rational>& q,
                                     const Ball& ball, const std::optional<Vec3<Rational>>& origin, double size);

}  // namespace qverify
