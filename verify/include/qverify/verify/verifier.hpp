#pragma once
/// \file verifier.hpp
/// `qverify verify`: exact sample points on every requested terminator
/// (A ∩ polar plane) and on every requested quadric, checked against results
/// computed in any precision, or read from another program's eval document
/// (`--candidate`).
///
/// The sample points are exact (Q(sqrt delta), from the exact scene). The
/// results are converted *exactly* to rationals (a binary float is a dyadic
/// rational), so x^T Q x is evaluated without any rounding; only its size is
/// then measured, to 80 digits. In exact arithmetic a zero is a proof.

#include <qverify/verify/eval.hpp>

#include <nlohmann/json.hpp>

namespace qverify {

/// One shadow item's matrices as exact rationals.
struct ShadowMatrices {
  bool present = false;
  std::string status, problem;  ///< problem: why the item cannot be checked (missing, non-finite ...)
  Mat4<Rational> P, R;          ///< in the item's frame (local coordinates x - origin when origin is set)
  Vec4<Rational> polar;
  std::optional<Mat4<Rational>> A;  ///< the quadric as this item used it (same frame), when known
  std::optional<Vec3<Rational>> origin;
};

struct ReflectionMatrices {
  bool present = false;
  std::string status, problem;
  Mat4<Rational> M, B;  ///< in the item's frame
  std::optional<Vec3<Rational>> origin;
};

/// Results to verify, aligned with the scene's requested pairs.
struct ResultSet {
  Precision precision;  ///< the precision the results were computed in (sets the tolerance)
  std::string method = "direct";
  std::string source;   ///< "computed" or the candidate file
  std::vector<Mat4<Rational>> A;  ///< the quadrics as represented in that precision (exactly)
  std::vector<ShadowMatrices> shadows;
  std::vector<ReflectionMatrices> reflections;
  std::vector<std::string> notes;
};

/// Exact rational value of a finite scalar of any precision (binary floats are
/// dyadic rationals).
template <class S> Rational exact_value(const S& x) { return to_rational(x); }

template <class S, int R, int C> Eigen::Matrix<Rational, R, C> exact_matrix(const Eigen::Matrix<S, R, C>& m) {
  Eigen::Matrix<Rational, R, C> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = exact_value(m(i));
  return out;
}

/// Converts an evaluation exactly to rationals.
template <class S>
ResultSet result_set([[maybe_unused]] const Scene& sc, const Evaluation<S>& ev, const Precision& prec, Method method) {
  ResultSet rs;
  rs.precision = prec;
  rs.method = method_name(method);
  rs.source = "computed";
  for (const auto& A : ev.scene.A)
    rs.A.push_back(all_finite(A) ? exact_matrix(A) : Mat4<Rational>(Mat4<Rational>::Zero()));
  for (const auto& it : ev.shadows) {
    ShadowMatrices m;
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
  for (const auto& it : ev.reflections) {
    ReflectionMatrices m;
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

/// Computes the scene in S by `method` and converts the results exactly.
template <class S>
ResultSet computed_results(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame) {
  return result_set<S>(sc, evaluate<S>(sc, method, frame), prec, method);
}

/// computed_results for a run-time precision (instantiated per scalar type).
ResultSet computed_results(const Scene& sc, const Precision& prec, Method method,
                           std::optional<Frame> frame = std::nullopt);

/// Reads a `qverify-eval/1` document made by any program. Numbers are read
/// exactly from their text (JSON numbers, "p/q" or decimal strings, and
/// {"lo", "hi"} intervals, checked at their midpoint). Malformed documents are
/// InputErrors (file, JSON path); requested items it lacks are reported by the
/// verifier as failures.
ResultSet candidate_results(const Scene& sc, const std::string& file, const Precision& fallback);
/// The same from text (`file` names it in messages).
ResultSet candidate_results_text(const Scene& sc, const std::string& text, const std::string& file,
                                 const Precision& fallback);

struct VerifyOptions {
  int samples = 64;
  std::uint64_t seed = 1;
};

/// The `qverify-verify/1` document; `failed` counts failing checks.
nlohmann::ordered_json verify_document(const Scene& sc, const ResultSet& rs, const VerifyOptions& opt, int& failed);

}  // namespace qverify
