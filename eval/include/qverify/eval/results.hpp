#pragma once
/// \file results.hpp
/// An evaluation's results converted *exactly* to rationals (a binary float is
/// a dyadic rational), aligned with the scene's requested pairs: what the
/// verifier judges and the studies measure. Another program's results (a
/// candidate, verify/verifier.hpp) are read into the same ResultSet.

#include <qverify/eval/eval.hpp>

#include <optional>
#include <string>
#include <vector>

namespace qverify {

/// One shadow item's matrices as exact rationals.
struct ShadowMatrices {
  bool present = false;
  std::string status, problem;  ///< problem: why the item cannot be checked (missing, non-finite ...)
  Mat4<Rational> P, R;          ///< in the item's frame (local coordinates x - origin when origin is set)
  Vec4<Rational> polar;
  /// Whether the item gave its polar plane and R (a candidate function may return P alone: the
  /// parts it left out are zero here, and neither checked nor measured).
  bool polar_given = true, R_given = true;
  std::optional<Mat4<Rational>> A;  ///< the quadric as this item used it (same frame), when known
  std::optional<Vec3<Rational>> origin;
  std::optional<ItemAccuracy> accuracy;  ///< eval's error_bound and flag (computed results)
};

struct ReflectionMatrices {
  bool present = false;
  std::string status, problem;
  Mat4<Rational> M, B;  ///< in the item's frame
  bool M_given = true;  ///< whether the item gave M (a candidate function may return B alone; M is zero then)
  std::optional<Vec3<Rational>> origin;
  std::optional<ItemAccuracy> accuracy;
};

/// Results to verify, aligned with the scene's requested pairs.
struct ResultSet {
  Precision precision;  ///< the precision the results were computed in (sets the tolerance)
  Method method = Method::direct;
  std::string source;   ///< "computed" or the candidate file
  std::vector<Mat4<Rational>> A;  ///< the quadrics as represented in that precision (exactly)
  std::vector<ShadowMatrices> shadows;
  std::vector<ReflectionMatrices> reflections;
  std::vector<std::string> notes;
};

/// Converts an evaluation exactly to rationals.
template <class S>
ResultSet result_set([[maybe_unused]] const Scene& sc, const Evaluation<S>& ev, const Precision& prec, Method method) {
  ResultSet rs;
  rs.precision = prec;
  rs.method = method;
  rs.source = "computed";
  for (const auto& A : ev.scene.A)
    rs.A.push_back(all_finite(A) ? exact_matrix(A) : Mat4<Rational>(Mat4<Rational>::Zero()));
  for (std::size_t k = 0; k < ev.shadows.size(); ++k) {
    const auto& it = ev.shadows[k];
    ShadowMatrices m;
    if (k < ev.shadow_accuracy.size()) m.accuracy = ev.shadow_accuracy[k];
    m.status = it.result.status();
    if (all_finite(it.result.P) && all_finite(it.result.R) && all_finite(it.result.polar_plane) && all_finite(it.A)) {
      m.present = true;
      m.origin = it.origin;
      m.P = exact_matrix(it.result.P);
      m.R = exact_matrix(it.result.R);
      m.polar = exact_matrix(it.result.polar_plane);
      m.A = exact_matrix(it.A);
    } else {
      m.problem = "non-finite entries in the computed result";
    }
    rs.shadows.push_back(std::move(m));
  }
  for (std::size_t k = 0; k < ev.reflections.size(); ++k) {
    const auto& it = ev.reflections[k];
    ReflectionMatrices m;
    if (k < ev.reflection_accuracy.size()) m.accuracy = ev.reflection_accuracy[k];
    m.status = it.result.status();
    if (all_finite(it.M) && all_finite(it.result.B)) {
      m.present = true;
      m.origin = it.origin;
      m.M = exact_matrix(it.M);
      m.B = exact_matrix(it.result.B);
    } else {
      m.problem = "non-finite entries in the computed result";
    }
    rs.reflections.push_back(std::move(m));
  }
  return rs;
}

/// Computes the scene in S by `method` as eval does (exact statuses; with
/// `accuracy`, error bounds and the escalation they trigger) and converts the
/// results exactly.
template <class S>
ResultSet computed_results(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame,
                           const std::optional<AccuracyOptions>& accuracy) {
  return result_set<S>(sc, evaluate_checked<S>(sc, method, frame, accuracy), prec, method);
}

/// computed_results for a run-time precision (instantiated per scalar type).
ResultSet computed_results(const Scene& sc, const Precision& prec, Method method,
                           std::optional<Frame> frame = std::nullopt,
                           const std::optional<AccuracyOptions>& accuracy = AccuracyOptions{});

}  // namespace qverify
