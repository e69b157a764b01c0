#include <qverify/exact/root_point.hpp>
#include <qverify/studies/audit.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/scene/json_tree.hpp>  // JsonLimits: the size limit of a scene file

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace qverify {

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

ErrorStats error_stats(std::vector<double> e) {
  std::sort(e.begin(), e.end());
  if (e.empty()) return {};
  return {e.back(), e[e.size() / 2]};
}

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

  /// The report: the rows, and what is computed from them (the Pareto front, the items, the figure).
  AuditReport report() const {
    AuditReport rep;
    rep.scene = sc_.name;
    rep.options = opt_;
    rep.options.progress = nullptr;
    if (rep.options.ladder.empty()) rep.options.ladder = default_ladder();
    rep.rows = rows_;
    rep.pareto = pareto_front();
    rep.items = items();
    rep.skipped = skipped_pairs(sc_);
    rep.error_vs_time = plot(rep.pareto);
    return rep;
  }

 private:
  /// One precision and method of the ladder: timed (timed_results), its errors against exact, eval's flags.
  AuditRow ladder_row(const Precision& prec, Method m) const {
    AuditRow r;
    r.precision = prec.name();
    r.method = method_name(m);
    const TimedResult tr = timed_results(sc_, prec, m, opt_.batch_seconds, opt_.batches);
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
    // eval's flag self-checked as stress checks it (FlagCheck), with finite errors only: verify's exact points measure each
    // item's geometric error from below, so one beyond the target that eval did not flag is a flag
    // proved missing. (Exact rows have neither flags nor errors. An infinite error, a point off the
    // result where its gradient vanishes, is no distance, and proves nothing here: verify fails it.)
    if (prec.kind != Precision::Kind::exact) {
      const VerifyReport v = verify_results(sc_, tr.results, VerifyOptions{opt_.samples, 1, kDefaultAccuracy});
      for (const VerifyCheck& g : v.checks)
        if (g.report && !g.report->skipped && std::isfinite(g.report->geometric_error) &&
            g.report->geometric_error > kDefaultAccuracy && !g.inaccurate)
          f.missed_flags.push_back(g.kind + " " + g.quadric + "/" + g.other);
    }
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
        if (!g.passed() && !g.skipped()) {
          const std::string item = g.kind + " " + g.quadric + "/" + g.other + ": ";
          if (!g.report) c.problems.push_back(item + (g.missing.empty() ? std::string("no result") : g.missing));
          else
            for (const std::string& p : g.report->problems) c.problems.push_back(item + p);
        }
        if (g.report && !g.report->skipped && std::isfinite(g.report->geometric_error))
          candidate_geo_[i] = g.report->geometric_error;
        else if (g.skipped() || !g.report)
          candidate_geo_[i] = NAN;  // nothing to measure on (no real terminator point; an item missing: a failed check)
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
    std::string reason = call.ok ? std::string(buf) : "candidate-failed: " + call.error;
    for (const std::string& p : c.problems) reason += "; " + p;
    c.reproducer = qverify::write_reproducer(failures_dir, c.name, "audit", 0, 0, text, call, reason);
  }

  /// The rows not dominated in (time, error): no other row is as fast and as accurate and better in one.
  /// A row without a finite error (a missing or non-finite result, a precision that cannot hold the
  /// scene) is on no front, however fast.
  std::vector<std::string> pareto_front() const {
    auto error = [](const AuditRow& r) { return std::isfinite(r.stats.max) ? r.stats.max : INFINITY; };
    std::vector<std::string> front;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      const double ti = rows_[i].ns_per_item, ei = error(rows_[i]);
      if (!std::isfinite(ei) || !std::isfinite(ti)) continue;  // no result to trade time against: never on the front
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

  /// Every item (shadows, then reflections), with the candidate's geometric error on it.
  std::vector<AuditItem> items() const {
    std::vector<AuditItem> items;
    for (const auto& it : ref_.shadows)
      items.push_back({true, sc_.quadrics[it.pair.quadric].id, sc_.lights[it.pair.other].id, it.result.status(), {}});
    for (const auto& it : ref_.reflections)
      items.push_back({false, sc_.quadrics[it.pair.quadric].id, sc_.mirrors[it.pair.other].id, it.result.status(), {}});
    if (opt_.candidate)
      for (std::size_t k = 0; k < items.size(); ++k) items[k].candidate_geometric_error = candidate_geo_[k];
    return items;
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
};

}  // namespace

bool audit_found_error(const AuditReport& a) {
  return std::any_of(a.rows.begin(), a.rows.end(), [](const AuditRow& r) {
    return (r.candidate && r.candidate->bad) || (r.ladder && !r.ladder->missed_flags.empty());
  });
}

AuditReport run_audit(const Scene& sc, const AuditOptions& opt) {
  create_output_directory(opt.out_dir);  // before the measurements: a bad --out fails at once
  SceneAudit audit(sc, opt);
  audit.measure_ladder();
  audit.measure_candidate();
  return audit.report();
}

}  // namespace qverify
