#include <qverify/report/eval_document.hpp>
#include <qverify/report/verify_document.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace qverify {
namespace {

using json = nlohmann::ordered_json;

double to_d(const Measure& m) { return m.convert_to<double>(); }

json metric_json(const QuadricCheck& c) {
  const Metric& m = c.metric;
  if (c.name == "as_matrices")  // (check.cpp: P, the polar plane and R against the exact ones, a single-point terminator)
    return {{"max_cross_residual", to_d(m.residual)}, {"geometric_error", number_or_null(c.geometric_error)}};
  json j{{"max_residual", to_d(m.residual)}, {"max_distance", m.singular ? json(nullptr) : json(to_d(m.distance))}};
  if (!c.judged) j["judged"] = false;
  j["geometric_error"] = number_or_null(c.geometric_error);
  if (m.singular) j["note"] = "a point lies off the result where its gradient vanishes: no distance of either order";
  return j;
}

/// The check's measures: points, target, object size, geometric error, one entry per quadric checked.
void measures_json(json& c, const CheckReport& r, const std::vector<const char*>& quadrics,
                   const std::vector<std::pair<const char*, const char*>>& contract_keys) {
  c["points"] = r.points;
  c["tolerance"] = r.accuracy;
  c["accuracy"] = r.accuracy;
  c["object_size"] = r.object_size;
  c["geometric_error"] = number_or_null(r.geometric_error);
  for (const char* name : quadrics)
    if (const QuadricCheck* q = r.find(name)) c[name] = metric_json(*q);
  // The contract's per-quadric keys (key, result) are in every check with a report, for each result
  // given, as where there are points (scripts read them unguarded: audit 42c F1). With no finite
  // point to sample (a terminator real only at infinity, A L = 0, a zero quadric) they measure
  // nothing: no point, no residual; the results were judged without points (as_matrices, the zero
  // and sign tests), which the verdict and the note say.
  if (r.points == 0)
    for (const auto& [key, result] : contract_keys)
      if (!c.contains(key) && std::find(r.given.begin(), r.given.end(), result) != r.given.end())
        c[key] = {{"max_residual", 0.0}, {"max_distance", 0.0}, {"judged", false}, {"geometric_error", 0.0}, {"points", 0}};
}

/// A check's problems in one line.
std::string problems_text(const CheckReport& r) {
  std::string text;
  for (const auto& p : r.problems) text += (text.empty() ? "" : "; ") + p;
  return text;
}

void verdict_json(json& c, const CheckReport& r) {
  if (!r.problems.empty()) c["reason"] = problems_text(r);
  c["status"] = r.passed ? "pass" : "fail";
}

json check_json(const VerifyCheck& v, bool exact) {
  const bool shadow = v.kind == "shadow";
  json c;
  c["kind"] = v.kind;
  c["quadric"] = v.quadric;
  c[shadow ? "light" : "mirror"] = v.other;
  c["exact_status"] = v.exact_status;
  if (!v.report) {
    c["reason"] = v.missing;
    c["status"] = "fail";
    return c;
  }
  const CheckReport& r = *v.report;
  if (r.skipped) {  // nothing to sample
    c["status"] = "skipped";
    c["reason"] = r.problems.front();
    return c;
  }
  if (shadow) {
    measures_json(c, r, {"on_A", "on_P", "on_R", "on_polar_plane", "on_generators", "R_on_polar_plane", "as_matrices"},
                  {{"on_A", "A"}, {"on_P", "P"}, {"on_R", "R"}});
    c["R_on_second_plane"] = number_or_null(r.second_plane_error.value_or(0));
    if (exact) c["proved_exactly"] = r.proved_exactly;
    c["consistent_with_precision"] = r.consistent_with_precision;
    c["rounding_tolerance"] = r.rounding_tolerance;
    c["kappa"] = r.kappa;
    c["item_status"] = r.item_status;
    if (v.inaccurate) c["flags"] = json::array({"inaccurate"});
    if (v.origin) c["origin"] = origin_json(*v.origin);
    std::string notes;  // every remark, one key
    for (const std::string& n : r.notes) notes += (notes.empty() ? "" : "; ") + n;
    if (!notes.empty()) c["note"] = notes;
  } else {
    measures_json(c, r, {"on_B"}, {{"on_B", "B"}});
    if (exact) c["proved_exactly"] = r.proved_exactly;
    c["consistent_with_precision"] = r.consistent_with_precision;
    c["rounding_tolerance"] = r.rounding_tolerance;
    c["M_error"] = r.M_error.value_or(0);
    if (v.origin) c["origin"] = origin_json(*v.origin);
    c["kappa"] = r.kappa;
    c["item_status"] = r.item_status;
    if (v.inaccurate) c["flags"] = json::array({"inaccurate"});
  }
  if (r.certified)  // the bound over every point of the geometry, not only the samples
    c["certified"] = {{"results", r.certified_for},
                      {"geometric_error_bound", number_or_null(r.certified->upper)},
                      {"geometric_error_attained", r.certified->attained},
                      {"boxes", r.certified->boxes}};
  verdict_json(c, r);
  return c;
}

}  // namespace

