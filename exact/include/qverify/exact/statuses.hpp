#pragma once
/// \file statuses.hpp
/// Status words settled exactly: the predicates of core/predicates.hpp on
/// the exact inputs, filtered (CGAL's discipline): first on certified interval
/// enclosures of the inputs, then, only where an enclosure cannot decide, on
/// the exact rationals. The answer is the exact one, whatever the precision
/// the results are computed in, the units or the placement of the scene.

#include <qverify/core/mirror.hpp>
#include <qverify/core/shadow.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/rounding.hpp>

namespace qverify {

/// shadow_status of the exact (A, L): decided in every case (undecided == 0).
StatusDecision exact_shadow_status(const Mat4<Rational>& A, const Vec4<Rational>& L);

/// rank A <= 2 for the exact A.
bool exact_degenerate(const Mat4<Rational>& A);

/// The predicates of the exact values of floating inputs (every binary float
/// is a dyadic rational): what the core's filter left open is settled here.
template <class S> void settle_status(ShadowResult<S>& r, const Mat4<S>& A, const Vec4<S>& L) {
  if (r.undecided == 0) return;
  const StatusDecision d = exact_shadow_status(exact_matrix(A), exact_matrix(L));
  r.flags = d.flags | (r.flags & static_cast<unsigned>(ShadowFlag::singular_frame));
  r.undecided = 0;
}
template <class S> void settle_status(ReflectionResult<S>& r, const Mat4<S>& A) {
  if (!r.undecided) return;
  set_reflection_status(r, exact_degenerate(exact_matrix(A)) ? Truth::yes : Truth::no);
}

}  // namespace qverify
