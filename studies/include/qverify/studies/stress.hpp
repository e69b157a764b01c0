#pragma once
/// \file stress.hpp
/// `qverify stress`: sweeps of stiff and extreme cases. Each family pushes one
/// parameter over many decades towards a breaking point; every point is
/// computed in several precisions, by both methods (and for double in the
/// world frame and in the robust local frame), and compared with exact: as a
/// matrix (projective error) and geometrically (distance of exact terminator or
/// reflected points from the computed P or B, relative to the object's size).
///
/// With a candidate (another implementation, candidate_run.hpp) every point's
/// scene is also given to it: its result is measured by the same code as
/// qverify's own runs and added to the point as a run of the candidate; a
/// failed call or a result beyond the accuracy target is written as a
/// reproducer into out_dir/failures/.
///
/// The result is typed (StressReport); report/stress.hpp writes it as the
/// `qverify-stress/1` document and as the text `qverify stress` prints.

#include <qverify/eval/accuracy.hpp>
#include <qverify/eval/eval.hpp>
#include <qverify/studies/figure.hpp>
#include <qverify/verify/candidate_run.hpp>

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace qverify {

/// A family of stress points: one parameter swept over decades towards a breaking point.
struct StressFamily {
  std::string name, description, parameter;
  std::vector<double> values;              ///< parameter values (decades)
  std::function<std::string(double)> scene;  ///< qverify-scene/1 text for a parameter value
  bool reflection = false;                 ///< the family's item is a reflection (else a shadow)
};

/// The families of `qverify stress --list`.
const std::vector<StressFamily>& stress_families();

struct StressOptions {
  std::string out_dir;
  std::vector<std::string> families;  ///< empty: all
  int samples = 8;                    ///< exact points per item for the geometric error
  bool worst_only = false;            ///< only the last (most extreme) parameter value of each family
  std::function<void(const std::string&)> progress;
  /// Another implementation run on every point beside qverify's own runs (stress --candidate-cmd).
  std::optional<Candidate> candidate;
  /// The candidate's accuracy target T: a point where its item geometric error (P, polar plane and R, or B)
  /// exceeds T, or its call failed, is a reproducer (out_dir/failures/NAME-FAMILY-K.json, K the point's index).
  double accuracy = kDefaultAccuracy;
};

/// One run at a stress point: one of qverify's own (a precision and method,
/// computed as eval computes it) or the candidate's call, its item measured
/// against exact on the point's sample points. An error is infinite when the
/// run gave no finite item.
struct StressRun {
  std::string run;         ///< qverify's label ("double/direct (default, robust)", ...) or the candidate's name
  bool candidate = false;  ///< the candidate's call (else one of qverify's own runs)
  /// As run; the candidate's as its results state, none when its call failed.
  std::optional<Precision> precision;
  std::optional<Method> method;
  /// qverify's runs: eval gave the item with its accuracy (a run refused for its inputs did not).
  bool returned = false;
  std::optional<double> error_bound;  ///< eval's error bound, when it gives one (returned runs)
  std::optional<Frame> frame;         ///< the frame of the item (none when there is no item; a failed call)
  std::string status;                 ///< the item's status (the candidate: as claimed, or "unstated", or "candidate-failed")
  bool failed_call = false;           ///< the candidate's call failed (status "candidate-failed", `error` says why)
  std::string error;                  ///< why the candidate's call failed
  double seconds = 0;                 ///< the candidate's call: its wall time
  double matrix_error = std::numeric_limits<double>::infinity();     ///< projective error of P (B) against exact
  double geometric_error = std::numeric_limits<double>::infinity();  ///< geometric error of P (B)
  /// Geometric error over every result of the item (P, polar plane and R, or B): what eval's flag and the
  /// candidate's accuracy target are about. Measured on the sweep's points; for qverify's runs at least
  /// the error eval found the item to reach (ItemAccuracy::attained: certified where its bound is).
  double item_geometric_error = std::numeric_limits<double>::infinity();
  bool inaccurate = false;       ///< qverify's runs: eval flagged the item inaccurate
  bool beyond_accuracy = false;  ///< the candidate's call returned an item beyond the accuracy target
  /// The candidate: what verify's checks of its item found wrong (a status, sign, M or symmetry that
  /// no geometric error sees, or the geometric error itself); empty when they pass.
  std::vector<std::string> problems;
  std::optional<std::string> reproducer;  ///< the candidate: its reproducer's scene ("failures/...") when one was written
};

/// One parameter value of a family: the exact result's status, the references
/// the runs are judged against, and every run.
struct StressPoint {
  double param = 0;
  std::string exact_status;
  std::size_t sample_points = 0;      ///< exact points of the item the errors are measured on
  double kappa = 0;                   ///< first-order condition estimate of the naive (world-frame) double computation
  double predicted_double_error = 0;  ///< eps_double * kappa
  /// The floor: the exact results correctly rounded to double in the default run's frame, P's (B's) error on
  /// these points or the item's error eval finds the rounding to reach (certified where it certifies),
  /// the larger (infinite when not finite).
  double rounded_exact_error = std::numeric_limits<double>::infinity();
  double target = 0;                  ///< max(1e-9, 10 rounded_exact_error)
  /// The default (robust) double run is within the target from above: eval's error bound of the item
  /// (certified for what its certified_for names, accuracy.hpp) and its error on these points and in what
  /// eval proves it reaches (item_geometric_error) are at most `target`.
  bool default_meets_target = false;
  std::vector<StressRun> runs;        ///< qverify's runs, then the candidate's
};

/// A run of the flag's self-check: a missed flag, or a flag on an error these points measure small.
struct FlaggedRun {
  double param = 0;
  std::string run;
  double item_geometric_error = std::numeric_limits<double>::infinity();
};

/// The self-check of eval's inaccurate flag over a family. These points are not
/// eval's, and a sample bounds the true error only from below: an error above
/// the target here proves a flag missing; a flag where they show less than
/// target / 100 proves nothing and is listed as information.
struct FlagCheck {
  std::vector<FlaggedRun> missed;         ///< returned runs beyond the target 1e-9 and not flagged
  std::vector<FlaggedRun> flagged_below;  ///< flagged runs measured below 1e-11 here
  bool ok() const { return missed.empty(); }
};

/// A run's trend over a family: least-squares slopes of log10(error) against
/// log10(parameter) (none with fewer than two finite points) and its breakdown.
struct StressRunSummary {
  std::string run;  ///< the run's label, or the candidate's name
  std::optional<double> matrix_slope, geometric_slope;
  /// First parameter value where the run breaks: qverify's runs, a geometric error beyond 1e-9 (or none);
  /// the candidate, a failed call or an item beyond its accuracy target.
  std::optional<double> breakdown;
};

/// The candidate over one family.
struct StressCandidateFamily {
  std::string name;
  std::optional<double> breakdown;              ///< first parameter value with a failed call or beyond the target
  std::optional<std::string> breakdown_reason;  ///< the reason of that point's reproducer
  /// The family's reproducers, by kind: the call failed; the item beyond the accuracy target; else
  /// a check failed (status, sign, M, symmetry).
  int failed_calls = 0, beyond_accuracy = 0, failed_checks = 0;
};

/// One family swept: its points, the summaries of its runs and the flag's self-check.
struct StressFamilyResult {
  std::string name, description, parameter;
  bool reflection = false;  ///< the item is a reflection B (else a shadow P)
  /// The default double run meets the geometric target at every point.
  bool default_meets_target = true;
  FlagCheck flag_check;
  std::vector<StressPoint> points;
  std::optional<double> predicted_slope;  ///< slope of predicted_double_error (eps * kappa)
  std::vector<StressRunSummary> runs;     ///< in the order of the points' runs
  std::optional<StressCandidateFamily> candidate;
};

/// A reproducer of the candidate, as listed in the report.
struct StressReproducer {
  Reproducer written;        ///< the case and its files
  /// "candidate-failed" (the call failed), "beyond-accuracy" (its item beyond the accuracy target) or
  /// "failed-checks" (within the target, but a check failed: status, sign, M, symmetry)
  std::string status;
  double item_geometric_error = std::numeric_limits<double>::infinity();
};

/// The candidate over every family.
struct StressCandidateSummary {
  Candidate candidate;  ///< who it was: name, command (description), time-out; its function is not kept
  double accuracy = kDefaultAccuracy;  ///< its accuracy target T
  std::vector<double> call_seconds;    ///< every call's wall time, in the order of the calls
  int failed_calls = 0, beyond_accuracy = 0, failed_checks = 0;
  std::vector<StressReproducer> reproducers;
};

/// What a stress run found: the families swept, the candidate's totals (when
/// one was given) and one figure per family (geometric error against the
/// family's parameter for every run). report/stress.hpp writes it as the
/// `qverify-stress/1` document and as text; report/report.hpp as report.json,
/// report.html and FAMILY.svg.
struct StressReport {
  std::vector<StressFamilyResult> families;
  std::optional<StressCandidateSummary> candidate;
  std::vector<std::pair<std::string, Plot>> plots;  ///< (family name, figure)
};

/// Runs the sweeps. `out_dir` is created first (a bad one fails before any
/// work: FileWriteError naming the path); with a candidate its reproducers are
/// written into out_dir/failures/ as they are found (earlier NAME-* files there
/// are removed first).
StressReport run_stress(const StressOptions& opt);

}  // namespace qverify
