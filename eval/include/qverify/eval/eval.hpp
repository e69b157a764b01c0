#pragma once
/// \file eval.hpp
/// Demand-driven evaluation of a scene in one scalar type: only the requested
/// (quadric, light) and (quadric, mirror) pairs are computed; a mirror matrix
/// is built only when some reflection needs it.

#include <qverify/batch/items.hpp>
#include <qverify/exact/statuses.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/exact/precision.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/eval/number.hpp>
#include <qverify/eval/frames.hpp>
#include <qverify/scene/scene.hpp>

#include <cmath>
#include <optional>
#include <limits>
#include <type_traits>

namespace qverify {

/// Which frame floating results are computed in: `world`, or `local` (the
/// robust default: per-object origin, exact change of frame, power-of-two
/// normalisation; see frames.hpp). `world_rounded`: computed as by default
/// (local frames where the default takes them), then given in world
/// coordinates, each result moved there exactly from its local frame and
/// rounded once (move_to_world): for callers that read matrices without an
/// `origin` (the Python module's qverify.shadow and qverify.reflection). A
/// world result cannot be better than its rounding: where the local frame is
/// what made a result accurate (a small object far from the world origin,
/// R's planes crossing on the terminator at a light height that is no
/// multiple of a power of two) the world one may be flagged inaccurate.
enum class Frame { world, local, world_rounded };

/// The default frame: local for floating types with the direct method (the
/// paper's route is defined in world coordinates: T depends on l_z).
template <class S> Frame default_frame(Method method) {
  return !is_exact<S>() && !ScalarOps<S>::interval && method == Method::direct ? Frame::local : Frame::world;
}

/// Scales a matrix by an exact power of two so that its largest entry lies in
/// [2^-64, 2^64]: projective results change by a positive power of two only,
/// and entries of 1e+-150 neither overflow nor underflow. No-op for types with
/// a wide exponent range.
template <class S, int R, int C> void normalise_pow2(Eigen::Matrix<S, R, C>& m) {
  if constexpr (std::is_floating_point_v<S>) {
    const S big = max_abs(m);
    if (!(big > S(0)) || !std::isfinite(big)) return;
    const int e = std::ilogb(big);
    if (e > 64 || e < -64) m *= std::ldexp(S(1), -e);
  }
}

/// Rounds an exact matrix to S entry by entry, to nearest (an entry beyond S's range to an
/// infinity): for M, which is the reflection itself, not a result up to a factor.
template <class S, int R, int C> Eigen::Matrix<S, R, C> rounded(const Eigen::Matrix<Rational, R, C>& m) {
  Eigen::Matrix<S, R, C> out;
  RoundingReport rep;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = round_rational<S>(m(i), rep);
  return out;
}

/// Rounds an exact matrix to S, after an exact power-of-two scaling that keeps
/// its largest entry near 1 (builtin floating types and binary128, whose
/// exponents end at 2^+-16384: unscaled, a light at 1e2500 made its products of
/// L overflow in the float128 escalation, and a double eval gave null results;
/// MPFR's range is beyond any scene's numbers).
template <class S, int R, int C> Eigen::Matrix<S, R, C> rounded_scaled(Eigen::Matrix<Rational, R, C> m) {
  if constexpr (std::is_floating_point_v<S> || std::is_same_v<S, Float128>) {
    const Rational big = max_abs(m);
    if (big != 0) {
      const long e = floor_log2(big);
      if (e > 64 || e < -64) m *= exact_pow2(-e);
    }
  }
  return rounded<S>(m);
}

/// Inputs of one shadow item, in its frame (and, in the robust path, their
/// exact values for escalation).
template <class S> struct PreparedShadow {
  Pair pair;
  Mat4<S> A;
  Vec4<S> L;
  std::optional<Vec3<Rational>> origin;
  std::optional<std::pair<Mat4<Rational>, Vec4<Rational>>> exact;
};

/// Entrywise cancellation of P = s A - pi pi^T: the largest
/// (|s| |A_ij| + |pi_i| |pi_j|) / |P_ij| (infinite when P_ij vanishes by
/// cancellation). Small entries of P computed with large cancellation carry
/// absolute, not relative, errors: the geometry of the cone is in them.
template <class S> S cone_cancellation(const Mat4<S>& A, const Vec4<S>& L, const Mat4<S>& P) {
  const Vec4<S> pi = A * L;
  const S s = abs_of<S>(S(L.dot(pi)));
  S worst(0);
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j) {
      const S terms = s * abs_of<S>(A(i, j)) + abs_of<S>(pi(i)) * abs_of<S>(pi(j));
      if (terms == S(0)) continue;
      const S p = abs_of<S>(P(i, j));
      if (p == S(0)) return S(std::numeric_limits<double>::infinity());
      if (worst < terms / p) worst = terms / p;
    }
  return worst;
}

