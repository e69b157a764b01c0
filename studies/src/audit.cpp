#include <qverify/exact/root_point.hpp>
#include <qverify/studies/audit.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/scene/json_tree.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace qverify {

using json = nlohmann::ordered_json;
using Q = Rational;

namespace {
template <int R, int C> double projective_error_impl(const Eigen::Matrix<Q, R, C>& X, const Eigen::Matrix<Q, R, C>& Y,
                                                      bool positive) {
  if (positive && !Y.isZero()) {
    const Eigen::Index p = pivot_index(Y);
    if (sign_of<Q>(X(p)) != sign_of<Q>(Y(p))) return 2;
  }
  return to_measure(cross_residual(X, Y)).template convert_to<double>();
}
}  // namespace

double projective_error(const Mat4<Q>& X, const Mat4<Q>& Y, bool positive) { return projective_error_impl(X, Y, positive); }
double projective_error(const Vec4<Q>& X, const Vec4<Q>& Y, bool positive) { return projective_error_impl(X, Y, positive); }

std::vector<Precision> default_ladder() {
  std::vector<Precision> out;
  for (const char* p : {"float", "double", "long-double", "float128", "mpfr:128", "mpfr:256", "interval", "exact"})
    out.push_back(*parse_precision(p));
  return out;
}

namespace {

/// Per item error of a result set against the exact evaluation (infinity when missing or not finite).
std::vector<double> item_errors(const ResultSet& rs, const Evaluation<Q>& ref) {
  std::vector<double> out;
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < ref.shadows.size(); ++k) {
    const ShadowMatrices& g = rs.shadows[k];
    const ShadowResult<Q>& w = ref.shadows[k].result;
    if (!g.present) {
      out.push_back(inf);
      continue;
    }
    const Vec3<Q> o = g.origin ? *g.origin : Vec3<Q>::Zero();  // compare in world coordinates
    out.push_back(std::max({projective_error(quadric_from_local(g.P, o), w.P, true),
                            projective_error(plane_from_local(g.polar, o), w.polar_plane, true),
                            projective_error(quadric_from_local(g.R, o), w.R, false)}));
  }
  for (std::size_t k = 0; k < ref.reflections.size(); ++k) {
    const ReflectionMatrices& g = rs.reflections[k];
    if (!g.present) {
      out.push_back(inf);
      continue;
    }
    const Vec3<Q> o = g.origin ? *g.origin : Vec3<Q>::Zero();
    const Mat4<Q> Me = translation<Q>(Vec3<Q>(-o)) * ref.reflections[k].M * translation<Q>(o);  // M in g's frame
    const double m_err =
        (to_measure(max_abs(Mat4<Q>(g.M - Me))) / to_measure(std::max(Q(1), max_abs(Me)))).convert_to<double>();
    out.push_back(std::max(projective_error(quadric_from_local(g.B, o), ref.reflections[k].result.B, true), m_err));
  }
  return out;
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

/// The largest and the median of a row's per-item errors (0 for a scene with no items): the two numbers a row
/// reports and the Pareto front and the figure read.
struct ErrorStats {
  double max = 0, median = 0;
};
ErrorStats error_stats(std::vector<double> e) {
  std::sort(e.begin(), e.end());
  if (e.empty()) return {};
  return {e.back(), e[e.size() / 2]};
}

/// What timed_results measured of a ladder row beside its errors.
struct LadderFacts {
  int inaccurate_items = 0;  ///< eval's flag: items whose error bound exceeds the accuracy target 1e-9
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
  bool bad = false;              ///< failed, a failed check or a geometric error beyond the accuracy target
  std::optional<json> reproducer;  ///< the reproducer's scene, when one was written
};

/// One row of the audit as typed values: a precision and method of the ladder, or the candidate. The Pareto
/// front, the items' errors and the figure are computed from these; the row's JSON is written once (to_json).
struct AuditRow {
  std::string precision, method;  ///< the candidate: its name and "candidate"
  double ns_per_item = 0;
  std::vector<double> errors;  ///< per item (infinity when missing or not finite)
  ErrorStats stats;
  std::optional<LadderFacts> ladder;        ///< set for a ladder row
  std::optional<CandidateFacts> candidate;  ///< set for the candidate's row

