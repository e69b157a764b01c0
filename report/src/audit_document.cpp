#include <qverify/report/audit_document.hpp>
#include <qverify/report/candidate_section.hpp>
#include <qverify/report/eval_document.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace qverify {
namespace {

using json = nlohmann::ordered_json;

/// max_rel_error, median_rel_error, correct_bits (= -log2(error), at most the significand's bits of a floating
/// precision, `bits`, which an exact zero gets too; null for an exact zero in exact arithmetic or without a
/// precision) and exact_match.
void error_fields(json& r, const ErrorStats& stats, std::optional<unsigned> bits = std::nullopt) {
  r["max_rel_error"] = number_or_null(stats.max);
  r["median_rel_error"] = number_or_null(stats.median);
  const double b = bits ? static_cast<double>(*bits) : std::numeric_limits<double>::infinity();
  r["correct_bits"] = stats.max > 0 ? number_or_null(std::min(-std::log2(stats.max), b)) : bits ? json(*bits) : json(nullptr);
  if (stats.max == 0) r["exact_match"] = true;
}

/// A ladder row: its timing and errors, then what timed_results reports.
json ladder_json(const AuditRow& row, std::size_t n_items) {
  const LadderFacts& f = *row.ladder;
  json r;
  r["precision"] = row.precision;
  r["method"] = row.method;
  r["ns_per_item"] = row.ns_per_item;
  const std::optional<Precision> p = parse_precision(row.precision);
  error_fields(r, row.stats, p ? p->significand_bits() : std::nullopt);
  r["items"] = n_items;
  r["inaccurate_items"] = f.inaccurate_items;
  if (p && p->kind != Precision::Kind::exact) r["missed_flags"] = f.missed_flags;
  r["reps_per_batch"] = f.reps_per_batch;
  r["batches"] = f.batches;
  r["inputs_rounded"] = f.inputs_rounded;
  if (f.working_bits) r["working_bits"] = *f.working_bits;
  return r;
}

/// Why the candidate's reproducer was written: its call failed, an item beyond the accuracy target, or
/// (within it) a failed check (a status word, sign, M or symmetry).
const char* reproducer_status(const CandidateFacts& c, double accuracy) {
  return !c.ok ? "candidate-failed" : !(c.max_geometric_error <= accuracy) ? "beyond-accuracy" : "failed-checks";
}

/// The candidate's row: who it is and its status, its time per call and errors, then the ladder's fields
/// it has no value for (null or 1), whether it missed the target and its reproducer's scene.
json candidate_row_json(const AuditRow& row, std::size_t n_items, double a_accuracy) {
  const CandidateFacts& c = *row.candidate;
  json r;
  r["precision"] = row.precision;
  r["method"] = row.method;
  r["source"] = "candidate";
  r["run"] = c.name;
  r["status"] = c.status;
  if (c.ok) {
    r["claimed_precision"] = c.claimed_precision;
    r["claimed_method"] = c.claimed_method;
    r["checks_passed"] = c.checks_passed;
    r["checks_failed"] = c.checks_failed;
    r["problems"] = c.problems;
  } else {
    r["error"] = c.error;
  }
  r["ns_per_item"] = row.ns_per_item;
  r["seconds_per_call"] = c.seconds;
  const std::optional<Precision> claimed = c.ok ? parse_precision(c.claimed_precision) : std::nullopt;
  error_fields(r, row.stats, claimed ? claimed->significand_bits() : std::nullopt);
  r["max_geometric_error"] = number_or_null(c.max_geometric_error);
  r["items"] = n_items;
  r["inaccurate_items"] = nullptr;
  r["reps_per_batch"] = 1;
  r["batches"] = 1;
  r["inputs_rounded"] = nullptr;
  r["beyond_accuracy"] = c.ok && !(c.max_geometric_error <= a_accuracy);
  if (c.reproducer) r["reproducer"] = c.reproducer->scene;
  return r;
}

/// Every item with its error in every row, and the candidate's geometric error.
json items_json(const AuditReport& a) {
  json items = json::array();
  for (std::size_t k = 0; k < a.items.size(); ++k) {
    const AuditItem& it = a.items[k];
    json j{{"kind", it.shadow ? "shadow" : "reflection"},
           {"quadric", it.quadric},
           {it.shadow ? "light" : "mirror", it.other},
           {"exact_status", it.exact_status}};
    json errs;
    for (const AuditRow& r : a.rows) errs[r.key()] = number_or_null(r.errors[k]);
    j["errors"] = errs;
    if (it.candidate_geometric_error && a.options.candidate)
      j["geometric_errors"] = {{a.options.candidate->name, number_or_null(*it.candidate_geometric_error)}};
    items.push_back(j);
  }
  return items;
}

/// The candidate's row (the last one, when a candidate was given).
const AuditRow* candidate_row(const AuditReport& a) {
  return !a.rows.empty() && a.rows.back().candidate ? &a.rows.back() : nullptr;
}

/// The document's "candidate" section: the candidate, its rule, its status and its reproducer.
json candidate_json(const AuditReport& a) {
  const AuditOptions& o = a.options;
  json c = candidate_head_json(*o.candidate, o.accuracy);
  c["rule"] = "the candidate is called once on the scene and must return a qverify-eval/1 document with every "
              "requested item; its row has the matrix errors of the ladder and ns_per_item = the wall time of the "
              "call (process start included) / items; each item is checked as verify --candidate checks it (" +
              std::to_string(o.samples) + " exact points, seed 1): geometric_errors; a failed call, a failed "
              "check or a geometric error beyond accuracy writes the scene as a reproducer";
  const AuditRow* row = candidate_row(a);
  c["status"] = row ? row->candidate->status : "";
  json reproducers = json::array();
  if (row && row->candidate->reproducer) {
    json rep = reproducer_json(*row->candidate->reproducer);
    rep.erase("param");  // one call on the scene: no parameter
    rep["status"] = reproducer_status(*row->candidate, o.accuracy);
    reproducers.push_back(rep);
  }
  c["failures_dir"] = reproducers.empty() ? json(nullptr) : json("failures");
  c["reproducers"] = reproducers;
  return c;
}

}  // namespace

