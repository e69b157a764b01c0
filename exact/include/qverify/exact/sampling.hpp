#pragma once
/// \file sampling.hpp
/// Exact, deterministic (seeded) sample points on quadrics and on plane
/// sections of quadrics (the terminator A ∩ polar plane).
///
/// Method: a rational base point b at the object (A's centre, a point of its axis of centres, a point
/// inside a paraboloid on its axis; for a section, the conic's centre, else the foot of that point on
/// the plane: never the world origin, which may be far from the object) and a random
/// rational direction u (inside the plane, for a section); the line b + t u
/// meets A where alpha t^2 + 2 beta t + c = 0, at
///   x = b - (beta/alpha) u +- sqrt(beta^2 - alpha c) (u/alpha),
/// a point of Q(sqrt(delta))^4 (RootPoint). Directions with delta < 0 miss
/// the quadric and are drawn again. The arithmetic is on integers (A, b and u
/// scaled by positive factors, which change neither the quadric nor the line;
/// one gcd per coordinate at the end). A singular section (a line pair, a double
/// line, a single real point) also contributes its exact rational singular
/// point(s), so a terminator that is a single point is still sampled.

#include <qverify/exact/root_point.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace qverify {

struct SampleReport {
  std::vector<RootPoint> points;
  long long attempts = 0;  ///< lines drawn
  bool exhausted = false;  ///< fewer points than asked were found
  /// The middle of the stretch sample_section or sample_quadric draws, from which its ends are the
  /// farthest points: a pair of parallel lines' midline point its chords pass through, a hyperbola's
  /// centre, the middle of a parabola's stretch of axis, a single line's point nearest the base; of
  /// sample_quadric's axial sections and prisms, a hyperboloid's or cone's centre, the middle of a
  /// paraboloid's or parabolic cylinder's stretch of axis, a plane pair's or a plane's base point
  /// (unset for an ellipsoid and a cylinder, whose centre is known). (The object size is measured
  /// from it where A has no centre of its own: eval/accuracy.hpp.)
  std::optional<Vec3<Rational>> middle;
  /// How many points the sample's farthest ones are, drawn first (a parallel pair's 4 chord ends, a
  /// hyperbola's two end chords' 4, a parabola's end chord's 2, and on a hyperboloid its point
  /// farthest from A's centre where that lies inside its stretch, a single line's 2 ends; of a
  /// quadric, an ellipsoid's 2, its axial sections' or prism's end lines' points): fewer than that do
  /// not reach its size (0: no such ends).
  int ends = 0;
};

/// A quadric's core, exactly. With K = A_xyz,xyz and k = A_xyz,w: a basis of K's kernel (none where
/// K is invertible), k_n, k's part in that kernel (0 where A has a centre or an axis of centres; not
/// 0 for a paraboloid, a parabolic cylinder, a plane), and a point y with K y = -(k - k_n): A's
/// centre, a point of its axis of centres, a point of a paraboloid's axis. K y + k does not change
/// along the kernel, so neither does A where k_n = 0. `found` is false where no such y was found
/// (not expected: k - k_n lies in K's range). Shared by the sampler's base point and the certified
/// bounds' gradient floors (eval/certified_bound.hpp).
struct QuadricCore {
  Eigen::Matrix<Rational, 3, Eigen::Dynamic> kernel;
  Vec3<Rational> kn, y;
  bool found = false;
  /// y moved along the kernel to the point of its line (plane) nearest p.
  Vec3<Rational> nearest(const Vec3<Rational>& p) const;
  /// Where A has no centre (k_n != 0: a paraboloid, a parabolic cylinder, a plane), A's point on the
  /// line p + t k_n (its vertex where p is a core point; a plane's foot of p): A(p + t k_n) = A(p) +
  /// 2 t |k_n|^2 (K k_n = 0 and k_n . (K p + k) = |k_n|^2 for p in the core; for a plane, K = 0 and
  /// k = k_n, for any p), 0 at t = -A(p) / (2 |k_n|^2).
  Vec3<Rational> vertex(const Mat4<Rational>& A, const Vec3<Rational>& p) const;
  /// A line of centres (an elliptic or hyperbolic cylinder, a pair of crossing planes): K's kernel a
  /// line, k in K's range.
  bool line_of_centres() const { return found && kernel.cols() == 1 && kn.isZero(); }
};
QuadricCore quadric_core(const Mat4<Rational>& A);

/// A's value at the Cartesian point y: y^T K y + 2 k . y + A_ww.
Rational quadric_value(const Mat4<Rational>& A, const Vec3<Rational>& y);

/// The point sample_section draws its lines through, a function of A, pi and `anchor` alone: the
/// centre of the section A ∩ {pi . x = 0} (the pole of its line at infinity) where that is a finite
/// point, else the foot on the plane of A's core point (a parabola's section, a degenerate one);
/// where A's core is a line or a plane (a cylinder's axis), its point nearest `anchor` (a point
/// light: the base then moves with the scene, which a factorisation's particular solution does not).
/// Finite; pi's normal must not be zero. (verify's check of R on its second plane starts from it:
/// eval/accuracy.hpp, second_plane_error.)
Vec4<Rational> section_base(const Mat4<Rational>& A, const Vec4<Rational>& pi,
                            const std::optional<Vec3<Rational>>& anchor = std::nullopt);