  /// "precision/method": the row's name in the document's pareto list and in each item's errors.
  std::string key() const { return precision + "/" + method; }
  /// The row's JSON (qverify-audit/1), fields in the document's order.
  json to_json(std::size_t n_items) const { return candidate ? candidate_json(n_items) : ladder_json(n_items); }

 private:
  /// max_rel_error, median_rel_error, correct_bits (= -log2(error); null for an exact zero) and exact_match.
  void error_fields(json& r) const {
    r["max_rel_error"] = number_or_null(stats.max);
    r["median_rel_error"] = number_or_null(stats.median);
    r["correct_bits"] = stats.max > 0 ? number_or_null(-std::log2(stats.max)) : json(nullptr);
    if (stats.max == 0) r["exact_match"] = true;
  }
  /// A ladder row: its timing and errors, then what timed_results reports.
  json ladder_json(std::size_t n_items) const {
    json r;
    r["precision"] = precision;
    r["method"] = method;
    r["ns_per_item"] = ns_per_item;
    error_fields(r);
    r["items"] = n_items;
    r["inaccurate_items"] = ladder->inaccurate_items;
    r["reps_per_batch"] = ladder->reps_per_batch;
    r["batches"] = ladder->batches;
    r["inputs_rounded"] = ladder->inputs_rounded;
    if (ladder->working_bits) r["working_bits"] = *ladder->working_bits;
    return r;
  }
  /// The candidate's row: who it is and its status, its time per call and errors, then the ladder's fields
  /// it has no value for (null or 1), whether it missed the target and its reproducer.
  json candidate_json(std::size_t n_items) const {
    const CandidateFacts& c = *candidate;
    json r;
    r["precision"] = precision;
    r["method"] = method;
    r["source"] = "candidate";
    r["run"] = c.name;
    r["status"] = c.status;
    if (c.ok) {
      r["claimed_precision"] = c.claimed_precision;
      r["claimed_method"] = c.claimed_method;
      r["checks_passed"] = c.checks_passed;
      r["checks_failed"] = c.checks_failed;
    } else {
      r["error"] = c.error;
    }
    r["ns_per_item"] = ns_per_item;
    r["seconds_per_call"] = c.seconds;
    error_fields(r);
    r["max_geometric_error"] = number_or_null(c.max_geometric_error);
    r["items"] = n_items;
    r["inaccurate_items"] = nullptr;
    r["reps_per_batch"] = 1;
    r["batches"] = 1;
    r["inputs_rounded"] = nullptr;
    r["beyond_accuracy"] = c.ok && c.bad;
    if (c.reproducer) r["reproducer"] = *c.reproducer;
    return r;
  }
};

/// One audit of a scene: the exact reference, then every row (the ladder's, the candidate's), then what is
/// computed from the rows (the Pareto front, the items' errors, the figure) and the document. A class so that
/// each step is a function of its own sharing the run's state, as FamilySweep does for stress.
class SceneAudit {
 public:
  /// The exact evaluation of the scene, the reference of every row.
  SceneAudit(const Scene& sc, const AuditOptions& opt)
      : sc_(sc), opt_(opt), ref_(evaluate<Q>(sc, Method::direct)), n_items_(sc.shadows.size() + sc.reflections.size()) {}

  /// Every precision of the ladder by both methods: timed and measured against exact, one row each.
  void measure_ladder() {
    const auto ladder = opt_.ladder.empty() ? default_ladder() : opt_.ladder;
    const std::size_t total = ladder.size() * 2;
    std::size_t done = 0;
    for (const Precision& prec : ladder)
      for (Method m : {Method::direct, Method::paper}) {
        if (opt_.progress)
          opt_.progress("audit: [" + std::to_string(++done) + "/" + std::to_string(total) + "] " + prec.name() + "/" +
                        method_name(m));
        rows_.push_back(ladder_row(prec, m));
      }
  }