/// Escalation threshold of the robust path: 2^16 (16 of the 53 bits of a double lost).
inline double escalation_threshold() { return 65536.0; }

/// Conditioning of the quadric's quadratic part K (3x3): |K|_max^3 / |det K|,
/// infinite for a singular K. Rounding A to S perturbs its geometry by about
/// eps times this (the small eigenvalues of K carry the shape).
template <class S> S quadric_conditioning(const Mat4<S>& A) {
  const Mat3<S> K = A.template topLeftCorner<3, 3>();
  const S k = max_abs(K), d = abs_of<S>(S(K.determinant()));
  if (d == S(0)) return S(std::numeric_limits<double>::infinity());
  return k * k * k / d;
}

/// Inputs of one reflection item: A in the quadric's frame; in the local path
/// G maps the image's frame into A's (B = G^T A G) and M is output in the
/// image's frame.
template <class S> struct PreparedReflection {
  Pair pair;
  Mat4<S> A;
  bool local = false;
  Mat4<S> G, M;
  Mat4<S> M_world;  ///< Frame::world_rounded: the exact world M rounded once (move_to_world)
  std::optional<Vec3<Rational>> origin;
  std::optional<std::pair<Mat4<Rational>, Mat4<Rational>>> exact;  ///< A and G, exactly (robust path)
};

template <class S> struct ShadowItem {
  Pair pair;
  ShadowResult<S> result;
  std::optional<Vec3<Rational>> origin;  ///< results in local coordinates x - origin
  Mat4<S> A;                             ///< the quadric as used (same frame)
  const char* escalated = nullptr;       ///< wider type the item was recomputed in, if any
};
template <class S> struct ReflectionItem {
  Pair pair;
  Mat4<S> M;
  ReflectionResult<S> result;
  std::optional<Vec3<Rational>> origin;
  const char* escalated = nullptr;
};

template <class S> struct Evaluation {
  TypedScene<S> scene;  ///< world frame, each input rounded once (range checks)
  std::vector<ItemAccuracy> shadow_accuracy, reflection_accuracy;  ///< filled by assess_accuracy
  Frame frame = Frame::world;
  std::vector<PreparedShadow<S>> prepared_shadows;
  std::vector<PreparedReflection<S>> prepared_reflections;
  std::vector<ShadowItem<S>> shadows;
  std::vector<ReflectionItem<S>> reflections;
};

