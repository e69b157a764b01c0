#pragma once
/// \file frames.hpp
/// Local frames for the robust floating-point path (cli.md, "origin").
///
/// A double matrix in world coordinates cannot hold a small object far from
/// the world origin: |c|^2 - r^2 loses r^2 when |c| >> r. So each item may be
/// computed in a frame x_local = x - origin, with the origin a double near the
/// object. The inputs are carried to that frame *exactly* (the scene's numbers
/// are exact) and rounded once there:
///   Q_local = T^T Q T,  plane_local = T^T plane,  L_local = T^-1 L,
///   M_local = T^-1 M T,  T = translation by origin.

#include <qverify/exact/rounding.hpp>  // floor_log2, exact_pow2
#include <qverify/scene/scene.hpp>

#include <optional>

namespace qverify {

/// 4x4 translation by v.
template <class S> Mat4<S> translation(const Vec3<S>& v) {
  Mat4<S> T = Mat4<S>::Identity();
  T.template topRightCorner<3, 1>() = v;
  return T;
}

/// The natural centre of a quadric: the shape's centre, point or apex; for a
/// matrix, the centre -K^-1 k when the quadratic part K is invertible.
std::optional<Vec3<Rational>> natural_center(const QuadricSpec& q, const Mat4<Rational>& A);

/// The object's size estimate sqrt(|c0| / |K|_max) with c0 the constant term
/// in its own frame (the radius of a sphere); 0 for a cone (c0 = 0: no length of its own, and a
/// frame at its apex wherever that is off the origin, in any units: its rounded matrix is a
/// hyperboloid about sqrt(eps) |apex| off near the apex, where its gradient vanishes; a cone at
/// (0, 0, 5) kept the world frame below 64 units and was flagged, audit 31a F6); 1 for a plane, and
/// for a quadric without a centre of its own on it (a plane pair about a point of its crossing line).
Rational size_squared(const Mat4<Rational>& A_local);

/// The nearest double to each coordinate (an exactly representable origin).
Vec3<Rational> rounded_to_double(const Vec3<Rational>& v);

/// Should an object of squared size s2 at `center` be computed in a local
/// frame? When |center|_inf > 64 size (more than 12 bits would be lost).
bool wants_local_frame(const Vec3<Rational>& center, const Rational& s2);

/// Does the plane h of a point light L, z = l_z (R's second plane: R = pi h^T + h pi^T, pi = A L),
/// meet A's terminator, or nearly? (Exact: the line pi ∩ h restricted to A is a t^2 + 2 b t + c, and
/// b^2 - a c >= 0, or, nearly, A's least value on the line, (a c - b^2) / a, within |A(centre)| / 64
/// of 0: a sphere's line at most 1.008 radii from its centre.) Where it does, a rounded R is a hyperboloid about sqrt(eps)
/// from the terminator's points on the line where R's planes cross (no rounding of a plane pair's
/// products keeps its rank), and the robust path computes the item in a frame at the light's height
/// (light_height_origin): there h = (0, 0, 1, -d) with d tiny or 0, and R's entries are pi's, exact.
bool light_plane_meets_terminator(const Mat4<Rational>& A, const Vec4<Rational>& L);

/// Does a shadow item want the frame at the light's height? For an ellipsoid where h meets the
/// terminator (which is bounded), or cuts the ellipsoid, or nearly (its least value on h within
/// |A(centre)| / 64 of 0: R's planes close together over the terminator, a lamp just above a sphere's
/// top); for a quadric without a centre (a paraboloid) where h meets the
/// terminator; for a line of centres (a cylinder, whose given centre is any point of its axis)
/// wherever the light's height is within 64 radii (beyond the 16 half-widths its samples reach) of the lamp's
/// foot on the axis (shadow_origin puts the frame there); for another quadric with a centre wherever
/// the light's height is within 4 sizes of it
/// (s2 = size_squared), met or not: its terminator may be unbounded, and is
/// bounded in a ball about the sampled points, which R's crossing line may cross away from the
/// terminator; and farther, where h meets the terminator inside the ball of the item's default
/// sample (an unbounded terminator's sample reaches many of the quadric's own sizes: a two-sheet
/// hyperboloid lit from 4.2 sizes below had R truly 1e-9 to 1.1e-8 of the object's size off at the
/// crossing points in its own frame, 1e-17 at the light's height). Elsewhere (a cylinder's
/// terminator crossed far from its centre, say) the first-order bound in the item's ball holds, and
/// a frame there would only put the object away from its origin.
bool wants_light_height_frame(const Mat4<Rational>& A, const Vec4<Rational>& L,
                              const std::optional<Vec3<Rational>>& centre, const Rational& s2);

/// The origin o (or 0) with its z the light's height rounded to a double.
Vec3<Rational> light_height_origin(const std::optional<Vec3<Rational>>& o, const Vec4<Rational>& L);

/// The frame the direct route computes a shadow item in (o: the quadric's own local frame, or none).
/// A line of centres (a cylinder): the item's base point on the axis (accuracy.hpp, item_base: the
/// lamp's foot, or under a parallel light the point nearest the world origin), where the terminator
/// is sampled, with its z the light's height where
/// wants_light_height_frame; rounded to doubles. (The scene's point of the axis may lie anywhere
/// along it: a lamp 1e8 away put the samples 7.6e7 from a frame there, where a double P was 6.8e-4
/// off; and the axis point at the light's height, tried first, is 2e9 away along an axis 1e-9 from
/// level: audit 32a F3, F4.) Otherwise the frame at the light's height where
/// wants_light_height_frame, else o. A cone lit by a lamp: always above its apex (o, where a double
/// holds the apex; else the world origin) at the light's
/// height. Its P is the pair of planes through the lamp and the generators, whose gradient vanishes
/// on the terminator at the apex, and R's gradient where h crosses the terminator: rounded, each is
/// about sqrt(eps) times the origin's distance from that point off there, and no one frame holds
/// both; here R rounds as pi does, and P is off at the apex by about sqrt(eps) |dz| (dz the
/// lamp's height above the apex), within the target wherever |dz| is a small part of the
/// cone's sampled stretch (16 lamp distances). (The rule was 4 units of the scene: a cone's
/// flags changed with the scene's units.)
std::optional<Vec3<Rational>> shadow_origin(const Mat4<Rational>& A, const Vec4<Rational>& L,
                                            const std::optional<Vec3<Rational>>& o,
                                            const std::optional<Vec3<Rational>>& centre, const Rational& s2);

inline Mat4<Rational> quadric_to_local(const Mat4<Rational>& A, const Vec3<Rational>& o) {
  const Mat4<Rational> T = translation<Rational>(o);
  return T.transpose() * A * T;
}
inline Mat4<Rational> quadric_from_local(const Mat4<Rational>& A, const Vec3<Rational>& o) {
  const Mat4<Rational> T = translation<Rational>(Vec3<Rational>(-o));
  return T.transpose() * A * T;
}
inline Vec4<Rational> plane_from_local(const Vec4<Rational>& p, const Vec3<Rational>& o) {
  return translation<Rational>(Vec3<Rational>(-o)).transpose() * p;
}
inline Vec4<Rational> point_to_local(const Vec4<Rational>& L, const Vec3<Rational>& o) {
  return translation<Rational>(Vec3<Rational>(-o)) * L;
}

}  // namespace qverify
