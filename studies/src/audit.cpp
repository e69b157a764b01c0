#include <qverify/exact/root_point.hpp>
#include <qverify/studies/audit.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/scene/json_tree.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

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

std::string row_key(const json& r) { return r["precision"].get<std::string>() + "/" + r["method"].get<std::string>(); }

}  // namespace

AuditReport run_audit(const Scene& sc, const AuditOptions& opt) {
  create_output_directory(opt.out_dir);  // before the measurements: a bad --out fails at once
  const auto ladder = opt.ladder.empty() ? default_ladder() : opt.ladder;
  const Evaluation<Q> ref = evaluate<Q>(sc, Method::direct);
  const std::size_t n_items = sc.shadows.size() + sc.reflections.size();

  json rows = json::array();
  std::vector<std::vector<double>> errors;  // per row, per item
  const std::size_t total = ladder.size() * 2;
  std::size_t done = 0;
  for (const Precision& prec : ladder)
    for (Method m : {Method::direct, Method::paper}) {
      if (opt.progress)
        opt.progress("audit: [" + std::to_string(++done) + "/" + std::to_string(total) + "] " + prec.name() + "/" +
                     method_name(m));
      const TimedResult tr = timed_results(sc, prec, m, opt.batch_seconds, opt.batches);
      std::vector<double> e = item_errors(tr.results, ref);
      std::vector<double> sorted = e;
      std::sort(sorted.begin(), sorted.end());
      const double maxe = sorted.empty() ? 0 : sorted.back();
      const double mede = sorted.empty() ? 0 : sorted[sorted.size() / 2];
      json r;
      r["precision"] = prec.name();
      r["method"] = method_name(m);
      r["ns_per_item"] = tr.ns_per_item;
      r["max_rel_error"] = number_or_null(maxe);
      r["median_rel_error"] = number_or_null(mede);
      // correct bits = -log2(error); infinite (null) for an exact zero
      r["correct_bits"] = maxe > 0 ? number_or_null(-std::log2(maxe)) : json(nullptr);
      if (maxe == 0) r["exact_match"] = true;
      r["items"] = n_items;
      // eval's flag per precision: items whose error bound exceeds the accuracy target 1e-9
      int inaccurate = 0;
      for (const auto& it : tr.results.shadows) inaccurate += it.accuracy && it.accuracy->inaccurate;
      for (const auto& it : tr.results.reflections) inaccurate += it.accuracy && it.accuracy->inaccurate;
      r["inaccurate_items"] = inaccurate;
      r["reps_per_batch"] = tr.reps_per_batch;
      r["batches"] = tr.batches;
      r["inputs_rounded"] = tr.inputs_rounded;
      if (prec.kind == Precision::Kind::mpfr) r["working_bits"] = digits_for_bits(prec.bits).bits;
      rows.push_back(r);
      errors.push_back(std::move(e));
    }

  // The candidate: one call on the scene, a row beside the ladder's.
  json candidate_doc = nullptr;
  std::vector<double> candidate_geo;  // per item: geometric error as verify --candidate measures it
  if (opt.candidate) {
    const Candidate& cand = *opt.candidate;
    if (opt.progress) opt.progress("audit: candidate " + cand.name);
    const std::filesystem::path failures_dir = std::filesystem::path(opt.out_dir) / "failures";
    remove_candidate_reproducers(failures_dir, cand.name);
    const std::string text = opt.scene_text.empty() ? read_text_file(sc.file, JsonLimits{}.max_bytes) : opt.scene_text;
    const CandidateCall call = call_candidate(cand, sc, text, "audit-0");
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> e(n_items, inf);
    candidate_geo.assign(n_items, inf);
    int checks_failed = static_cast<int>(n_items);
    json r;
    r["precision"] = cand.name;
    r["method"] = "candidate";
    r["source"] = "candidate";
    r["run"] = cand.name;
    if (call.ok) {
      e = item_errors(call.results, ref);
      const VerifyReport v = verify_results(sc, call.results, VerifyOptions{opt.samples, 1, opt.accuracy});
      checks_failed = v.failed;
      for (std::size_t i = 0; i < n_items && i < v.checks.size(); ++i) {
        const VerifyCheck& g = v.checks[i];
        if (g.report && !g.report->skipped && std::isfinite(g.report->geometric_error))
          candidate_geo[i] = g.report->geometric_error;
        else if (g.skipped())
          candidate_geo[i] = NAN;  // nothing to measure on (no real terminator point)
      }
      r["status"] = v.failed > 0 ? "fail" : "pass";
      r["claimed_precision"] = call.results.precision.name();
      r["claimed_method"] = method_name(call.results.method);
      r["checks_passed"] = v.passed;
      r["checks_failed"] = v.failed;
    } else {
      r["status"] = "candidate-failed";
      r["error"] = call.error;
    }
    std::vector<double> sorted = e;
    std::sort(sorted.begin(), sorted.end());
    const double maxe = sorted.empty() ? 0 : sorted.back();
    const double mede = sorted.empty() ? 0 : sorted[sorted.size() / 2];
    double max_geo = 0;
    for (double g : candidate_geo)
      if (!std::isnan(g)) max_geo = std::max(max_geo, g);
    r["ns_per_item"] = call.seconds * 1e9 / static_cast<double>(std::max<std::size_t>(n_items, 1));
    r["seconds_per_call"] = call.seconds;
    r["max_rel_error"] = number_or_null(maxe);
    r["median_rel_error"] = number_or_null(mede);
    r["correct_bits"] = maxe > 0 ? number_or_null(-std::log2(maxe)) : json(nullptr);
    if (maxe == 0) r["exact_match"] = true;
    r["max_geometric_error"] = number_or_null(max_geo);
    r["items"] = n_items;
    r["inaccurate_items"] = nullptr;
    r["reps_per_batch"] = 1;
    r["batches"] = 1;
    r["inputs_rounded"] = nullptr;
    const bool bad = !call.ok || checks_failed > 0 || !(max_geo <= opt.accuracy);
    r["beyond_accuracy"] = call.ok && bad;
    json reproducers = json::array();
    if (bad) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "largest item geometric error %.3g of the object size (accuracy target %.3g); %d of %zu checks failed",
                    max_geo, opt.accuracy, checks_failed, n_items);
      const std::string reason = call.ok ? std::string(buf) : "candidate-failed: " + call.error;
      json rep = write_candidate_reproducer(failures_dir, cand.name, "audit", 0, 0, text, call, reason);
      rep.erase("param");
      rep["status"] = call.ok ? "beyond-accuracy" : "candidate-failed";
      r["reproducer"] = rep["scene"];
      reproducers.push_back(rep);
    }
    rows.push_back(r);
    errors.push_back(std::move(e));
    candidate_doc = {{"name", cand.name},
                     {"source", "candidate"},
                     {"command", cand.description},
                     {"timeout_seconds", cand.timeout_seconds > 0 ? json(cand.timeout_seconds) : json(nullptr)},
                     {"accuracy", opt.accuracy},
                     {"rule", "the candidate is called once on the scene and must return a qverify-eval/1 document "
                              "with every requested item; its row has the matrix errors of the ladder and ns_per_item = "
                              "the wall time of the call (process start included) / items; each item is checked as "
                              "verify --candidate checks it (" + std::to_string(opt.samples) + " exact points, seed 1): "
                              "geometric_errors; a failed call, a failed check or a geometric error beyond accuracy "
                              "writes the scene as a reproducer"},
                     {"status", r["status"]},
                     {"failures_dir", reproducers.empty() ? json(nullptr) : json("failures")},
                     {"reproducers", reproducers}};
  }

  // Pareto front: not dominated in (time, error).
  json pareto = json::array();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double ti = rows[i]["ns_per_item"].get<double>();
    const double ei = rows[i]["max_rel_error"].is_null() ? INFINITY : rows[i]["max_rel_error"].get<double>();
    bool dominated = false;
    for (std::size_t j = 0; j < rows.size() && !dominated; ++j) {
      if (i == j) continue;
      const double tj = rows[j]["ns_per_item"].get<double>();
      const double ej = rows[j]["max_rel_error"].is_null() ? INFINITY : rows[j]["max_rel_error"].get<double>();
      dominated = tj <= ti && ej <= ei && (tj < ti || ej < ei);
    }
    if (!dominated) pareto.push_back(row_key(rows[i]));
  }

  json items = json::array();
  std::size_t k = 0;
  auto add_item = [&](json it) {
    json errs;
    for (std::size_t r = 0; r < rows.size(); ++r) errs[row_key(rows[r])] = number_or_null(errors[r][k]);
    it["errors"] = errs;
    if (opt.candidate) it["geometric_errors"] = {{opt.candidate->name, number_or_null(candidate_geo[k])}};
    items.push_back(it);
    ++k;
  };
  for (const auto& it : ref.shadows)
    add_item({{"kind", "shadow"},
              {"quadric", sc.quadrics[it.pair.quadric].id},
              {"light", sc.lights[it.pair.other].id},
              {"exact_status", it.result.status()}});
  for (const auto& it : ref.reflections)
    add_item({{"kind", "reflection"},
              {"quadric", sc.quadrics[it.pair.quadric].id},
              {"mirror", sc.mirrors[it.pair.other].id},
              {"exact_status", it.result.status()}});

  json doc;
  doc["format"] = "qverify-audit/1";
  doc["scene"] = sc.name;
  doc["reference"] = "exact";
  doc["scale_removal"] =
      "each result X is compared with the exact Y as a projective object: max_i |X_i Y_p - Y_i X_p| / (|X|_max |Y_p|), "
      "p the largest entry of Y (cross-multiplication, no division by an entry; zero exactly when X = lambda Y). P, the "
      "polar plane and B must have the contract's positive factor (a sign error counts as 2); R is free up to any "
      "non-zero factor; M is compared entry by entry (relative to max(1, |M|_max)). An item's error is the largest of "
      "its matrices'; errors are computed exactly from the results converted to rationals.";
  doc["timing"] = "ns_per_item: median over " + std::to_string(opt.batches) +
                  " batches of the evaluation of all requested items from inputs already in the precision (each batch "
                  "repeated until it lasts >= " +
                  std::to_string(static_cast<int>(opt.batch_seconds * 1000)) +
                  " ms; results kept behind a compiler barrier), single thread";
  doc["rows"] = rows;
  doc["pareto"] = pareto;
  doc["items"] = items;
  doc["skipped"] = skipped_json(sc);
  if (opt.candidate) doc["candidate"] = candidate_doc;

  // ---- the figure
  Plot plot;
  plot.title = "error against run time: " + sc.name;
  plot.x_label = "ns per item (median, single thread)";
  plot.y_label = "max relative error as quadrics";
  PlotSeries direct{"direct", "#1f77b4", {}, false, true, false, {}}, paper{"paper", "#ff7f0e", {}, false, true, false, {}},
      front{"Pareto front", "#2ca02c", {}, true, false, true, {}},
      candidate{(opt.candidate ? opt.candidate->name : std::string()) + " (candidate; wall time per call)", "#e377c2", {}, false,
                true, false, {}};
  for (const auto& r : rows) {
    const double t = r["ns_per_item"].get<double>();
    const double e = r["max_rel_error"].is_null() ? NAN : r["max_rel_error"].get<double>();
    PlotSeries& s = r.contains("source") ? candidate : r["method"] == "direct" ? direct : paper;
    s.points.emplace_back(t, e);
    s.labels.push_back(r.contains("source") ? r["run"].get<std::string>() : r["precision"].get<std::string>());
  }
  std::vector<std::pair<double, double>> fpts;
  for (const auto& r : rows)
    for (const auto& key : pareto)
      if (row_key(r) == key.get<std::string>() && !r["max_rel_error"].is_null())
        fpts.emplace_back(r["ns_per_item"].get<double>(), r["max_rel_error"].get<double>());
  std::sort(fpts.begin(), fpts.end());
  front.points = fpts;
  paper.labels_below = true;
  plot.series = {direct, paper, front};
  if (!candidate.points.empty()) plot.series.push_back(candidate);
  return {std::move(doc), std::move(plot)};
}

}  // namespace qverify
