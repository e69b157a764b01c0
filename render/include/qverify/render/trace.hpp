#pragma once
/// \file trace.hpp
/// What one pixel shows, by two methods, generic over the scalar.
///
/// A pixel's primary ray is X(t) = O + t D (O = (o, 1), D = (d, 0)). It shows
/// the nearest of: a quadric A_q (clipped to the render box unless bounded),
/// a mirror plane m. Behind a mirror the pixel shows the requested quadrics
/// reflected in it (one bounce; mirrors are not seen in mirrors). A shown
/// surface point x is shadowed from light L by occluder q (a requested
/// (q, L) pair) when the open segment from x to L meets A_q. Mirrors neither
/// block nor reflect light. Shadows are cast by the *unclipped* quadrics.
///
/// `raytrace` decides all this the classic way (Whitted): reflection rays
/// from the mirror, shadow rays from x to each light, solving
/// a s^2 + 2 b s + c = 0 for each occluder.
///
/// `transforms` uses only the primary ray and the precomputed quadrics:
///  - behind mirror m the primary ray is intersected with the mirror images
///    B = M^T A M of eq. (11) (the point seen is y; x = M y is its original);
///  - the shadow test is a point-in-quadric test with P of eq. (3) and the
///    polar plane pi = A L (eq. (5): the plane S carried back to world coordinates):
///
///      x shadowed  <=>  x^T P x < 0  and  ( s (x^T A x) < 0  or  s (pi.x) < 0 ),
///      s = L^T A L.
///
///    Proof. The segment is {L + mu x : mu > 0} (x, L homogeneous, w >= 0).
///    g(mu) = (L + mu x)^T A (L + mu x) = s + 2 mu (pi.x) + mu^2 (x^T A x);
///    its discriminant is (pi.x)^2 - s x^T A x = -x^T P x. g has a root
///    mu > 0 iff g(0) = s and g(oo) ~ x^T A x differ in sign (then the
///    discriminant is positive), or they agree and there are two real roots
///    with positive sum -2 (pi.x)/(x^T A x), i.e. s (pi.x) < 0. []
///    For the paper's setting (light and x outside a convex object) the
///    second clause alone holds: x is inside the cone P and beyond the
///    polar plane, the paper's "P cut by R" (R = pi h^T + h pi^T,
///    sign R(x) = sign(pi.x) sign(h.x)). The first clause adds the solid of
///    A itself (a light inside a hyperboloid, an object inside another).
///
/// In exact arithmetic both methods give the same answer on every pixel whose
/// ray does not graze a boundary. In double they differ only where rounding
/// flips a decision; `certify` re-traces such pixels with certified intervals
/// (Mpfi) from the same double ray to say which method was right.
///
/// Every decision goes through `decide_sign`: for floating types it is the
/// sign; for interval types it throws `Undecided` when the interval contains
/// zero but is not {0}.

#include <qverify/core/scalar.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