json verify_document(const Scene& sc, const VerifyReport& report) {
  const bool exact = report.proof();
  json doc;
  doc["format"] = "qverify-verify/1";
  doc["scene"] = sc.name;
  doc["precision"] = report.precision.name();
  doc["method"] = method_name(report.method);
  doc["samples"] = report.options.samples;
  doc["seed"] = report.options.seed;
  doc["source"] = report.source;
  doc["accuracy"] = exact ? 0.0 : report.options.accuracy;
  doc["tolerance_rule"] =
      exact ? "exact: every residual must be exactly zero (a proof)"
            : "pass: the geometric error of every checked result (geometric_error: largest distance of exact points "
              "of the terminator from P, R and the polar plane, or of A reflected from B: first-order, |x^T Q x| / "
              "|grad|, or second-order, sqrt(|x^T Q x| / kappa), where smaller; in the result's frame, divided by the "
              "object size: the largest distance of the points from A's centre) is at most the accuracy target; the "
              "results' shapes too, at the same target (on_generators: P on exact points of its generator lines, the "
              "cone from L; R_on_polar_plane and R_on_second_plane: R the plane pair of the polar plane and h), signs "
              "and M against references computed here from A, L and the mirror; and where certified, eval's certified "
              "bound of the geometric error over every point of the terminator or of A reflected (certified.results; "
              "near a point where the reference's gradient vanishes, a cone's apex or where R's planes cross, of the "
              "Euclidean distance, by second order) is at most the target. "
              "consistent_with_precision (information only): every relative residual "
              "|x^T Q x| / (|Q|_F |x|^2) within 64 eps kappa, kappa the rounding amplification of the formulas";
  json checks = json::array();
  for (const VerifyCheck& v : report.checks) checks.push_back(check_json(v, exact));
  doc["checks"] = checks;
  doc["passed"] = report.passed;
  doc["failed"] = report.failed;
  doc["skipped"] = report.skipped;
  doc["left_out"] = skipped_json(skipped_pairs(sc));
  if (!report.notes.empty()) doc["notes"] = report.notes;
  return doc;
}

std::string verify_text(const Scene& sc, const VerifyReport& report) {
  const bool exact = report.proof();
  const double target = exact ? 0.0 : report.options.accuracy;
  std::string out = fmt::format(
      "scene      {}\nprecision  {}   method {}   source {}\nsamples    {} per item, seed {}   accuracy target {}\n\n",
      sc.name, report.precision.name(), method_name(report.method), report.source, report.options.samples,
      report.options.seed, exact ? std::string("0 (exact proof)") : fmt::format("{:.3g}", target));
  out += fmt::format("{:<11} {:<10} {:<10} {:<8} {:>6} {:>11} {:>11} {:>11} {:>9}\n", "kind", "quadric", "with", "status",
                     "points", "geo. error", "obj. size", "proved", "rounding");
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.2e}", v) : std::string("inf"); };
  for (const VerifyCheck& v : report.checks) {
    const CheckReport* r = v.report && !v.report->skipped ? &*v.report : nullptr;  // measured
    out += fmt::format("{:<11} {:<10} {:<10} {:<8} {:>6} {:>11} {:>11} {:>11} {:>9}\n", v.kind, v.quadric, v.other,
                       v.status(), r ? r->points : 0, r ? num(r->geometric_error) : "-", r ? num(r->object_size) : "-",
                       r && exact ? std::to_string(r->proved_exactly) : "-",
                       !r ? "-" : r->consistent_with_precision ? "as good" : "worse");
    const std::string reason = !v.report ? v.missing : v.report->skipped ? v.report->problems.front() : problems_text(*r);
    if (!reason.empty()) out += fmt::format("            {}\n", reason);
  }
  out += fmt::format("\npass = geometric error <= accuracy target{}; 'rounding' says whether the residuals are as small as "
                     "this precision can make them (information only)\n",
                     exact ? " (exact: every residual exactly zero)" : "");
  out += fmt::format("\n{} passed, {} failed, {} skipped\n", report.passed, report.failed, report.skipped);
  return out;
}

}  // namespace qverify
