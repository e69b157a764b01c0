#pragma once
/// \file shadow.hpp
/// Shadow volume of a quadric A lit by a light L, equations (2)-(6) of
/// Hashimoto & Suenaga, "A study on the transformation of quadric surfaces".
///
/// The light is a homogeneous 4-vector: L = (p, 1) for a point light at p,
/// L = (v, 0) for a light at infinity in direction v (a parallel light
/// travelling along d has v = -d).
///
/// Two routes compute the same three results:
///  - *direct* (projective formulas, defined for every light):
///      P  = (L^T A L) A - (A L)(A L)^T              tangent cone from L
///      pi = A L                                     polar plane of L
///      R  = pi h^T + h pi^T                         plane pi read as a quadric
///    with h the plane that the paper's frame sends to infinity
///    (h = (0, 0, 1, -l_z) for a point light, the plane at infinity e4 for a
///    parallel light);
///  - *paper*: M, T, C (2), D (4), P (3), S (5), R (6) as the paper builds them.
/// Both give P up to a positive factor (1/l_z^2), pi up to a positive factor
/// (after orienting S) and R up to a non-zero factor.

#include <qverify/core/method.hpp>
#include <qverify/core/predicates.hpp>

namespace qverify {

// ---------------------------------------------------------------- direct route

/// Polar plane of L with respect to A: pi = A L. Its intersection with A is the
/// terminator (the points where rays from L graze A). (Sums in a fixed order:
/// ordered_product.)
template <class S> Vec4<S> polar_plane(const Mat4<S>& A, const Vec4<S>& L) { return ordered_product<S>(A, L); }

/// The entries of the tangent cone, P_ij = (L^T A L) A_ij - AL_i AL_j, as a
/// function of (i, j), from a precomputed polar plane AL = A L. Batches store
/// the ten entries of packs straight from it (store_sym_entries, batch.hpp):
/// no 4x4 temporary of packs, which GCC 12 keeps on the stack and copies
/// (README, "bench"; with AL captured by value GCC's double kernel took 12.0
/// ns per item against 6.6). It refers to A and AL: use it while they live
/// (within the expression that calls it, as the callers here do).
template <class S> [[nodiscard]] auto tangent_cone_entries(const Mat4<S>& A, const Vec4<S>& L, const Vec4<S>& AL) {
  return [&A, &AL, s = S(ordered_dot<S, 4>(L, AL))](int i, int j) { return S(s * A(i, j) - AL(i) * AL(j)); };
}

/// The tangent cone from a precomputed polar plane AL = A L (batches reuse it).
template <class S> Mat4<S> tangent_cone_from_polar(const Mat4<S>& A, const Vec4<S>& L, const Vec4<S>& AL) {
  return symmetric_from<S>(tangent_cone_entries<S>(A, L, AL));
}

/// Tangent cone of A from L (the cone P of eq. (3), apex L):
///   P = (L^T A L) A - (A L)(A L)^T.
/// P L = 0 (L is its apex) and P agrees with A on the polar plane up to the
/// factor L^T A L, so P contains the terminator.
template <class S> Mat4<S> tangent_cone(const Mat4<S>& A, const Vec4<S>& L) {
  return tangent_cone_from_polar<S>(A, L, polar_plane<S>(A, L));
}

/// The plane that the paper's frame change N = T M sends to infinity (row 4 of
/// N up to a factor): z = l_z for a point light, the plane at infinity for a
/// parallel light.
template <class S> Vec4<S> frame_plane(const Vec4<S>& L) {
  if (qverify::equals_zero<S>(L(3))) return Vec4<S>(S(0), S(0), S(0), S(1));
  return Vec4<S>(S(0), S(0), L(3), S(-L(2)));
}

/// The entries of R = pi h^T + h pi^T as a function of (i, j), i <= j, from
/// a precomputed polar plane pi = AL (batches reuse it and store the entries
/// straight from this, as tangent_cone_entries; it refers to AL: use it while
/// AL lives), with h = frame_plane(L). As h has no x and y components, the
/// x-y block of R is zero and the other entries have at most two terms:
///   R_ij = 0 (i, j < 2),  R_ij = pi_i h_j (i < 2 <= j),
///   R_ij = pi_i h_j + h_i pi_j (2 <= i < j),  R_ii = t + t with t = pi_i h_i (i >= 2).
/// The terms with a zero factor are not formed, and a diagonal entry doubles
/// its one product (x y + y x = t + t exactly, also for intervals, whose
/// product is commutative and whose doubling is exact): 8 products instead of
/// plane_pair's 20, for the same values when pi is finite (up to the sign of
/// a zero; with a non-finite pi the x-y block is 0 where plane_pair's 0 * inf
/// gave NaN, and the other entries stay non-finite). The double kernel with
/// its data in the caches went from 5.37 to 4.97 ns per item (measured with
/// an earlier form of 10 products); the interval kernel, bound by moving its
/// data, did not move (README, "bench").
template <class S> [[nodiscard]] auto terminator_entries(const Vec4<S>& L, const Vec4<S>& AL) {
  return [&AL, h = Vec4<S>(frame_plane<S>(L))](int i, int j) {
    if (j < 2) return S(0);
    if (i < 2) return S(AL(i) * h(j));
    if (i == j) {
      const S t = AL(i) * h(i);
      return S(t + t);
    }
    return S(AL(i) * h(j) + h(i) * AL(j));
  };
}

/// R from a precomputed polar plane AL (terminator_entries says how).
template <class S> Mat4<S> terminator_quadric_from_polar(const Vec4<S>& L, const Vec4<S>& AL) {
  return symmetric_from<S>(terminator_entries<S>(L, AL));
}

/// The quadric R of eq. (6) by the direct route: the polar plane pi read as a
/// quadric in the paper's way, pi h^T + h pi^T (the plane pair pi ∪ h).
/// It contains the terminator A ∩ pi.
template <class S> Mat4<S> terminator_quadric(const Mat4<S>& A, const Vec4<S>& L) {
  return terminator_quadric_from_polar<S>(L, polar_plane<S>(A, L));
}

// ------------------------------------------------------------------ paper route

/// The paper's normalising frame for a light L:
///  M: translation by (-l_x, -l_y, 0) (for a parallel light, whose translation
///     is not defined, the shear x -= (v_x/v_z) z, y -= (v_y/v_z) z, which
///     carries the direction v to the z axis);
///  T: perspective transformation along Z with vanishing point (0, 0, l_z):
///     w' = w - z / l_z, sending the light to the point at infinity of the z
///     axis (identity for a parallel light, already at infinity).
/// `singular` when T (l_z = 0) or the shear (v_z = 0) does not exist; the
/// matrices are then left as identities.
template <class S> struct PaperFrame {
  Mat4<S> M = Mat4<S>::Identity(), Minv = Mat4<S>::Identity();
  Mat4<S> T = Mat4<S>::Identity(), Tinv = Mat4<S>::Identity();
  bool singular = false;
  /// (N L)_z where N = T M: the light sits at (N L)_z e3 in the frame of C.
  S light_z = S(0);
};

template <class S> PaperFrame<S> paper_frame(const Vec4<S>& L) {
  PaperFrame<S> f;
  if (qverify::equals_zero<S>(L(2))) {
    f.singular = true;
    return f;
  }
  if (qverify::equals_zero<S>(L(3))) {  // parallel light: shear, T = I
    const S sx = L(0) / L(2), sy = L(1) / L(2);
    f.M(0, 2) = -sx;
    f.M(1, 2) = -sy;
    f.Minv(0, 2) = sx;
    f.Minv(1, 2) = sy;
    f.light_z = L(2);
    return f;
  }
  const S lx = L(0) / L(3), ly = L(1) / L(3), lz = L(2) / L(3);
  f.M(0, 3) = -lx;
  f.M(1, 3) = -ly;
  f.Minv(0, 3) = lx;
  f.Minv(1, 3) = ly;
  f.T(3, 2) = S(-1) / lz;
  f.Tinv(3, 2) = S(1) / lz;
  f.light_z = lz;  // T M (l, 1) = (0, 0, l_z, 0)
  return f;
}

/// Eq. (2): C = (T^{-1})^T (M^{-1})^T A M^{-1} T^{-1}, the quadric in the frame
/// where the light sits at infinity on the z axis.
template <class S> Mat4<S> paper_C(const Mat4<S>& A, const PaperFrame<S>& f) {
  return congruence<S>(A, Mat4<S>(f.Minv * f.Tinv));
}

/// Eq. (4): the elliptic cylinder D along Z through the outline of C (the curve
/// of C where dC/dz = 0), entry by entry as printed, with
/// C = [[a1 b1 b2 c1] [b1 a2 b3 c2] [b2 b3 a3 c3] [c1 c2 c3 d]].
/// (Identically D = a3 C - (C e3)(C e3)^T: z is eliminated.)
template <class S> Mat4<S> paper_D(const Mat4<S>& C) {
  const S a1 = C(0, 0), a2 = C(1, 1), a3 = C(2, 2), d = C(3, 3);
  const S b1 = C(0, 1), b2 = C(0, 2), b3 = C(1, 2);
  const S c1 = C(0, 3), c2 = C(1, 3), c3 = C(2, 3);
  Mat4<S> D = Mat4<S>::Zero();
  D(0, 0) = a1 * a3 - b2 * b2;
  D(0, 1) = D(1, 0) = a3 * b1 - b2 * b3;
  D(0, 3) = D(3, 0) = a3 * c1 - b2 * c3;
  D(1, 1) = a2 * a3 - b3 * b3;
  D(1, 3) = D(3, 1) = a3 * c2 - b3 * c3;
  D(3, 3) = a3 * d - c3 * c3;
  return D;
}

/// Eq. (3): P = M^T T^T D T M, the cylinder D carried back to a cone with apex L.
template <class S> Mat4<S> paper_P(const Mat4<S>& D, const PaperFrame<S>& f) {
  return congruence<S>(D, Mat4<S>(f.T * f.M));
}

/// Eq. (5): the plane S: b2 x + b3 y + a3 z + c3 = 0 (that is dC/dz = 0, the
/// polar plane of the light e3 in the frame of C), as (b2, b3, a3, c3).
template <class S> Vec4<S> paper_S(const Mat4<S>& C) { return C.col(2); }

/// S carried back through T and M: the plane N^T S (= A L / (N L)_z), oriented
/// by the sign of (N L)_z so that it is A L up to a *positive* factor.
template <class S> Vec4<S> paper_polar_plane(const Vec4<S>& Splane, const PaperFrame<S>& f) {
  const Mat4<S> N = f.T * f.M;
  Vec4<S> pi = N.transpose() * Splane;
  if (qverify::less_than<S>(f.light_z, S(0))) pi = -pi;
  return pi;
}

/// Eq. (6): R, the plane S carried back through T and M, read as a quadric:
/// S is the quadric S e4^T + e4 S^T in the frame of C (the affine equation
/// times w), and R = (T M)^T (S e4^T + e4 S^T) (T M). Section 2.2 of the
/// paper. (The matrix printed as (6) is audited separately by `qverify paper`.)
template <class S> Mat4<S> paper_R(const Vec4<S>& Splane, const PaperFrame<S>& f) {
  const Mat4<S> N = f.T * f.M;
  const Vec4<S> e4(S(0), S(0), S(0), S(1));
  return congruence<S>(plane_pair<S>(Splane, e4), N);
}

// --------------------------------------------------------------------- results

/// Special cases of a shadow item, the status words of the CLI contract.
enum class ShadowFlag : unsigned {
  degenerate_quadric = 1u << 0,  ///< rank A <= 2
  light_on_surface = 1u << 1,    ///< L^T A L = 0 (P collapses to -(AL)(AL)^T)
  no_real_silhouette = 1u << 2,  ///< the terminator A ∩ pi has no real point
  singular_frame = 1u << 3,      ///< method paper: T or M does not exist (l_z = 0)
};

/// Status words in priority order (the first flag set is an item's `status`).
inline const char* flag_word(ShadowFlag f) {
  switch (f) {
    case ShadowFlag::degenerate_quadric: return "degenerate-quadric";
    case ShadowFlag::light_on_surface: return "light-on-surface";
    case ShadowFlag::no_real_silhouette: return "no-real-silhouette";
    case ShadowFlag::singular_frame: return "singular-frame";
  }
  return "ok";
}
constexpr ShadowFlag kFlagOrder[] = {ShadowFlag::degenerate_quadric, ShadowFlag::light_on_surface,
                                     ShadowFlag::no_real_silhouette, ShadowFlag::singular_frame};

/// The paper route's intermediate matrices, kept for inspection.
template <class S> struct PaperIntermediates {
  PaperFrame<S> frame;
  Mat4<S> C, D;
  Vec4<S> S_plane;
};

template <class S> struct ShadowResult {
  Mat4<S> P, R;
  Vec4<S> polar_plane;
  unsigned flags = 0;
  /// Predicates the floating filter could not decide on these inputs (see
  /// predicates.hpp); qverify/exact/statuses.hpp settles them exactly.
  unsigned undecided = 0;
  /// Method paper with a singular frame: P, pi and R come from the direct formulas.
  bool direct_fallback = false;
  bool has_paper = false;
  PaperIntermediates<S> paper;

  bool has(ShadowFlag f) const { return flags & static_cast<unsigned>(f); }
  /// The item's status word: "ok" or the highest-priority flag; "undecided"
  /// when a predicate of higher priority than every flag set is still open.
  const char* status() const {
    for (ShadowFlag f : kFlagOrder) {
      if (has(f)) return flag_word(f);
      if (undecided & static_cast<unsigned>(f)) return "undecided";
    }
    return "ok";
  }
};

/// The status predicates of (A, L) (predicates.hpp), evaluated exactly for
/// exact types and through the certified filter otherwise: degenerate-quadric,
/// light-on-surface and, when the light is not on the surface,
/// no-real-silhouette. Never a tolerance: what the filter cannot decide is
/// reported in `undecided`.
template <class S> StatusDecision shadow_status(const Mat4<S>& A, const Vec4<S>& L) {
  using P = PredicateScalar<S>;
  const Mat4<P> a = to_predicate<P>(A);
  const Vec4<P> l = to_predicate<P>(L);
  StatusDecision d;
  auto put = [&d](Truth t, ShadowFlag f) {
    if (t == Truth::yes) d.flags |= static_cast<unsigned>(f);
    if (t == Truth::unknown) d.undecided |= static_cast<unsigned>(f);
  };
  put(degenerate_quadric<P>(a), ShadowFlag::degenerate_quadric);
  const Truth on = light_on_surface<P>(a, l);
  put(on, ShadowFlag::light_on_surface);
  if (on != Truth::yes) {
    const Truth empty = silhouette_empty<P>(a, l);
    // Unknown whether the light is on the surface: a definite conic counts only if it is not.
    put(on == Truth::unknown && empty == Truth::yes ? Truth::unknown : empty, ShadowFlag::no_real_silhouette);
  }
  return d;
}

/// The decided flags of shadow_status (all of them for exact types).
template <class S> unsigned shadow_flags(const Mat4<S>& A, const Vec4<S>& L) { return shadow_status<S>(A, L).flags; }

/// Shadow volume of A under L by either route (see the file comment).
template <class S> ShadowResult<S> shadow(const Mat4<S>& A, const Vec4<S>& L, Method method) {
  ShadowResult<S> r;
  const StatusDecision d = shadow_status<S>(A, L);
  r.flags = d.flags;
  r.undecided = d.undecided;
  if (method == Method::paper) {
    r.paper.frame = paper_frame<S>(L);
    if (r.paper.frame.singular) {
      r.flags |= static_cast<unsigned>(ShadowFlag::singular_frame);
      r.direct_fallback = true;
    } else {
      r.has_paper = true;
      r.paper.C = paper_C<S>(A, r.paper.frame);
      r.paper.D = paper_D<S>(r.paper.C);
      r.paper.S_plane = paper_S<S>(r.paper.C);
      r.P = paper_P<S>(r.paper.D, r.paper.frame);
      r.polar_plane = paper_polar_plane<S>(r.paper.S_plane, r.paper.frame);
      r.R = paper_R<S>(r.paper.S_plane, r.paper.frame);
      return r;
    }
  }
  r.P = tangent_cone<S>(A, L);
  r.polar_plane = polar_plane<S>(A, L);
  r.R = terminator_quadric<S>(A, L);
  return r;
}

}  // namespace qverify