namespace qverify::render {

/// An interval decision that the working precision cannot certify.
struct Undecided {};

template <class S> int decide_sign(const S& x) {
  const int s = sign_of<S>(x);
  if constexpr (ScalarOps<S>::interval) {
    if (s == 0 && !equals_zero<S>(x)) throw Undecided{};
  }
  return s;
}
template <class S> bool decide_less(const S& a, const S& b) { return decide_sign<S>(S(b - a)) > 0; }

enum class RenderMethod { transforms, raytrace };
inline const char* method_word(RenderMethod m) { return m == RenderMethod::transforms ? "transforms" : "raytrace"; }

/// What a pixel shows: the quadric (-1: background), the mirror it is seen
/// in (-1: seen directly), the lights from which the shown point is
/// shadowed (bit l for light l) and, for a pixel on a mirror, the lights
/// from which the mirror's own point is shadowed (mirrors are partly
/// diffuse, so shadows fall on them).
struct PixelId {
  std::int32_t surface = -1, mirror = -1;
  std::uint64_t shadowed = 0, mirror_shadowed = 0;
  bool operator==(const PixelId& o) const {
    return surface == o.surface && mirror == o.mirror && shadowed == o.shadowed && mirror_shadowed == o.mirror_shadowed;
  }
  bool operator!=(const PixelId& o) const { return !(*this == o); }
};

/// One requested shadow: the occluder's index, its cone P (eq. 3), its polar
/// plane pi = A L and s = sign(L^T A L) (never 0: pairs with the light on
/// the surface or a degenerate quadric are left out).
template <class S> struct Occluder {
  int quadric = 0;
  Mat4<S> P;
  Vec4<S> pi;
  int side = 1;
};

template <class S> struct LightData {
  Vec4<S> L;  ///< (p, 1) for a point light, (-d, 0) for a parallel one
  std::vector<Occluder<S>> occluders;
};

/// What every primary ray shares: Q O for the eye O = (e, 1), and O^T Q O.
template <class S> struct EyeForm {
  Vec3<S> q;  ///< the first three entries of Q O
  S c;        ///< O^T Q O
};

/// One requested reflection: the quadric and its mirror image B (eq. 11).
template <class S> struct MirrorImage {
  int quadric = 0;
  Mat4<S> B;
  EyeForm<S> B_eye;
};

template <class S> struct MirrorData {
  Vec4<S> plane;  ///< (n, d): n.x + d = 0
  Mat4<S> M;      ///< eq. (9) for a non-unit normal; M M = I
  std::vector<MirrorImage<S>> images;
};

/// Everything both methods read, in scalar S.
template <class S> struct RenderData {
  Vec3<S> eye;  ///< every primary ray starts here
  std::vector<Mat4<S>> A;
  std::vector<EyeForm<S>> A_eye;
  std::vector<char> clipped;  ///< unbounded quadrics are clipped to the box
  Vec3<S> box_lo, box_hi;
  std::vector<LightData<S>> lights;
  std::vector<MirrorData<S>> mirrors;
};

/// x^T Q x for X = (x, 1), from the upper triangle (10 products).
template <class S> S form_at(const Mat4<S>& Q, const Vec3<S>& x) {
  const S& a = x(0);
  const S& b = x(1);
  const S& c = x(2);
  return a * (Q(0, 0) * a + S(2) * (Q(0, 1) * b + Q(0, 2) * c + Q(0, 3))) +
         b * (Q(1, 1) * b + S(2) * (Q(1, 2) * c + Q(1, 3))) + c * (Q(2, 2) * c + S(2) * Q(2, 3)) + Q(3, 3);
}

/// pi . (x, 1)
template <class S> S plane_at(const Vec4<S>& p, const Vec3<S>& x) {
  return p(0) * x(0) + p(1) * x(1) + p(2) * x(2) + p(3);
}

/// Line coefficients of X(t) = (o, 1) + t (d, 0) on Q: Q(X(t)) = a t^2 + 2 b t + c.
template <class S> struct LineForm {
  S a, b, c;
};
/// d^T Q d over the 3x3 block, from its upper triangle (9 products).
template <class S> S direction_form(const Mat4<S>& Q, const Vec3<S>& d) {
  return d(0) * (Q(0, 0) * d(0) + S(2) * (Q(0, 1) * d(1) + Q(0, 2) * d(2))) +
         d(1) * (Q(1, 1) * d(1) + S(2) * Q(1, 2) * d(2)) + Q(2, 2) * d(2) * d(2);
}
template <class S> EyeForm<S> eye_form(const Mat4<S>& Q, const Vec3<S>& o) {
  const Vec4<S> Qo = Q.template leftCols<3>() * o + Q.col(3);
  return {Qo.template head<3>(), S(o.dot(Qo.template head<3>()) + Qo(3))};
}
template <class S> LineForm<S> line_form(const Mat4<S>& Q, const EyeForm<S>& e, const Vec3<S>& d) {
  return {direction_form<S>(Q, d), d.dot(e.q), e.c};
}
template <class S> LineForm<S> line_form(const Mat4<S>& Q, const Vec3<S>& o, const Vec3<S>& d) {
  return line_form<S>(Q, eye_form<S>(Q, o), d);
}

/// The real roots of a t^2 + 2 b t + c = 0 in increasing order (0, 1 or 2;
/// a tangent line counts as no crossing). Numerically stable form.
template <class S> int line_roots(const LineForm<S>& f, S roots[2]) {
  const int sa = decide_sign<S>(f.a);
  if (sa == 0) {  // linear (exactly: a line along an asymptotic direction)
    if (decide_sign<S>(f.b) == 0) return 0;
    roots[0] = S(-f.c / (S(2) * f.b));
    return 1;
  }
  const S disc = f.b * f.b - f.a * f.c;
  if (decide_sign<S>(disc) <= 0) return 0;
  using std::sqrt;
  const S sq = sqrt(disc);
  const int sb = sign_of<S>(f.b);  // 0 when uncertain: then the plain form
  S r0, r1;
  if (sb != 0 && decide_sign<S>(f.c) != 0) {
    const S q = sb > 0 ? S(-(f.b + sq)) : S(sq - f.b);
    r0 = q / f.a;
    r1 = f.c / q;
  } else {
    r0 = (-f.b - sq) / f.a;
    r1 = (-f.b + sq) / f.a;
  }
  if (decide_less<S>(r1, r0)) std::swap(r0, r1);
  roots[0] = r0;
  roots[1] = r1;
  return 2;
}

template <class S> bool in_box(const RenderData<S>& rd, int q, const Vec3<S>& x) {
  if (!rd.clipped[static_cast<std::size_t>(q)]) return true;
  for (int i = 0; i < 3; ++i)
    if (decide_less<S>(x(i), rd.box_lo(i)) || decide_less<S>(rd.box_hi(i), x(i))) return false;
  return true;
}

/// Nearest hit.
template <class S> struct Hit {
  int quadric = -1;
  S t;
};

/// The nearest accepted crossing of o + t d with the quadrics and t > tmin.
/// `get(k)` gives the k-th quadric's index, matrix and, for rays from the
/// eye, its precomputed EyeForm (else nullptr); `accept(q, t)` clips.
template <class S, class GetQ, class Accept>
Hit<S> nearest(int n, GetQ&& get, const Vec3<S>& o, const Vec3<S>& d, const S& tmin, Accept&& accept) {
  Hit<S> best;
  for (int k = 0; k < n; ++k) {
    const auto [q, Q, E] = get(k);
    S r[2];
    const int nr = line_roots<S>(E ? line_form<S>(*Q, *E, d) : line_form<S>(*Q, o, d), r);
    for (int i = 0; i < nr; ++i) {
      if (!decide_less<S>(tmin, r[i])) continue;
      if (best.quadric >= 0 && !decide_less<S>(r[i], best.t)) break;
      if (accept(q, r[i])) {
        best.quadric = q;
        best.t = r[i];
        break;
      }
    }
  }
  return best;
}

/// The reflection of direction d in a plane with normal n: d - 2 (n.d)/(n.n) n.
template <class S> Vec3<S> reflect_direction(const Vec4<S>& plane, const Vec3<S>& d) {
  const Vec3<S> n = plane.template head<3>();
  return d - (S(2) * n.dot(d) / n.squaredNorm()) * n;
}

/// Raytrace: does the open segment from x (on surface `self`) to the light
/// meet the occluder? Shadow ray x + s D, s in (0, 1) towards a point
/// light, s in (0, oo) along a parallel one. On its own surface the root
/// s = 0 is removed exactly (c = 0) instead of by an epsilon.
template <class S> bool shadow_ray_blocked(const Mat4<S>& A, const Vec4<S>& L, const Vec3<S>& x, bool self) {
  const bool point = decide_sign<S>(L(3)) != 0;
  const Vec3<S> D = point ? Vec3<S>(L.template head<3>() / L(3) - x) : Vec3<S>(L.template head<3>());
  LineForm<S> f = line_form<S>(A, x, D);
  auto on_segment = [&](const S& s) { return decide_sign<S>(s) > 0 && (!point || decide_less<S>(s, S(1))); };
  if (self) {  // roots 0 and -2b/a
    if (decide_sign<S>(f.a) == 0 || decide_sign<S>(f.b) == 0) return false;
    return on_segment(S(-S(2) * f.b / f.a));
  }
  S r[2];
  const int nr = line_roots<S>(f, r);
  for (int i = 0; i < nr; ++i)
    if (on_segment(r[i])) return true;
  return false;
}

/// Transforms: the point-in-shadow-volume test of the file comment.
/// The cheap test first: a point on the light's side of the polar plane is
/// shadowed only from inside the solid of A (never on A itself).
template <class S> bool in_shadow_volume(const Occluder<S>& oc, const Mat4<S>& A, const Vec3<S>& x, bool self) {
  auto inside_cone = [&] { return decide_sign<S>(form_at<S>(oc.P, x)) < 0; };
  if (oc.side * decide_sign<S>(plane_at<S>(oc.pi, x)) < 0) return inside_cone();
  return !self && oc.side * decide_sign<S>(form_at<S>(A, x)) < 0 && inside_cone();
}

/// The traced pixel: its id and, for shading, the surface point x, the
/// direction of the ray that reached it and the mirror point p.
template <class S> struct Traced {
  PixelId id;
  Vec3<S> x, ray, p;
};

/// The lights from which x is shadowed (bit l), by `method`; `self` is the
/// quadric x lies on (-1: none, x is on a mirror).
template <class S> std::uint64_t shadow_mask(const RenderData<S>& rd, RenderMethod method, const Vec3<S>& x, int self) {
  std::uint64_t mask = 0;
  for (std::size_t l = 0; l < rd.lights.size(); ++l) {
    const LightData<S>& ld = rd.lights[l];
    for (const Occluder<S>& oc : ld.occluders) {
      const Mat4<S>& A = rd.A[static_cast<std::size_t>(oc.quadric)];
      const bool is_self = oc.quadric == self;
      const bool blocked = method == RenderMethod::raytrace ? shadow_ray_blocked<S>(A, ld.L, x, is_self)
                                                            : in_shadow_volume<S>(oc, A, x, is_self);
      if (blocked) {
        mask |= std::uint64_t(1) << std::min<std::size_t>(l, 63);
        break;
      }
    }
  }
  return mask;
}

/// What the ray eye + t d shows, by `method`.
template <class S> Traced<S> trace(const RenderData<S>& rd, RenderMethod method, const Vec3<S>& d) {
  using Q = std::tuple<int, const Mat4<S>*, const EyeForm<S>*>;
  const Vec3<S>& o = rd.eye;
  Traced<S> out;
  out.ray = d;
  const int nq = static_cast<int>(rd.A.size());
  const S zero(0);
  Hit<S> h = nearest<S>(
      nq, [&](int k) { return Q(k, &rd.A[static_cast<std::size_t>(k)], &rd.A_eye[static_cast<std::size_t>(k)]); }, o, d, zero,
      [&](int q, const S& t) { return in_box<S>(rd, q, Vec3<S>(o + t * d)); });
  int mirror = -1;
  S tm(0);
  for (std::size_t m = 0; m < rd.mirrors.size(); ++m) {
    const Vec4<S>& pl = rd.mirrors[m].plane;
    const S nd = pl.template head<3>().dot(d);
    if (decide_sign<S>(nd) == 0) continue;
    const S t = -plane_at<S>(pl, o) / nd;
    if (decide_sign<S>(t) <= 0) continue;
    if ((mirror < 0 || decide_less<S>(t, tm)) && (h.quadric < 0 || decide_less<S>(t, h.t))) {
      mirror = static_cast<int>(m);
      tm = t;
    }
  }
  if (mirror >= 0) {
    const MirrorData<S>& md = rd.mirrors[static_cast<std::size_t>(mirror)];
    const int ni = static_cast<int>(md.images.size());
    out.id.mirror = mirror;
    const Vec3<S> r = reflect_direction<S>(md.plane, d);
    out.ray = r;
    const Vec3<S> p = o + tm * d;
    out.p = p;
    out.id.mirror_shadowed = shadow_mask<S>(rd, method, p, -1);
    if (method == RenderMethod::raytrace) {
      const Hit<S> hr = nearest<S>(
          ni,
          [&](int k) {
            const int q = md.images[static_cast<std::size_t>(k)].quadric;
            return Q(q, &rd.A[static_cast<std::size_t>(q)], nullptr);
          },
          p, r, zero, [&](int q, const S& s) { return in_box<S>(rd, q, Vec3<S>(p + s * r)); });
      if (hr.quadric < 0) return out;
      out.id.surface = hr.quadric;
      out.x = p + hr.t * r;
    } else {
      auto original = [&](const Vec3<S>& y) {
        return Vec3<S>(md.M.template topLeftCorner<3, 3>() * y + md.M.template topRightCorner<3, 1>());
      };
      const Hit<S> hb = nearest<S>(
          ni,
          [&](int k) {
            const MirrorImage<S>& im = md.images[static_cast<std::size_t>(k)];
            return Q(im.quadric, &im.B, &im.B_eye);
          },
          o, d, tm, [&](int q, const S& t) { return in_box<S>(rd, q, original(Vec3<S>(o + t * d))); });
      if (hb.quadric < 0) return out;
      out.id.surface = hb.quadric;
      out.x = original(Vec3<S>(o + hb.t * d));
    }
  } else {
    if (h.quadric < 0) return out;
    out.id.surface = h.quadric;
    out.x = o + h.t * d;
  }
  out.id.shadowed = shadow_mask<S>(rd, method, out.x, out.id.surface);
  return out;
}

}  // namespace qverify::render
