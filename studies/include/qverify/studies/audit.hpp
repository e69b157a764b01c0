#pragma once
/// \file audit.hpp
/// `qverify audit SCENE --out DIR`: every requested item computed in every
/// precision of the ladder by both methods, timed, and compared with the exact
/// result as quadrics (scale removed by cross-multiplication): the
/// qverify-audit/1 document and its error-against-time figure.
///
/// With a candidate (another implementation, candidate_run.hpp), it is called
/// once on the scene and its results are a row beside the ladder's: the same
/// matrix error against exact, the wall time of the call per item, and the
/// geometric error of every item as `verify --candidate` measures it.

#include <qverify/eval/timed.hpp>
#include <qverify/studies/figure.hpp>
#include <qverify/verify/candidate_run.hpp>
#include <qverify/verify/verifier.hpp>

#include <algorithm>
#include <chrono>
#include <functional>

namespace qverify {

/// Relative error of X against the exact Y as projective objects (cross-
/// multiplication; see cross_residual), 2 when `positive` and the signs differ.
double projective_error(const Mat4<Rational>& X, const Mat4<Rational>& Y, bool positive);
double projective_error(const Vec4<Rational>& X, const Vec4<Rational>& Y, bool positive);

struct AuditOptions {
  std::string out_dir;
  double batch_seconds = 0.02;
  int batches = 7;
  std::vector<Precision> ladder;  ///< empty: the default ladder
  std::function<void(const std::string&)> progress;  ///< called with a line of progress
  /// Another implementation, called once on the scene (audit --candidate-cmd): a row with "source": "candidate".
  std::optional<Candidate> candidate;
  std::string scene_text;              ///< the scene as given to the candidate (empty: read from the scene's file)
  double accuracy = kDefaultAccuracy;  ///< the candidate's accuracy target T
  int samples = kDefaultSamples;       ///< exact points per item for its geometric error (verify's, seed 1)
};

/// The default ladder: float, double, long-double, float128, mpfr:128, mpfr:256, interval, exact.
std::vector<Precision> default_ladder();

/// What an audit found: the `qverify-audit/1` document and its figure (error
/// against run time). report/report.hpp writes them as report.json,
/// report.html and error-vs-time.svg.
struct AuditReport {
  nlohmann::ordered_json document;
  Plot error_vs_time;
};

/// Runs the audit. `out_dir` is created first (a bad one fails before any work:
/// FileWriteError naming the path); a candidate that fails or misses the target
/// leaves its reproducer in out_dir/failures/NAME-audit-0.* (earlier NAME-*
/// files there are removed first).
AuditReport run_audit(const Scene& sc, const AuditOptions& opt);

}  // namespace qverify
