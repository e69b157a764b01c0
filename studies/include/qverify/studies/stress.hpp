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
/// qverify's own runs and added to the point as a run with "source":
/// "candidate"; a failed call or a result beyond the accuracy target is
/// written as a reproducer into out_dir/failures/.

#include <qverify/eval/accuracy.hpp>
#include <qverify/studies/figure.hpp>
#include <qverify/verify/candidate_run.hpp>

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace qverify {

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

/// What a stress run found: the `qverify-stress/1` document and one figure per
/// family (geometric error against the family's parameter for every run).
/// report/report.hpp writes them as report.json, report.html and FAMILY.svg.
struct StressReport {
  nlohmann::ordered_json document;
  std::vector<std::pair<std::string, Plot>> plots;  ///< (family name, figure)
};

/// Runs the sweeps. `out_dir` is created first (a bad one fails before any
/// work: FileWriteError naming the path); with a candidate its reproducers are
/// written into out_dir/failures/ as they are found (earlier NAME-* files there
/// are removed first).
StressReport run_stress(const StressOptions& opt);

}  // namespace qverify
