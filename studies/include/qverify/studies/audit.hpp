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

#include <qverify/eval/eval_report.hpp>
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
  int samples = kDefaultSamples;       ///< exact points per item for its geometric error (verify's, seed 1): the
                                       ///< candidate's, and the ladder rows' for eval's flag self-check
};

/// The default ladder: float, double, long-double, float128, mpfr:128, mpfr:256, interval, exact.
std::vector<Precision> default_ladder();

/// The largest and the median of a row's per-item errors (0 for a scene with no items): the two numbers a row
/// reports and the Pareto front and the figure read.
struct ErrorStats {
  double max = 0, median = 0;
};

/// What timed_results measured of a ladder row beside its errors.
struct LadderFacts {
  int inaccurate_items = 0;  ///< eval's flag: items whose error bound exceeds the accuracy target
  /// eval's flag self-checked (floating rows): the items ("shadow ball/lamp") whose geometric error on
  /// verify's exact points (AuditOptions::samples, seed 1) exceeds eval's accuracy target, 1e-9, while
  /// eval did not flag them `inaccurate`. A sample bounds the error from below, so each is a flag
  /// proved missing: an error of qverify's beyond tolerance, and the audit exits 1.
  std::vector<std::string> missed_flags;
  long reps_per_batch = 0;
  int batches = 0;
  std::size_t inputs_rounded = 0;
  std::optional<unsigned> working_bits;  ///< mpfr only: the precision actually used
};

/// What the candidate's call and the verification of its results found beside its errors.
struct CandidateFacts {
  std::string name;
  bool ok = false;                ///< the call returned every requested item
  std::string error;              ///< why the call failed (when !ok)
  std::string status;             ///< "pass", "fail" or "candidate-failed"
  std::string claimed_precision;  ///< as its document states (when ok)
  std::string claimed_method;
  int checks_passed = 0, checks_failed = 0;  ///< verify's counts (when !ok: every item counts as failed)
  double seconds = 0;                        ///< wall time of the call
  double max_geometric_error = 0;            ///< over the items with something to measure
  bool bad = false;  ///< failed, a failed check or a geometric error beyond the accuracy target
  /// Every problem of its failed checks, each after its item ("shadow ball/lamp: ..."): a status word,
  /// sign, M or symmetry that no geometric error sees, or the geometric error itself.
  std::vector<std::string> problems;
  std::optional<Reproducer> reproducer;  ///< written when bad
};

/// One row of the audit: a precision and method of the ladder, or the candidate.
struct AuditRow {
  std::string precision, method;  ///< the candidate: its name and "candidate"
  double ns_per_item = 0;
  std::vector<double> errors;  ///< per item (infinity when missing or not finite)
  ErrorStats stats;
  std::optional<LadderFacts> ladder;        ///< set for a ladder row
  std::optional<CandidateFacts> candidate;  ///< set for the candidate's row

  /// "precision/method": the row's name in the Pareto front and in each item's errors.
  std::string key() const { return precision + "/" + method; }
};

/// One requested item (shadows, then reflections) and the candidate's geometric error on it.
struct AuditItem {
  bool shadow = true;
  std::string quadric, other;  ///< the ids of the quadric and of the light or mirror
  std::string exact_status;
  /// verify --candidate's geometric error of the candidate's result (NaN: nothing to measure on), with a candidate.
  std::optional<double> candidate_geometric_error;
};

/// What an audit found: its rows (the ladder's, then the candidate's), the
/// Pareto front of (time, error), the items and the figure (error against run
/// time). report/audit_document.hpp writes it as the `qverify-audit/1`
/// document and text; report/report.hpp as report.json, report.html and
/// error-vs-time.svg.
struct AuditReport {
  std::string scene;
  AuditOptions options;  ///< as run (the ladder filled in; no progress callback)
  std::vector<AuditRow> rows;
  std::vector<std::string> pareto;  ///< the keys of the rows not dominated in (time, error)
  std::vector<AuditItem> items;
  std::vector<SkippedPair> skipped;
  Plot error_vs_time;
};

/// Did the audit find an error beyond tolerance: the candidate bad, or a flag of eval's missed on a
/// ladder row? (`qverify audit` exits 1.)
bool audit_found_error(const AuditReport& a);

/// Runs the audit. `out_dir` is created first (a bad one fails before any work:
/// FileWriteError naming the path); a candidate that fails or misses the target
/// leaves its reproducer in out_dir/failures/NAME-audit-0.* (earlier NAME-*
/// files there are removed first).
AuditReport run_audit(const Scene& sc, const AuditOptions& opt);

}  // namespace qverify
