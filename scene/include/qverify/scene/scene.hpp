#pragma once
/// \file scene.hpp
/// The scene model of `qverify-scene/1` (docs/scene-format.md).
///
/// Every number is kept as an exact Rational together with the JSON path it
/// came from. A scalar type is chosen only when a typed scene is built
/// (`typed_scene<S>`): each input number is then rounded once, to nearest,
/// and the shapes are turned into matrices in that scalar type.

#include <qverify/core/core.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/scene/input_error.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace qverify {

/// An exact input number and where it was written.
struct Num {
  Rational value;
  std::string path;
  std::string text;  ///< the literal as written (for messages)
};

enum class Shape { matrix, coefficients, sphere, ellipsoid, cylinder, cone };

/// A quadric as written: its shape and its numbers, in the order
///  matrix: 16 entries row by row; coefficients: xx yy zz xy xz yz x y z c;
///  sphere: center[3] radius; ellipsoid: center[3] radii[3] axes[9] (rows);
///  cylinder: point[3] axis[3] radius; cone: apex[3] axis[3] tan_half_angle.
struct QuadricSpec {
  std::string id, path;
  Shape shape = Shape::matrix;
  std::vector<Num> params;
};

struct LightSpec {
  std::string id, path;
  bool parallel = false;  ///< `direction` (L = (-d, 0)) rather than `position` (L = (p, 1))
  std::vector<Num> xyz;
};

struct MirrorSpec {
  std::string id, path;
  std::vector<Num> plane;  ///< a, b, c, d of a x + b y + c z + d = 0
};

struct CameraSpec {
  std::vector<Num> eye, look_at, up;
  Num fov_y_deg;
  long width = 0, height = 0;
};

/// One requested pair: indices into quadrics and lights (or mirrors).
struct Pair {
  std::size_t quadric = 0, other = 0;
};

struct Scene {
  std::string file, name;
  std::vector<QuadricSpec> quadrics;
  std::vector<LightSpec> lights;
  std::vector<MirrorSpec> mirrors;
  std::vector<Pair> shadows, reflections;  ///< requested, in scene order
  bool has_camera = false;
  CameraSpec camera;

  /// Pairs not requested (everything the tool leaves out).
  std::vector<Pair> skipped_shadows() const;
  std::vector<Pair> skipped_reflections() const;
};

/// Reads and validates a scene file. Throws InputError naming the file, the
/// JSON path and the problem; nothing is computed from a rejected scene.
Scene load_scene(const std::string& file);
/// The same from text (`file` only names it in messages).
Scene parse_scene(const std::string& text, const std::string& file);

/// The scene in scalar type S: matrices of the quadrics, homogeneous lights,
/// mirror planes. Each input number is rounded once (exactly kept for exact
/// types), to nearest: a number beyond the range of S to an infinity. Such a
/// scene is legal (numbers have no size limit) and is not refused: its
/// statuses are predicates of the exact inputs, the robust path computes from
/// the exact inputs scaled by powers of two (eval.hpp, rounded_scaled), and an
/// item computed from an infinite input is non-finite, flagged so.
template <class S> struct TypedScene {
  std::vector<Mat4<S>> A;
  std::vector<Vec4<S>> L;
  std::vector<Vec4<S>> planes;
  /// Paths of the inputs that S cannot represent exactly (rounded once), those beyond its range included.
  std::vector<std::string> rounded_inputs;
};

template <class S> S typed_number(const Num& n, TypedScene<S>& ts) {
  RoundingReport rep;
  S v = round_rational<S>(n.value, rep);
  if (rep.inexact || rep.overflow) ts.rounded_inputs.push_back(n.path);
  return v;
}

template <class S> Mat4<S> build_quadric(const QuadricSpec& q, const std::vector<S>& p) {
  auto v3 = [&](std::size_t i) { return Vec3<S>(p[i], p[i + 1], p[i + 2]); };
  switch (q.shape) {
    case Shape::matrix: {
      Mat4<S> A;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) A(i, j) = p[static_cast<std::size_t>(4 * i + j)];
      return A;
    }
    case Shape::coefficients:
      return quadric_from_coefficients<S>(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9]);
    case Shape::sphere: return sphere_quadric<S>(v3(0), p[3]);
    case Shape::ellipsoid: {
      Mat3<S> axes;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) axes(i, j) = p[static_cast<std::size_t>(6 + 3 * i + j)];
      return ellipsoid_quadric<S>(v3(0), v3(3), axes);
    }
    case Shape::cylinder: return cylinder_quadric<S>(v3(0), v3(3), p[6]);
    case Shape::cone: return cone_quadric<S>(v3(0), v3(3), p[6]);
  }
  return Mat4<S>::Zero();
}

/// Homogeneous light: (p, 1) for a point light, (-d, 0) for a parallel one.
template <class S> Vec4<S> homogeneous_light(bool parallel, const Vec3<S>& v) {
  if (parallel) return Vec4<S>(S(-v(0)), S(-v(1)), S(-v(2)), S(0));
  return Vec4<S>(v(0), v(1), v(2), S(1));
}

template <class S> TypedScene<S> typed_scene(const Scene& sc) {
  TypedScene<S> ts;
  auto conv = [&](const std::vector<Num>& ns) {
    std::vector<S> out;
    out.reserve(ns.size());
    for (const Num& n : ns) out.push_back(typed_number<S>(n, ts));
    return out;
  };
  for (const QuadricSpec& q : sc.quadrics) ts.A.push_back(build_quadric<S>(q, conv(q.params)));
  for (const LightSpec& l : sc.lights) {
    const auto v = conv(l.xyz);
    ts.L.push_back(homogeneous_light<S>(l.parallel, Vec3<S>(v[0], v[1], v[2])));
  }
  for (const MirrorSpec& m : sc.mirrors) {
    const auto v = conv(m.plane);
    ts.planes.push_back(Vec4<S>(v[0], v[1], v[2], v[3]));
  }
  return ts;
}

}  // namespace qverify