json audit_json(const AuditReport& a) {
  const std::size_t n_items = a.items.size();
  json rows = json::array();
  for (const AuditRow& r : a.rows) rows.push_back(r.candidate ? candidate_row_json(r, n_items, a.options.accuracy) : ladder_json(r, n_items));
  json doc;
  doc["format"] = "qverify-audit/1";
  doc["scene"] = a.scene;
  doc["reference"] = "exact";
  doc["scale_removal"] =
      "each result X is compared with the exact Y as a projective object: max_i |X_i Y_p - Y_i X_p| / (|X|_max |Y_p|), "
      "p the largest entry of Y (cross-multiplication, no division by an entry; zero exactly when X = lambda Y). P, the "
      "polar plane and B must have the contract's positive factor (a sign error counts as 2); R is free up to any "
      "non-zero factor; M is compared entry by entry (relative to max(1, |M|_max)). An item's error is the largest of "
      "its matrices'; errors are computed exactly from the results converted to rationals.";
  doc["timing"] = "ns_per_item: median over " + std::to_string(a.options.batches) +
                  " batches of the evaluation of all requested items from inputs already in the precision (each batch "
                  "repeated until it lasts >= " +
                  std::to_string(static_cast<int>(a.options.batch_seconds * 1000)) +
                  " ms; results kept behind a compiler barrier), single thread";
  doc["flag_check"] =
      "every floating row's items are checked as verify checks them (" + std::to_string(a.options.samples) +
      " exact points, seed 1): an item whose geometric error there is finite and exceeds eval's accuracy target 1e-9 "
      "while eval did not flag it inaccurate is listed in the row's missed_flags (a sample bounds the error from below: "
      "a flag proved missing; an infinite error, a point off the result where its gradient vanishes, is no distance), "
      "and the audit exits 1";
  doc["rows"] = rows;
  doc["pareto"] = a.pareto;
  doc["items"] = items_json(a);
  doc["skipped"] = skipped_json(a.skipped);
  if (a.options.candidate) doc["candidate"] = candidate_json(a);
  return doc;
}

std::string audit_text(const AuditReport& a, const std::string& dir) {
  std::string out = fmt::format("precision audit of {} (reference: exact)\n\n", a.scene);
  out += fmt::format("{:<12} {:<9} {:>12} {:>14} {:>14} {:>8} {:>11}  {}\n", "precision", "method", "ns/item",
                     "max rel.err", "median", "bits", "inaccurate", "pareto");
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.3g}", v) : std::string("-"); };
  for (const AuditRow& r : a.rows) {
    const double bits = -std::log2(r.stats.max);
    out += fmt::format("{:<12} {:<9} {:>12.1f} {:>14} {:>14} {:>8} {:>11}  {}\n", r.precision, r.method, r.ns_per_item,
                       num(r.stats.max), num(r.stats.median), r.stats.max == 0 ? std::string("exact") : num(bits),
                       r.ladder ? fmt::format("{}/{}", r.ladder->inaccurate_items, a.items.size()) : std::string("-"),
                       std::find(a.pareto.begin(), a.pareto.end(), r.key()) != a.pareto.end() ? "*" : "");
  }
  for (const AuditRow& r : a.rows)
    if (r.ladder && !r.ladder->missed_flags.empty()) {
      out += fmt::format("\nMISSED FLAG in {}: geometric error beyond 1e-9 without `inaccurate`:", r.key());
      for (const std::string& item : r.ladder->missed_flags) out += " " + item;
      out += "\n";
    }
  if (const AuditRow* row = candidate_row(a)) {
    const CandidateFacts& c = *row->candidate;
    out += fmt::format("\ncandidate {}: {}", c.name, c.status);
    if (!c.ok) out += fmt::format(" ({})", c.error);
    out += fmt::format("; {:.3f} s per call; largest geometric error {} (target {:.3g})\n", c.seconds,
                       num(c.max_geometric_error), a.options.accuracy);
    if (c.reproducer) out += fmt::format("reproducer: {}/{} ({})\n", dir, c.reproducer->scene, c.reproducer->reason);
  }
  out += fmt::format("\nwrote {0}/report.json, {0}/report.html, {0}/error-vs-time.svg\n", dir);
  return out;
}

}  // namespace qverify