/// Prepares the inputs of every requested item (not timed by the audit).
template <class S> void prepare(const Scene& sc, Frame frame, Evaluation<S>& ev, Method method = Method::direct) {
  ev.frame = frame;
  ev.prepared_shadows.clear();
  ev.prepared_reflections.clear();
  if (frame == Frame::world || (frame == Frame::world_rounded && default_frame<S>(method) == Frame::world)) {
    for (const Pair& p : sc.shadows) {
      PreparedShadow<S> ps{p, ev.scene.A[p.quadric], ev.scene.L[p.other], std::nullopt, std::nullopt};
      normalise_pow2(ps.A);
      normalise_pow2(ps.L);
      ev.prepared_shadows.push_back(ps);
    }
    for (const Pair& p : sc.reflections) {
      PreparedReflection<S> pr;
      pr.pair = p;
      pr.A = ev.scene.A[p.quadric];
      normalise_pow2(pr.A);
      ev.prepared_reflections.push_back(pr);
    }
    return;
  }
  // Local frames: exact change of frame, then one rounding.
  using Q = Rational;
  std::vector<Mat4<Q>> A_exact;
  std::vector<std::optional<Vec3<Q>>> origin, center;
  std::vector<Vec3<Q>> core;  // the point each frame is about: the centre, else quadric_base
  std::vector<Q> size2;
  for (const QuadricSpec& q : sc.quadrics) {
    std::vector<Q> params;
    for (const Num& n : q.params) params.push_back(n.value);
    const Mat4<Q> A = build_quadric<Q>(q, params);
    A_exact.push_back(A);
    const auto c = natural_center(q, A);
    center.push_back(c);
    // Without a centre (a cylinder or a paraboloid given as a matrix) the frame is about a point of
    // A's core, quadric_base: a point of its axis, or inside a paraboloid on its axis. (Such a
    // quadric 1e6 from the world origin was computed there, and lost what a centred one kept.)
    core.push_back(c ? *c : Vec3<Q>(quadric_base(canonical_quadric(A)).template head<3>()));
    const Q s2 = size_squared(quadric_to_local(A, core.back()));
    size2.push_back(s2);
    origin.push_back(wants_local_frame(core.back(), s2) ? std::optional<Vec3<Q>>(rounded_to_double(core.back()))
                                                        : std::nullopt);
  }
  std::vector<Vec4<Q>> L_exact, planes_exact;
  for (const LightSpec& l : sc.lights)
    L_exact.push_back(homogeneous_light<Q>(l.parallel, Vec3<Q>(l.xyz[0].value, l.xyz[1].value, l.xyz[2].value)));
  for (const MirrorSpec& m : sc.mirrors)
    planes_exact.push_back(Vec4<Q>(m.plane[0].value, m.plane[1].value, m.plane[2].value, m.plane[3].value));
  auto local_A = [&](std::size_t q) {
    return origin[q] ? quadric_to_local(A_exact[q], *origin[q]) : A_exact[q];
  };
  for (const Pair& p : sc.shadows) {
    PreparedShadow<S> ps;
    ps.pair = p;
    ps.origin = origin[p.quadric];
    // R's planes crossing on the terminator: the frame at the light's height, where R rounds exactly;
    // a cylinder's at the lamp's foot on its axis (shadow_origin; the paper's route keeps the
    // quadric's frame: its T depends on l_z)
    if (method == Method::direct)
      ps.origin = shadow_origin(A_exact[p.quadric], L_exact[p.other], ps.origin, center[p.quadric], size2[p.quadric]);
    const Mat4<Q> Al = ps.origin ? quadric_to_local(A_exact[p.quadric], *ps.origin) : A_exact[p.quadric];
    const Vec4<Q> Ll = ps.origin ? point_to_local(L_exact[p.other], *ps.origin) : L_exact[p.other];
    ps.A = rounded_scaled<S>(Al);
    ps.L = rounded_scaled<S>(Ll);
    if constexpr (std::is_floating_point_v<S>) ps.exact = std::make_pair(Al, Ll);
    ev.prepared_shadows.push_back(ps);
  }
  for (const Pair& p : sc.reflections) {
    PreparedReflection<S> pr;
    pr.pair = p;
    pr.local = true;
    pr.A = rounded_scaled<S>(local_A(p.quadric));
    const Mat4<Q> M = mirror_matrix<Q>(planes_exact[p.other]);  // exact, rational in n and d
    const Vec3<Q> oA = origin[p.quadric] ? *origin[p.quadric] : Vec3<Q>::Zero();
    std::optional<Vec3<Q>> oB;
    {  // about the image of the item's base point (item_base: A's centre, apex, a point of its axis
       // on the mirror, where its points are sampled; the scene's point of a cylinder's axis may lie
       // anywhere along it)
      const Vec3<Q> k = item_base(2, A_exact[p.quadric], planes_exact[p.other]);
      const Vec3<Q> mc = (M * Vec4<Q>(k.x(), k.y(), k.z(), Q(1))).template head<3>();
      if (wants_local_frame(mc, size2[p.quadric])) oB = rounded_to_double(mc);
    }
    const Vec3<Q> ob = oB ? *oB : Vec3<Q>::Zero();
    // G: image frame -> A's frame, x_A = M (u + o_B) - o_A; M_local = T_B^-1 M T_B.
    const Mat4<Q> G = translation<Q>(Vec3<Q>(-oA)) * M * translation<Q>(ob);
    pr.G = rounded_scaled<S>(G);
    if constexpr (std::is_floating_point_v<S>) pr.exact = std::make_pair(local_A(p.quadric), G);
    // M is the reflection itself (last row 0 0 0 1): rounded entry by entry, never scaled
    pr.M = rounded<S>(Mat4<Q>(translation<Q>(Vec3<Q>(-ob)) * M * translation<Q>(ob)));
    if (frame == Frame::world_rounded) pr.M_world = rounded<S>(M);
    pr.origin = oB;
    ev.prepared_reflections.push_back(pr);
  }
}

