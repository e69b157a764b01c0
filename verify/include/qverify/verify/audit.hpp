#pragma once
/// \file audit.hpp
/// `qverify audit SCENE --out DIR`: every requested item computed in every
/// precision of the ladder by both methods, timed, and compared with the exact
/// result as quadrics (scale removed by cross-multiplication). Writes
/// report.json (qverify-audit/1), report.html (self-contained) and
/// error-vs-time.svg.
///
/// With a candidate (another implementation, candidate_run.hpp), it is called
/// once on the scene and its results are a row beside the ladder's: the same
/// matrix error against exact, the wall time of the call per item, and the
/// geometric error of every item as `verify --candidate` measures it.

#include <qverify/core/batch.hpp>
#include <qverify/verify/candidate_run.hpp>
#include <qverify/verify/verifier.hpp>

#include <algorithm>
#include <chrono>
#include <functional>

namespace qverify {

/// Results of one (precision, method) with the time per item.
struct TimedResult {
  ResultSet results;
  double ns_per_item = 0;  ///< median over batches
  long reps_per_batch = 0;
  int batches = 0;
  std::size_t inputs_rounded = 0;
};

/// Keeps `p`'s pointee alive as far as the optimiser can tell.
inline void clobber(const void* p) { asm volatile("" : : "r"(p) : "memory"); }

/// Times evaluate_items (inputs already rounded into S) in batches of at least
/// `batch_seconds`, median of `batches`, and returns the results converted
/// exactly.
template <class S>
TimedResult timed_results(const Scene& sc, const Precision& prec, Method method, double batch_seconds, int batches) {
  using clock = std::chrono::steady_clock;
  TimedResult tr;
  Evaluation<S> ev;
  ev.scene = typed_scene<S>(sc);
  prepare<S>(sc, Frame::world, ev);  // the ladder compares precisions in the world frame
  tr.inputs_rounded = ev.scene.rounded_inputs.size();
  const std::size_t items = sc.shadows.size() + sc.reflections.size();
  auto batch = [&](long reps) {
    const auto t0 = clock::now();
    for (long r = 0; r < reps; ++r) {
      evaluate_items<S>(sc, method, ev);
      clobber(ev.shadows.data());
      clobber(ev.reflections.data());
    }
    return std::chrono::duration<double>(clock::now() - t0).count();
  };
  long reps = 1;
  while (items > 0 && batch(reps) < batch_seconds && reps < (1L << 24)) reps *= 2;
  std::vector<double> ns;
  for (int b = 0; items > 0 && b < batches; ++b) ns.push_back(batch(reps) * 1e9 / static_cast<double>(reps * items));
  std::sort(ns.begin(), ns.end());
  tr.ns_per_item = ns.empty() ? 0 : ns[ns.size() / 2];
  tr.reps_per_batch = reps;
  tr.batches = static_cast<int>(ns.size());
  evaluate_items<S>(sc, method, ev);
  check_items<S>(sc, method, ev, AccuracyOptions{});  // error bounds, flags and exact statuses, not timed
  tr.results = result_set<S>(sc, ev, prec, method);
  return tr;
}

TimedResult timed_results(const Scene& sc, const Precision& prec, Method method, double batch_seconds, int batches);

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

/// Runs the audit, writes the three files into `out_dir` (created first; checked
/// writes, files.hpp: throws FileWriteError naming the path), with a candidate
/// that fails or misses the target also its reproducer (out_dir/failures/
/// NAME-audit-0.*; earlier NAME-* files there are removed first); returns
/// report.json's document.
nlohmann::ordered_json run_audit(const Scene& sc, const AuditOptions& opt);

}  // namespace qverify