/// The centre the object size is measured from (eval/accuracy.hpp), where A has one: its centre
/// (K invertible); where A has a line or a plane of centres (a cylinder, a plane pair), the one
/// nearest `anchor` (the point sample_section and sample_quadric draw their lines about:
/// quadric_base): a cylinder's axis point nearest its lamp, about which its sample is symmetric, not
/// the sample's centroid, which moved with the sample. nullopt where A has none (a paraboloid).
std::optional<Vec3<Rational>> centre_of_core(const Mat4<Rational>& A, const std::optional<Vec3<Rational>>& anchor);

/// The point sample_quadric draws its lines through, a function of A and `anchor` alone: A's centre,
/// the point of its axis (plane) of centres nearest `anchor` (any where none is given), a point
/// inside a paraboloid on its axis. Finite.
Vec4<Rational> quadric_base(const Mat4<Rational>& A, const std::optional<Vec3<Rational>>& anchor = std::nullopt);

/// The length the samplers step by (`reach`) where no line through their base point meets the
/// geometry (the base is a cone's apex, which every line through it only touches): for a point
/// light (w != 0) the L-infinity distance of the base b (finite) from it, a length of the item
/// (moving the scene or changing its units moves the points with it); else 1, in the scene's units.
/// A cone under a parallel light, or a cone's reflection (the mirror's distance is not a length of
/// A), has no length of its own: it is sampled by unit steps from its apex, so that its object
/// size, and the relative errors, do not move with its placement (a step of its apex's distance
/// from the origin passed a polar plane moved by 0.01 units at apex 1e6, failed it at the origin)
/// nor with the mirror's (a reflection stepped by the mirror's distance passed B moved by 0.02
/// units with the mirror at 1e7). Its steps once came from the primitive integers of the plane's
/// normal, whatever the units: points 1e7 to 1e9 units from a 3-unit cone's apex, where every
/// result within 0.01 of the terminator passed.
Rational reach_length(const Vec4<Rational>& b, const Vec4<Rational>& light);

/// Up to n points of A ∩ {pi . x = 0}, all finite, on lines through section_base(A, pi, anchor)
/// (a parabola: chords across its axis from bases on it; a single line: its own rational points).
/// A hyperbola's or a parabola's seeded points farther than its ends from the point its size is
/// measured from (A's centre, or centre_of_core) are dropped (up to n of them), so that the ends size
/// it (a parabola on a hyperboloid: its end chord and its farthest point inside the stretch).
/// Where no line through the base point meets the
/// section (the base is a cone's apex, which every line through it only touches) the base moves
/// within the plane by steps of L-infinity length `reach` (> 0: reach_length), and the points kept
/// lie within 16 such lengths of the moved base (lines nearly parallel to a generator meet it
/// far out: the object size would be theirs).
SampleReport sample_section(const Mat4<Rational>& A, const Vec4<Rational>& pi, int n, std::uint64_t seed,
                            const Rational& reach, const std::optional<Vec3<Rational>>& anchor = std::nullopt);

/// Up to n finite points of A, on a fixed stretch of it whose farthest points from the point its size
/// is measured from (A's centre, centre_of_core, or SampleReport::middle) are drawn first
/// (SampleReport::ends), seeded points farther than they dropped, so that its size is the same at
/// every seed and count: an ellipsoid all over, its longest axis's ends first; a cylinder within 16
/// cross-section radii of its axis point nearest `anchor`; a hyperboloid, a cone, a paraboloid as
/// its sections across an axis out to 4 times its waist or vertex, 16 `reach` (> 0; eval takes 1, in
/// the scene's units: a cone has no length of its own) or 16 focal lengths; a parabolic cylinder, a
/// plane pair, parallel planes, a plane by lines across their sections (sampling.cpp says how far).
/// Elsewhere (a point, a line, a
/// double plane) on lines through quadric_base(A, anchor), the base moving by steps of L-infinity
/// length `reach` where no line through it meets A, the points kept then within 16 such lengths of
/// the moved base.
SampleReport sample_quadric(const Mat4<Rational>& A, int n, std::uint64_t seed, const Rational& reach,
                            const std::optional<Vec3<Rational>>& anchor = std::nullopt);

/// Whether A has no real point at all, not even at infinity: A definite (exactly, Sylvester's leading
/// minors; x^T A x = 0 has a real solution x != 0 exactly where A is not definite). A quadric with
/// real points at infinity only (an imaginary cylinder x^2 + y^2 = -1: (0, 0, 1, 0)) is not.
bool without_real_points(const Mat4<Rational>& A);

}  // namespace qverify