/// The item recomputed in binary128 from its exact inputs, rounded once to S.
/// (Defined in escalate.cpp for float, double and long double.)
template <class S> ShadowItem<S> escalated_shadow(const PreparedShadow<S>& ps);
extern template ShadowItem<float> escalated_shadow<float>(const PreparedShadow<float>&);
extern template ShadowItem<double> escalated_shadow<double>(const PreparedShadow<double>&);
extern template ShadowItem<long double> escalated_shadow<long double>(const PreparedShadow<long double>&);
template <class S> ReflectionItem<S> escalated_reflection(const PreparedReflection<S>& pr);
extern template ReflectionItem<float> escalated_reflection<float>(const PreparedReflection<float>&);
extern template ReflectionItem<double> escalated_reflection<double>(const PreparedReflection<double>&);
extern template ReflectionItem<long double> escalated_reflection<long double>(const PreparedReflection<long double>&);

/// Frame::world_rounded: an item computed in a local frame (origin o), moved to world coordinates
/// exactly, Q = T^-T Q_local T^-1 for P, R and the quadric as used, plane = T^-T plane_local (T the
/// translation by o, frames.hpp), and rounded once to S with a power-of-two scaling (the results are
/// projective). An item without an origin is already in world coordinates; a non-finite one keeps
/// its local frame and origin, whole (flagged non-finite: nothing to move).
template <class S> void move_to_world(ShadowItem<S>& it) {
  if constexpr (!ScalarOps<S>::interval) {  // (intervals have no local frames)
    ShadowResult<S>& r = it.result;
    if (!it.origin || !all_finite(r.P) || !all_finite(r.polar_plane) || !all_finite(r.R) || !all_finite(it.A)) return;
    const Vec3<Rational> o = *it.origin;
    it.origin.reset();
    r.P = rounded_scaled<S>(quadric_from_local(exact_matrix(r.P), o));
    r.polar_plane = rounded_scaled<S>(plane_from_local(exact_matrix(r.polar_plane), o));
    r.R = rounded_scaled<S>(quadric_from_local(exact_matrix(r.R), o));
    it.A = rounded_scaled<S>(quadric_from_local(exact_matrix(it.A), o));
  }
}
/// The same for a reflection: B moved exactly and rounded once; M, the exact world reflection
/// rounded once (pr.M_world), rather than the local one moved back.
template <class S> void move_to_world(ReflectionItem<S>& it, const PreparedReflection<S>& pr) {
  if constexpr (!ScalarOps<S>::interval) {
    if (!it.origin || !all_finite(it.result.B)) return;
    const Vec3<Rational> o = *it.origin;
    it.origin.reset();
    it.M = pr.M_world;
    it.result.B = rounded_scaled<S>(quadric_from_local(exact_matrix(it.result.B), o));
  }
}

/// Computes every prepared item by `method` (the timed part of an audit).
template <class S> void evaluate_items(const Scene& sc, Method method, Evaluation<S>& ev) {
  ev.shadows.clear();
  ev.reflections.clear();
  for (const PreparedShadow<S>& ps : ev.prepared_shadows) {
    ShadowItem<S> item{ps.pair, shadow<S>(ps.A, ps.L, method), ps.origin, ps.A};
    if constexpr (std::is_floating_point_v<S>) {
      // Robust path: where P's entries come out of heavy cancellation, recompute the item in
      // binary128 from the exact inputs and round the results once.
      if (ps.exact && method == Method::direct &&
          (!(cone_cancellation<S>(ps.A, ps.L, item.result.P) <= S(escalation_threshold())) ||
           !(quadric_conditioning<S>(ps.A) <= S(1 << 20))))
        item = escalated_shadow<S>(ps);
    }
    ev.shadows.push_back(std::move(item));
  }
  std::vector<std::optional<Mat4<S>>> mirrors(sc.mirrors.size());
  for (const PreparedReflection<S>& pr : ev.prepared_reflections) {
    if (pr.local) {
      ReflectionResult<S> r;
      set_reflection_status(r, reflection_degenerate<S>(pr.A));
      r.B = mirror_image<S>(pr.A, pr.G);  // G^T A G
      ReflectionItem<S> item{pr.pair, pr.M, r, pr.origin};
      if constexpr (std::is_floating_point_v<S>)
        if (pr.exact && !(quadric_conditioning<S>(pr.A) <= S(1 << 20))) item = escalated_reflection<S>(pr);
      ev.reflections.push_back(item);
      continue;
    }
    auto& M = mirrors[pr.pair.other];
    if (!M) M = mirror_matrix<S>(ev.scene.planes[pr.pair.other]);
    ev.reflections.push_back(
        {pr.pair, *M, reflection_in_plane<S>(pr.A, ev.scene.planes[pr.pair.other], method), std::nullopt});
  }
}

