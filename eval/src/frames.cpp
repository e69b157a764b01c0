#include <qverify/core/predicates.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/eval/frames.hpp>

#include <limits>

namespace qverify {

using Q = Rational;

std::optional<Vec3<Q>> natural_center(const QuadricSpec& q, const Mat4<Q>& A) {
  auto v3 = [&](std::size_t i) { return Vec3<Q>(q.params[i].value, q.params[i + 1].value, q.params[i + 2].value); };
  switch (q.shape) {
    case Shape::sphere:
    case Shape::ellipsoid:
    case Shape::cylinder:
    case Shape::cone: return v3(0);
    case Shape::matrix:
    case Shape::coefficients: {
      const Mat3<Q> K = A.topLeftCorner<3, 3>();
      if (K.determinant() == 0) return std::nullopt;
      return Vec3<Q>(-(K.inverse() * Vec3<Q>(A.topRightCorner<3, 1>())));
    }
  }
  return std::nullopt;
}

Q size_squared(const Mat4<Q>& A_local) {
  const Q k = max_abs(Mat3<Q>(A_local.topLeftCorner<3, 3>()));
  const Q c0 = A_local(3, 3) < 0 ? Q(-A_local(3, 3)) : A_local(3, 3);
  if (k == 0) return Q(1);
  // (0 for a cone: no size of its own, so any apex off the origin gets a frame there; a plane pair's
  // point on its crossing line keeps 1)
  if (c0 == 0) return Mat3<Q>(A_local.topLeftCorner<3, 3>()).determinant() != 0 ? Q(0) : Q(1);
  return c0 / k;
}

Vec3<Q> rounded_to_double(const Vec3<Q>& v) {
  Vec3<Q> out;
  for (int i = 0; i < 3; ++i) {
    RoundingReport rep;
    out(i) = to_rational(round_rational<double>(v(i), rep));
  }
  return out;
}

namespace {
/// Does a double hold x's magnitude (|x| at most the largest finite double)? An origin rounded to
/// double beyond it would be an infinity, and to_rational of that 0: no frame is placed there.
bool double_holds(const Q& x) {
  static const Q largest = to_rational(std::numeric_limits<double>::max());
  return abs(x) <= largest;
}
}  // namespace

namespace {
/// A line of centres (an elliptic or hyperbolic cylinder): K's kernel a line, k in K's range.
bool has_line_of_centres(const Mat4<Q>& A) { return quadric_core(A).line_of_centres(); }

/// A cone: a centre (K invertible) on the quadric (its apex).
bool is_cone(const Mat4<Q>& A) {
  const QuadricCore core = quadric_core(A);
  return core.found && core.kernel.cols() == 0 && quadric_value(A, core.y) == 0;
}
}  // namespace

bool wants_local_frame(const Vec3<Q>& center, const Q& s2) {
  const Q c = max_abs(center);
  return c * c > Q(64 * 64) * s2 && double_holds(c);
}

namespace {
/// A(centre), K = A's spatial part invertible: the value the "nearly" tests below compare with.
Q centre_value(const Mat4<Q>& A) {
  const Vec3<Q> b = A.topRightCorner<3, 1>();
  return A(3, 3) - b.dot(Mat3<Q>(A.topLeftCorner<3, 3>()).inverse() * b);
}
}  // namespace

namespace {
/// Does h meet the terminator (exactly) at a point within the ball of the item's default sample
/// (terminator_points: the object size about its centre, where the bounds look)? The points in 80
/// digits (terminator_crossings): a choice of frame, not a predicate of the output.
bool crossing_in_sample(const Mat4<Q>& A, const Vec4<Q>& L) {
  const std::vector<Vec3<Q>> at = terminator_crossings(A, Vec4<Q>(A * L), reference_second_plane(L));
  if (at.empty()) return false;
  const ItemPoints pts = terminator_points(A, L, kDefaultSamples, item_seed(1, 1, A, L));
  if (pts.points.empty()) return false;
  for (const Vec3<Q>& x : at)
    if (Vec3<Q>(x - pts.ball.centre).squaredNorm() <= pts.ball.reach * pts.ball.reach) return true;
  return false;
}
}  // namespace

bool light_plane_meets_terminator(const Mat4<Q>& A, const Vec4<Q>& L) {
  if (L(3) == 0) return false;  // a parallel light: h is the plane at infinity
  const Vec4<Q> pi = A * L;
  const Q l = L(2) / L(3);
  // the line pi ∩ {z = l}: pi_x x + pi_y y = -(pi_z l + pi_w) in that plane
  const Q rhs = -(pi(2) * l + pi(3));
  Vec4<Q> x0(0, 0, l, 1), d(-pi(1), pi(0), 0, 0);
  if (abs(pi(0)) >= abs(pi(1))) {
    if (pi(0) == 0) return false;  // the planes are parallel (or the same: R is then pi's double plane)
    x0(0) = rhs / pi(0);
  } else {
    x0(1) = rhs / pi(1);
  }
  const Q a = d.dot(A * d), b = d.dot(A * x0), c = x0.dot(A * x0);
  if (a == 0 && b == 0) return c == 0;  // A constant on the line
  const Q disc = b * b - a * c;
  if (disc >= 0) return true;
  // nearly: on the line A's value comes within |A(centre)| / 64 of 0 (a = 0 with disc < 0: b = 0,
  // A constant on the line). Both sides move with A's scale alone, not with units or placement.
  if (a == 0 || Mat3<Q>(A.topLeftCorner<3, 3>()).determinant() == 0) return false;
  return abs(Q(disc / a)) <= abs(centre_value(A)) / 64;
}

namespace {
/// An ellipsoid (K definite of sign s): does the plane z = l cut it, or nearly: s A's least value on
/// the plane, c - v^T K2^-1 v (K2 the upper-left 2 x 2 of s K, v and c of s A at z = l), within
/// |A(centre)| / 64 of 0 (a sphere's plane at most 1.008 radii from its centre)?
bool height_plane_nearly_meets(const Mat4<Q>& A, int s, const Q& l) {
  const Mat4<Q> S = Q(s) * A;
  const Eigen::Matrix<Q, 2, 2> K2 = S.topLeftCorner<2, 2>();
  const Eigen::Matrix<Q, 2, 1> v = S.block<2, 1>(0, 2) * l + S.block<2, 1>(0, 3);
  const Q c = S(2, 2) * l * l + 2 * S(2, 3) * l + S(3, 3);
  const Q least = c - v.dot(K2.inverse() * v);
  return least <= abs(centre_value(A)) / 64;
}
}  // namespace

bool wants_light_height_frame(const Mat4<Q>& A, const Vec4<Q>& L, const std::optional<Vec3<Q>>& centre, const Q& s2) {
  if (L(3) == 0) return false;  // a parallel light: h is the plane at infinity
  if (!double_holds(Q(L(2) / L(3)))) return false;  // (a height no double holds: no frame there)
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  // An ellipsoid: its terminator is bounded. Where h cuts the ellipsoid or nearly, which it does where
  // it meets the terminator (or nearly: A's least value on the line pi ∩ h is no less than on h):
  // also where it meets the terminator nowhere near, R's planes, pi and h, lie close together over
  // the terminator (parallel: a lamp just above a sphere's top), and R's rounded products in world
  // coordinates lose one of them: a unit sphere lit from 1e-7 above its top had R bounded (and off)
  // at 1.15e-9, in the frame at the light's height 1e-23 (audit 38a F2). The frame there lies within
  // the ellipsoid's height, where it costs P and the polar plane nothing.
  if (const int s = *definiteness<Q, 3>(K); s != 0) return height_plane_nearly_meets(A, s, Q(L(2) / L(3)));
  const bool meets = light_plane_meets_terminator(A, L);
  // No centre (a paraboloid): the frame where h meets the terminator, at its height (near the object's
  // part that matters). A centre: wherever the light's height is within 4 sizes of it, also where h misses
  // the terminator: an unbounded terminator is bounded in a ball about the sampled points, and where R's
  // planes cross in that ball, however far from the terminator, a rounded R is bounded only to about
  // sqrt(eps) (a hyperboloid of one sheet lit from inside its waist was flagged at 5.5e-9 against 1e-16
  // attained); in the frame R's entries are pi's, exact.
  // A line of centres (a cylinder): the centre the scene gives is any point of its axis, and its
  // height no length of the item. Its terminator is sampled about the lamp's foot on the axis
  // (item_base), and shadow_origin puts the frame there: at the light's height wherever that is within
  // 64 radii of the foot, beyond the stretch its points are sampled on (16 half-widths of the terminator
  // either side of its middle, the foot: sampling.cpp, ParallelPair; a half-width is at most a radius,
  // and the axis may be steep, so the light's height within the stretch is within 16 radii of the
  // foot's). Where R's planes cross in
  // the ball about those points a rounded R is about sqrt(eps) off; a frame that far above the axis
  // costs P and the polar plane little. (An upright cylinder's foot is at the light's height: a
  // correctly rounded double R of radius 0.7 lit from 7.6 above its given point was bounded at 7.3e-9
  // and failed; the pipe of examples/scenes/mixed-requests.json, its foot 4.75 (9.5 radii) below the
  // light, failed verify at seeds 2, 3, 4, 6 and 8 with 4 radii. Where h crosses the axis far away, as
  // an axis 1e-9 from level does, the frame stays on the axis: audit 32a F3.)
  if (has_line_of_centres(A)) {
    const Q dz = L(2) / L(3) - item_base(1, A, L)(2);
    return dz * dz <= 4096 * s2;
  }
  if (!centre) return meets;
  const Q dz = L(2) / L(3) - (*centre)(2);
  if (dz * dz <= 16 * s2) return true;
  // Farther: where h meets the terminator within the ball its sample reaches (an unbounded terminator
  // reaches many of the quadric's own sizes), R's planes cross there, and in the quadric's frame a
  // rounded R is truly about sqrt(eps) off at those points (a two-sheet hyperboloid lit from 4.2 of
  // its sizes below: 1e-9 to 1.1e-8 of the object's size, flagged; audit 39a). The frame there lies
  // within the object's reach.
  return meets && crossing_in_sample(A, L);
}

Vec3<Q> light_height_origin(const std::optional<Vec3<Q>>& o, const Vec4<Q>& L) {
  Vec3<Q> out = o ? *o : Vec3<Q>::Zero();
  RoundingReport rep;
  out(2) = to_rational(round_rational<double>(Q(L(2) / L(3)), rep));
  return out;
}

std::optional<Vec3<Q>> shadow_origin(const Mat4<Q>& A, const Vec4<Q>& L, const std::optional<Vec3<Q>>& o,
                                     const std::optional<Vec3<Q>>& centre, const Q& s2) {
  if (is_cone(A) && L(3) != 0 && double_holds(Q(L(2) / L(3)))) return light_height_origin(o, L);
  const bool height = wants_light_height_frame(A, L, centre, s2);  // (false for a parallel light)
  if (has_line_of_centres(A)) {
    const Vec3<Q> base = item_base(1, A, L);  // the lamp's foot on the axis (parallel: nearest the origin)
    if (double_holds(max_abs(base))) {
      const Vec3<Q> out = rounded_to_double(base);
      return height ? light_height_origin(out, L) : out;
    }
  }
  return height ? std::optional<Vec3<Q>>(light_height_origin(o, L)) : o;
}

}  // namespace qverify