  /// The candidate (when given): one call on the scene, a row beside the ladder's, each item's geometric
  /// error as verify --candidate measures it, and a reproducer when it fails or misses the accuracy target.
  void measure_candidate() {
    if (!opt_.candidate) return;
    const Candidate& cand = *opt_.candidate;
    if (opt_.progress) opt_.progress("audit: candidate " + cand.name);
    const std::filesystem::path failures_dir = std::filesystem::path(opt_.out_dir) / "failures";
    remove_candidate_reproducers(failures_dir, cand.name);
    const std::string text = opt_.scene_text.empty() ? read_text_file(sc_.file, JsonLimits{}.max_bytes) : opt_.scene_text;
    const CandidateCall call = call_candidate(cand, sc_, text, "audit-0");
    AuditRow r = candidate_row(call);
    if (r.candidate->bad) write_reproducer(*r.candidate, failures_dir, text, call);
    rows_.push_back(std::move(r));
  }

  /// The document (qverify-audit/1) and its figure, from the rows.
  AuditReport report() const {
    const std::vector<std::string> front = pareto_front();
    return {document(front), plot(front)};
  }

 private:
  /// One precision and method of the ladder: timed (timed_results), its errors against exact, eval's flags.
  AuditRow ladder_row(const Precision& prec, Method m) const {
    const TimedResult tr = timed_results(sc_, prec, m, opt_.batch_seconds, opt_.batches);
    AuditRow r;
    r.precision = prec.name();
    r.method = method_name(m);
    r.ns_per_item = tr.ns_per_item;
    r.errors = item_errors(tr.results, ref_);
    r.stats = error_stats(r.errors);
    LadderFacts f;
    for (const auto& it : tr.results.shadows) f.inaccurate_items += it.accuracy && it.accuracy->inaccurate;
    for (const auto& it : tr.results.reflections) f.inaccurate_items += it.accuracy && it.accuracy->inaccurate;
    f.reps_per_batch = tr.reps_per_batch;
    f.batches = tr.batches;
    f.inputs_rounded = tr.inputs_rounded;
    if (prec.kind == Precision::Kind::mpfr) f.working_bits = digits_for_bits(prec.bits).bits;
    r.ladder = f;
    return r;
  }

  /// The candidate's row from its call: matrix errors against exact, and each item checked as verify
  /// --candidate checks it (opt.samples exact points, seed 1) for candidate_geo_. A failed call has
  /// infinite errors and every check failed.
  AuditRow candidate_row(const CandidateCall& call) {
    const Candidate& cand = *opt_.candidate;
    const double inf = std::numeric_limits<double>::infinity();
    AuditRow r;
    r.precision = cand.name;
    r.method = "candidate";
    r.errors.assign(n_items_, inf);
    candidate_geo_.assign(n_items_, inf);
    CandidateFacts c;
    c.name = cand.name;
    c.ok = call.ok;
    c.seconds = call.seconds;
    c.checks_failed = static_cast<int>(n_items_);
    if (call.ok) {
      r.errors = item_errors(call.results, ref_);
      const VerifyReport v = verify_results(sc_, call.results, VerifyOptions{opt_.samples, 1, opt_.accuracy});
      c.checks_failed = v.failed;
      for (std::size_t i = 0; i < n_items_ && i < v.checks.size(); ++i) {
        const VerifyCheck& g = v.checks[i];
        if (g.report && !g.report->skipped && std::isfinite(g.report->geometric_error))
          candidate_geo_[i] = g.report->geometric_error;
        else if (g.skipped())
          candidate_geo_[i] = NAN;  // nothing to measure on (no real terminator point)
      }
      c.status = v.failed > 0 ? "fail" : "pass";
      c.claimed_precision = call.results.precision.name();
      c.claimed_method = method_name(call.results.method);
      c.checks_passed = v.passed;
    } else {
      c.status = "candidate-failed";
      c.error = call.error;
    }
    r.stats = error_stats(r.errors);
    for (double g : candidate_geo_)
      if (!std::isnan(g)) c.max_geometric_error = std::max(c.max_geometric_error, g);
    r.ns_per_item = call.seconds * 1e9 / static_cast<double>(std::max<std::size_t>(n_items_, 1));
    c.bad = !call.ok || c.checks_failed > 0 || !(c.max_geometric_error <= opt_.accuracy);
    r.candidate = c;
    return r;
  }