/// Computes every requested item of `sc` in scalar type S by `method`, in
/// `frame` (default: see default_frame).
template <class S> Evaluation<S> evaluate(const Scene& sc, Method method, std::optional<Frame> frame = std::nullopt) {
  Evaluation<S> ev;
  ev.scene = typed_scene<S>(sc);
  prepare<S>(sc, frame ? *frame : default_frame<S>(method), ev, method);
  evaluate_items<S>(sc, method, ev);
  if (ev.frame == Frame::world_rounded) {
    for (ShadowItem<S>& it : ev.shadows) move_to_world(it);
    for (std::size_t k = 0; k < ev.reflections.size(); ++k) move_to_world(ev.reflections[k], ev.prepared_reflections[k]);
  }
  return ev;
}

/// The status words of every item, as predicates of the scene's exact inputs
/// (exact/statuses.hpp: interval filter, rationals on doubt), whatever S is
/// and whichever frame the item was computed in (the predicates are
/// projective invariants). Method paper adds singular-frame where the exact
/// light has l_z = 0 (v_z = 0 for a parallel light).
/// `ex` is typed_scene<Rational>(sc).
template <class S> void decide_statuses(const TypedScene<Rational>& ex, Method method, Evaluation<S>& ev) {
  std::vector<std::optional<bool>> degenerate(ex.A.size());
  for (auto& it : ev.shadows) {
    const Vec4<Rational>& L = ex.L[it.pair.other];
    const StatusDecision d = exact_shadow_status(ex.A[it.pair.quadric], L);
    it.result.flags = d.flags;
    it.result.undecided = 0;
    if (method == Method::paper && L(2) == 0) it.result.flags |= static_cast<unsigned>(ShadowFlag::singular_frame);
  }
  for (auto& it : ev.reflections) {
    auto& deg = degenerate[it.pair.quadric];
    if (!deg) deg = exact_degenerate(ex.A[it.pair.quadric]);
    set_reflection_status(it.result, *deg ? Truth::yes : Truth::no);
  }
}

