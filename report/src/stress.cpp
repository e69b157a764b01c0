#include <qverify/report/candidate_section.hpp>
#include <qverify/report/stress.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

namespace qverify {
namespace {

using json = nlohmann::ordered_json;

/// A measured error: null where the run gave no finite item.
json measured(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

/// One run at a point: who ran it and how, its status, its errors, eval's flag; the candidate's call also
/// with its time, whether it missed the accuracy target and its reproducer.
json run_json(const StressRun& r) {
  json j{{"run", r.run},
         {"source", r.candidate ? "candidate" : "qverify"},
         {"precision", r.precision ? json(r.precision->name()) : json(nullptr)},
         {"method", r.method ? json(method_name(*r.method)) : json(nullptr)}};
  if (!r.candidate && r.returned) j["error_bound"] = optional_number(r.error_bound);
  if (r.frame) j["frame"] = *r.frame == Frame::local ? "local" : "world";
  j["status"] = r.status;
  if (r.failed_call) j["error"] = r.error;
  if (r.candidate) j["seconds"] = r.seconds;
  j["matrix_error"] = measured(r.matrix_error);
  j["geometric_error"] = measured(r.geometric_error);
  j["item_geometric_error"] = measured(r.item_geometric_error);
  j["flags"] = r.inaccurate ? json::array({"inaccurate"}) : json::array();
  if (r.candidate) j["beyond_accuracy"] = r.beyond_accuracy, j["problems"] = r.problems;
  if (r.reproducer) j["reproducer"] = *r.reproducer;
  return j;
}

json point_json(const StressPoint& p) {
  json runs = json::array();
  for (const StressRun& r : p.runs) runs.push_back(run_json(r));
  return {{"param", p.param},
          {"exact_status", p.exact_status},
          {"points", p.sample_points},
          {"kappa", p.kappa},
          {"predicted_double_error", p.predicted_double_error},
          {"rounded_exact_error", measured(p.rounded_exact_error)},
          {"target", p.target},
          {"default_meets_target", p.default_meets_target},
          {"runs", runs}};
}

json flagged_json(const std::vector<FlaggedRun>& runs) {
  json a = json::array();
  for (const FlaggedRun& r : runs)
    a.push_back({{"param", r.param}, {"run", r.run}, {"item_geometric_error", measured(r.item_geometric_error)}});
  return a;
}

/// A family's entry: what it sweeps, the target and the flag's self-check, its points, and per run its slopes
/// and breakdown; with a candidate, the candidate's summary.
json family_json(const StressFamilyResult& f) {
  json points = json::array();
  for (const StressPoint& p : f.points) points.push_back(point_json(p));
  json slopes, breakdown;
  slopes["predicted_double_error (eps * kappa)"] = optional_number(f.predicted_slope);
  for (const StressRunSummary& s : f.runs) {
    slopes[s.run] = {{"matrix_error", optional_number(s.matrix_slope)}, {"geometric_error", optional_number(s.geometric_slope)}};
    breakdown[s.run] = optional_number(s.breakdown);
  }
  json j{{"name", f.name},
         {"description", f.description},
         {"parameter", f.parameter},
         {"item", f.reflection ? "reflection B" : "shadow P"},
         {"geometric_target", "max(1e-9, 10 x rounded_exact_error): the default double path must be within 1e-9 "
                              "of the object's size, or within 10x of a correctly rounded matrix in its own frame"},
         {"default_meets_target", f.default_meets_target},
         {"flag_check",
          {{"rule", "every run whose item geometric error (P, polar plane and R, or B: the largest measured on "
                    "these exact points, seed 11, and the error eval found the item to reach) exceeds the accuracy "
                    "target 1e-9 carries the flag inaccurate (from eval's error bound); flagged_below lists flagged "
                    "runs known to reach less than 1e-11 (information: samples bound the true error only from "
                    "below)"},
           {"ok", f.flag_check.ok()},
           {"missed", flagged_json(f.flag_check.missed)},
           {"flagged_below", flagged_json(f.flag_check.flagged_below)}}},
         {"points", points},
         {"slopes", slopes},
         {"breakdown", breakdown}};
  if (f.candidate) {
    const StressCandidateFamily& c = *f.candidate;
    j["candidate"] = {{"name", c.name},
                      {"breakdown", optional_number(c.breakdown)},
                      {"breakdown_reason", c.breakdown_reason ? json(*c.breakdown_reason) : json(nullptr)},
                      {"failed_calls", c.failed_calls},
                      {"beyond_accuracy", c.beyond_accuracy},
                      {"failed_checks", c.failed_checks},
                      {"reproducers", c.failed_calls + c.beyond_accuracy + c.failed_checks}};
  }
  return j;
}

/// The median wall time of the candidate's calls (none without a call).
std::optional<double> median_seconds(std::vector<double> seconds) {
  if (seconds.empty()) return std::nullopt;
  std::sort(seconds.begin(), seconds.end());
  return seconds[seconds.size() / 2];
}

/// The document's "candidate" section: who it is, its rule, its totals and its reproducers.
json candidate_json(const StressCandidateSummary& c) {
  json j = candidate_head_json(c.candidate, c.accuracy);
  j["rule"] = "the candidate is given each point's scene (the file of its reproducer) and must return a qverify-eval/1 "
              "document with the family's item; its results are measured like every run (matrix and geometric error "
              "against exact on the same points); a point is a reproducer when the call failed (status "
              "candidate-failed, with error), the item's geometric error over all its results (P, polar plane and R, "
              "or B) exceeds accuracy (beyond-accuracy), or another of verify --candidate's checks of the item fails "
              "(failed-checks: a status word that is not the exact inputs', a wrong sign, an M that is not the "
              "mirror's, an asymmetric matrix; problems lists them); breakdown is the first such parameter value";
  j["calls"] = c.call_seconds.size();
  j["failed_calls"] = c.failed_calls;
  j["beyond_accuracy"] = c.beyond_accuracy;
  j["failed_checks"] = c.failed_checks;
  j["median_seconds_per_call"] = optional_number(median_seconds(c.call_seconds));
  j["failures_dir"] = c.reproducers.empty() ? json(nullptr) : json("failures");
  json reproducers = json::array();
  for (const StressReproducer& r : c.reproducers) {
    json e = reproducer_json(r.written);
    e["status"] = r.status;
    e["item_geometric_error"] = measured(r.item_geometric_error);
    reproducers.push_back(e);
  }
  j["reproducers"] = reproducers;
  return j;
}

/// "1.23e-04"; a measured error that is not finite (no item) is "-".
std::string sci(double v) { return fmt::format("{:.2e}", v); }
std::string sci_measured(double v) { return std::isfinite(v) ? sci(v) : "-"; }

}  // namespace

json stress_json(const StressReport& report) {
  json doc{{"format", "qverify-stress/1"},
           {"reference", "exact"},
           {"geometric_error", "max over exact sample points (terminator points for P, reflected points of A for B, "
                               "sampled in Q(sqrt d)) of the distance: first-order, |x^T Q x| / |grad|, or second-order, "
                               "sqrt(|x^T Q x| / kappa), where smaller, in the result's own frame, divided by the object's "
                               "size"},
           {"matrix_error", "projective error against the exact matrix (cross-multiplication, see qverify audit)"}};
  if (report.candidate) doc["candidate"] = candidate_json(*report.candidate);
  json families = json::array();
  for (const StressFamilyResult& f : report.families) families.push_back(family_json(f));
  doc["families"] = families;
  return doc;
}

std::string stress_text(const StressReport& report, const std::string& dir) {
  std::string out;
  auto put = std::back_inserter(out);
  for (const StressFamilyResult& f : report.families) {
    fmt::format_to(put, "\n{} ({}): geometric error of {} / object size; default double meets the target: {}\n", f.name,
                   f.parameter, f.reflection ? "reflection B" : "shadow P", f.default_meets_target ? "yes" : "NO");
    // one column per run, headed by its label's first word (at most 12 characters)
    fmt::format_to(put, "{:>10} {:>10} {:>10}", f.parameter, "eps*kappa", "rounded");
    if (!f.points.empty())
      for (const StressRun& r : f.points.front().runs) fmt::format_to(put, " {:>12}", r.run.substr(0, r.run.find(' ')).substr(0, 12));
    out += "\n";
    for (const StressPoint& p : f.points) {
      fmt::format_to(put, "{:>10} {:>10} {:>10}", sci(p.param), sci(p.predicted_double_error), sci_measured(p.rounded_exact_error));
      for (const StressRun& r : p.runs) fmt::format_to(put, " {:>12}", r.failed_call ? std::string("FAILED") : sci_measured(r.geometric_error));
      out += "\n";
    }
    if (f.candidate) {
      const StressCandidateFamily& c = *f.candidate;
      if (!c.breakdown)
        fmt::format_to(put, "candidate {}: within the target at every point\n", c.name);
      else
        fmt::format_to(put, "candidate {}: breaks at {} = {:.3g}: {}\n", c.name, f.parameter, *c.breakdown,
                       c.breakdown_reason.value_or(std::string()));
    }
  }
  if (report.candidate) {
    const StressCandidateSummary& c = *report.candidate;
    fmt::format_to(put, "\ncandidate {}: {} calls, {} failed, {} beyond the target {:.3g}, {} with a failed check; {} reproducer(s){}\n",
                   c.candidate.name, c.call_seconds.size(), c.failed_calls, c.beyond_accuracy, c.accuracy, c.failed_checks,
                   c.reproducers.size(), c.reproducers.empty() ? std::string() : " in " + dir + "/failures/");
  }
  fmt::format_to(put, "\nwrote {0}/report.json, {0}/report.html and one SVG per family\n", dir);
  return out;
}

json stress_families_json(const std::vector<StressFamily>& families) {
  json list = json::array();
  for (const StressFamily& f : families) list.push_back({{"name", f.name}, {"parameter", f.parameter}, {"description", f.description}});
  return {{"families", list}};
}

std::string stress_families_text(const std::vector<StressFamily>& families) {
  std::string out;
  for (const StressFamily& f : families) fmt::format_to(std::back_inserter(out), "{:<20} {}\n", f.name, f.description);
  return out;
}

}  // namespace qverify