  /// Writes the scene as the candidate's reproducer (failures/NAME-audit-0.*) with the reason, and lists it.
  void write_reproducer(CandidateFacts& c, const std::filesystem::path& failures_dir, const std::string& text,
                        const CandidateCall& call) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "largest item geometric error %.3g of the object size (accuracy target %.3g); %d of %zu checks failed",
                  c.max_geometric_error, opt_.accuracy, c.checks_failed, n_items_);
    const std::string reason = call.ok ? std::string(buf) : "candidate-failed: " + call.error;
    json rep = write_candidate_reproducer(failures_dir, c.name, "audit", 0, 0, text, call, reason);
    rep.erase("param");
    rep["status"] = call.ok ? "beyond-accuracy" : "candidate-failed";
    c.reproducer = rep["scene"];
    reproducers_.push_back(rep);
  }

  /// The rows not dominated in (time, error): no other row is as fast and as accurate and better in one.
  /// A row without a finite error counts as infinitely wrong.
  std::vector<std::string> pareto_front() const {
    auto error = [](const AuditRow& r) { return std::isfinite(r.stats.max) ? r.stats.max : INFINITY; };
    std::vector<std::string> front;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      const double ti = rows_[i].ns_per_item, ei = error(rows_[i]);
      bool dominated = false;
      for (std::size_t j = 0; j < rows_.size() && !dominated; ++j) {
        if (i == j) continue;
        const double tj = rows_[j].ns_per_item, ej = error(rows_[j]);
        dominated = tj <= ti && ej <= ei && (tj < ti || ej < ei);
      }
      if (!dominated) front.push_back(rows_[i].key());
    }
    return front;
  }

  /// Every item (shadows, then reflections) with its error in every row, and the candidate's geometric error.
  json items() const {
    json items = json::array();
    std::size_t k = 0;
    auto add_item = [&](json it) {
      json errs;
      for (const AuditRow& r : rows_) errs[r.key()] = number_or_null(r.errors[k]);
      it["errors"] = errs;
      if (opt_.candidate) it["geometric_errors"] = {{opt_.candidate->name, number_or_null(candidate_geo_[k])}};
      items.push_back(it);
      ++k;
    };
    for (const auto& it : ref_.shadows)
      add_item({{"kind", "shadow"},
                {"quadric", sc_.quadrics[it.pair.quadric].id},
                {"light", sc_.lights[it.pair.other].id},
                {"exact_status", it.result.status()}});
    for (const auto& it : ref_.reflections)
      add_item({{"kind", "reflection"},
                {"quadric", sc_.quadrics[it.pair.quadric].id},
                {"mirror", sc_.mirrors[it.pair.other].id},
                {"exact_status", it.result.status()}});
    return items;
  }

  /// The document's "candidate" section: the candidate, its rule, its status and its reproducers.
  json candidate_section() const {
    json c = candidate_section_head(*opt_.candidate, opt_.accuracy);
    c["rule"] = "the candidate is called once on the scene and must return a qverify-eval/1 document with every "
                "requested item; its row has the matrix errors of the ladder and ns_per_item = the wall time of the "
                "call (process start included) / items; each item is checked as verify --candidate checks it (" +
                std::to_string(opt_.samples) + " exact points, seed 1): geometric_errors; a failed call, a failed "
                "check or a geometric error beyond accuracy writes the scene as a reproducer";
    c["status"] = rows_.back().candidate->status;
    c["failures_dir"] = reproducers_.empty() ? json(nullptr) : json("failures");
    c["reproducers"] = reproducers_;
    return c;
  }

  /// The qverify-audit/1 document: how errors and times are measured, the rows, the front, the items.
  json document(const std::vector<std::string>& front) const {
    json rows = json::array();
    for (const AuditRow& r : rows_) rows.push_back(r.to_json(n_items_));
    json doc;
    doc["format"] = "qverify-audit/1";
    doc["scene"] = sc_.name;
    doc["reference"] = "exact";
    doc["scale_removal"] =
        "each result X is compared with the exact Y as a projective object: max_i |X_i Y_p - Y_i X_p| / (|X|_max |Y_p|), "
        "p the largest entry of Y (cross-multiplication, no division by an entry; zero exactly when X = lambda Y). P, the "
        "polar plane and B must have the contract's positive factor (a sign error counts as 2); R is free up to any "
        "non-zero factor; M is compared entry by entry (relative to max(1, |M|_max)). An item's error is the largest of "
        "its matrices'; errors are computed exactly from the results converted to rationals.";
    doc["timing"] = "ns_per_item: median over " + std::to_string(opt_.batches) +
                    " batches of the evaluation of all requested items from inputs already in the precision (each batch "
                    "repeated until it lasts >= " +
                    std::to_string(static_cast<int>(opt_.batch_seconds * 1000)) +
                    " ms; results kept behind a compiler barrier), single thread";
    doc["rows"] = rows;
    doc["pareto"] = front;
    doc["items"] = items();
    doc["skipped"] = skipped_json(sc_);
    if (opt_.candidate) doc["candidate"] = candidate_section();
    return doc;
  }

  /// The figure: max error against ns per item, direct, paper and the candidate as series, the front as a line.
  Plot plot(const std::vector<std::string>& front) const {
    Plot plot;
    plot.title = "error against run time: " + sc_.name;
    plot.x_label = "ns per item (median, single thread)";
    plot.y_label = "max relative error as quadrics";
    PlotSeries direct{"direct", "#1f77b4", {}, false, true, false, {}}, paper{"paper", "#ff7f0e", {}, false, true, false, {}},
        front_series{"Pareto front", "#2ca02c", {}, true, false, true, {}},
        candidate{(opt_.candidate ? opt_.candidate->name : std::string()) + " (candidate; wall time per call)", "#e377c2", {},
                  false, true, false, {}};
    for (const AuditRow& r : rows_) {
      PlotSeries& s = r.candidate ? candidate : r.method == "direct" ? direct : paper;
      s.points.emplace_back(r.ns_per_item, std::isfinite(r.stats.max) ? r.stats.max : NAN);
      s.labels.push_back(r.candidate ? r.candidate->name : r.precision);
    }
    std::vector<std::pair<double, double>> fpts;
    for (const AuditRow& r : rows_)
      for (const std::string& key : front)
        if (r.key() == key && std::isfinite(r.stats.max)) fpts.emplace_back(r.ns_per_item, r.stats.max);
    std::sort(fpts.begin(), fpts.end());
    front_series.points = fpts;
    paper.labels_below = true;
    plot.series = {direct, paper, front_series};
    if (!candidate.points.empty()) plot.series.push_back(candidate);
    return plot;
  }

  const Scene& sc_;
  const AuditOptions& opt_;
  const Evaluation<Q> ref_;   ///< the exact results every row is measured against
  const std::size_t n_items_;  ///< requested items: shadows, then reflections
  std::vector<AuditRow> rows_;  ///< the ladder's, then the candidate's
  std::vector<double> candidate_geo_;  ///< per item: the candidate's geometric error as verify --candidate measures it
  json reproducers_ = json::array();   ///< the candidate's reproducer, when written
};

}  // namespace

AuditReport run_audit(const Scene& sc, const AuditOptions& opt) {
  create_output_directory(opt.out_dir);  // before the measurements: a bad --out fails at once
  SceneAudit audit(sc, opt);
  audit.measure_ladder();
  audit.measure_candidate();
  return audit.report();
}

}  // namespace qverify