/// error_bound and `inaccurate` of every floating item (ShadowMeter, ReflectionMeter): the geometric
/// error bounded over every point of the results ShadowBounds / ReflectionBounds cover, the rest
/// measured exactly on the seeded sample points (the points `verify` uses by default; near the
/// target, on kRefineFactor times more), times kBoundMargin. On the default path (builtin floating types,
/// method direct, local frames) an item whose bound exceeds the target is
/// first recomputed in binary128 from its exact inputs and measured again.
/// `ex` is typed_scene<Rational>(sc).
template <class S>
void assess_accuracy(const TypedScene<Rational>& ex, Method method, Evaluation<S>& ev, const AccuracyOptions& opt) {
  ev.shadow_accuracy.assign(ev.shadows.size(), {});
  ev.reflection_accuracy.assign(ev.reflections.size(), {});
  if constexpr (std::is_same_v<S, Rational>) {
    for (auto& a : ev.shadow_accuracy) a.bound = 0;
    for (auto& a : ev.reflection_accuracy) a.bound = 0;
    return;
  } else {
    // Items are independent (an item's points come from its own inputs, item_seed): threads over them,
    // shadows and reflections in one pass (one progress count).
    auto shadow_item = [&](std::size_t k) {
      ShadowMeter meter(ex.A[ev.shadows[k].pair.quadric], ex.L[ev.shadows[k].pair.other], opt);
      auto measure = [&](const ShadowItem<S>& it) {
        const ShadowResult<S>& r = it.result;
        if (!all_finite(r.P) || !all_finite(r.polar_plane) || !all_finite(r.R)) return non_finite_accuracy();
        return meter(it.origin, exact_matrix(r.P), exact_matrix(r.polar_plane), exact_matrix(r.R));
      };
      ev.shadow_accuracy[k] = measure(ev.shadows[k]);
      if constexpr (std::is_floating_point_v<S>) {
        const PreparedShadow<S>& ps = ev.prepared_shadows[k];
        if (ev.shadow_accuracy[k].inaccurate && ps.exact && method == Method::direct && !ev.shadows[k].escalated) {
          ev.shadows[k] = escalated_shadow<S>(ps);
          if (ev.frame == Frame::world_rounded) move_to_world(ev.shadows[k]);
          ev.shadow_accuracy[k] = measure(ev.shadows[k]);
        }
      }
    };
    auto reflection_item = [&](std::size_t k) {
      const Pair& p = ev.reflections[k].pair;
      ReflectionMeter meter(ex.A[p.quadric], ex.planes[p.other], opt);
      auto measure = [&](const ReflectionItem<S>& it) {
        if (!all_finite(it.M) || !all_finite(it.result.B)) return non_finite_accuracy();
        const Mat4<Rational> M = exact_matrix(it.M);  // judged by verify too: counted (exactly)
        return meter(it.origin, exact_matrix(it.result.B), &M);
      };
      ev.reflection_accuracy[k] = measure(ev.reflections[k]);
      if constexpr (std::is_floating_point_v<S>) {
        const PreparedReflection<S>& pr = ev.prepared_reflections[k];
        if (ev.reflection_accuracy[k].inaccurate && pr.exact && !ev.reflections[k].escalated) {
          ev.reflections[k] = escalated_reflection<S>(pr);
          if (ev.frame == Frame::world_rounded) move_to_world(ev.reflections[k], pr);
          ev.reflection_accuracy[k] = measure(ev.reflections[k]);
        }
      }
    };
    const std::size_t ns = ev.shadows.size();
    for_each_item(ns + ev.reflections.size(), opt.threads, opt.progress, [&](std::size_t i) {
      if (i < ns) shadow_item(i);
      else reflection_item(i - ns);
    });
  }
}

/// The items' error bounds (with `accuracy`) and exact statuses, after evaluate_items.
template <class S>
void check_items(const Scene& sc, Method method, Evaluation<S>& ev, const std::optional<AccuracyOptions>& accuracy) {
  const TypedScene<Rational> ex = typed_scene<Rational>(sc);
  if (accuracy) assess_accuracy<S>(ex, method, ev, *accuracy);
  decide_statuses<S>(ex, method, ev);
}

/// A whole evaluation as the command line makes it: the items, their exact
/// statuses and (with `accuracy`) their error bounds.
template <class S>
Evaluation<S> evaluate_checked(const Scene& sc, Method method, std::optional<Frame> frame,
                               const std::optional<AccuracyOptions>& accuracy) {
  Evaluation<S> ev = evaluate<S>(sc, method, frame);
  check_items<S>(sc, method, ev, accuracy);
  return ev;
}

inline const char* method_name(Method m) { return m == Method::paper ? "paper" : "direct"; }

}  // namespace qverify

/// evaluate<T> and typed_scene<T> are compiled once for each scalar of the ladder, with the rest of
/// the pipeline (eval/src/inst_*.cpp, QVERIFY_INSTANTIATE), not again in every file that calls them:
/// verify, studies and render each compiled the exact pipeline anew (the largest part of their build).
#include <qverify/exact/scalar_list.hpp>
#define QVERIFY_EXTERN_EVALUATE(T)                                                                              \
  extern template qverify::Evaluation<T> qverify::evaluate<T>(const qverify::Scene&, qverify::Method,            \
                                                              std::optional<qverify::Frame>);                   \
  extern template qverify::TypedScene<T> qverify::typed_scene<T>(const qverify::Scene&);
QVERIFY_FOR_EACH_SCALAR(QVERIFY_EXTERN_EVALUATE)
#undef QVERIFY_EXTERN_EVALUATE
