#include <qverify/report/eval_document.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace qverify {
namespace {

using json = nlohmann::ordered_json;

/// error_bound of an item (or null, with the reason in `reason`), and
/// `certified_for`: the results bounded over every point of their geometry.
void accuracy_json(json& j, const ItemAccuracy& acc) {
  j["error_bound"] = acc.bound ? json(*acc.bound) : json(nullptr);
  j["certified_for"] = acc.certified;
  if (!acc.reason.empty()) j["reason"] = acc.reason;
}

/// One item (docs/json-documents.md `shadows[]`, `reflections[]`). The
/// adaptive mode's items carry `certified` (the stage) before their accuracy.
json item_json(const EvalItem& it, bool shadow) {
  json j;
  j["quadric"] = it.quadric;
  j[shadow ? "light" : "mirror"] = it.other;
  j["status"] = it.status;
  if (it.origin) j["origin"] = origin_json(*it.origin);
  if (it.escalated) j["escalated"] = it.escalated;
  for (const auto& [name, m] : it.results) j[name] = matrix_json(m);
  j["flags"] = it.flags;
  if (it.accuracy && !it.certified) accuracy_json(j, *it.accuracy);
  if (it.direct_fallback) j["fallback"] = "direct formulas (the paper's frame does not exist for this light)";
  if (!it.paper.empty()) {
    json p;
    for (const auto& [name, m] : it.paper) p[name] = matrix_json(m);
    j["paper"] = p;
  }
  if (it.certified) {
    j["certified"] = {{"by", it.certified->by}, {"relative_error_bound", it.certified->relative_error_bound}};
    if (it.accuracy) accuracy_json(j, *it.accuracy);
  }
  return j;
}

/// A number in a text table: text unquoted, anything else as in JSON.
std::string cell(const Number& x) {
  if (const auto* s = std::get_if<std::string>(&x)) return *s;
  return number_json(x).dump();
}

std::string matrix_text(const std::string& name, const NumberMatrix& m) {
  std::string out;
  if (m.cols == 1) {
    std::string row;
    for (const Number& x : m.entries) row += fmt::format(" {:>14}", cell(x));
    return fmt::format("    {:<12}[{} ]\n", name, row);
  }
  for (int i = 0; i < m.rows; ++i) {
    std::string row;
    for (int j = 0; j < m.cols; ++j) row += fmt::format(" {:>14}", cell(m(i, j)));
    out += fmt::format("    {:<12}[{} ]\n", i == 0 ? name : "", row);
  }
  return out;
}

/// The item's error bound, and in words whether it may miss the accuracy target.
std::string accuracy_text(const EvalItem& it, double target) {
  if (!it.accuracy) return "";
  const ItemAccuracy& acc = *it.accuracy;
  const bool inaccurate = std::find(it.flags.begin(), it.flags.end(), "inaccurate") != it.flags.end();
  if (!acc.bound)
    return fmt::format("    error bound: none ({}){}\n", acc.reason,
                       inaccurate ? "; INACCURATE: the result may be off by more than the accuracy target" : "");
  if (inaccurate)
    return fmt::format("    INACCURATE: error bound {:.3g} of the object size exceeds the accuracy target {:.3g}\n",
                       *acc.bound, target);
  return fmt::format("    accurate: error bound {:.3g} of the object size (target {:.3g})\n", *acc.bound, target);
}

/// Why a pair is in the `skipped` list.
const char* skipped_reason(const SkippedPair& p) {
  return p.shadow ? "not requested (requests.shadows)" : "not requested (requests.reflections)";
}

}  // namespace

json number_json(const Number& x) {
  return std::visit(
      [](const auto& v) -> json {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::monostate>) return nullptr;
        else if constexpr (std::is_same_v<V, Enclosure>) return {{"lo", v.lo}, {"hi", v.hi}};
        else return v;  // nlohmann writes a double's shortest round-trip text
      },
      x);
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json matrix_json(const NumberMatrix& m) {
  json out = json::array();
  if (m.cols == 1) {
    for (const Number& x : m.entries) out.push_back(number_json(x));
    return out;
  }
  for (int i = 0; i < m.rows; ++i) {
    json row = json::array();
    for (int j = 0; j < m.cols; ++j) row.push_back(number_json(m(i, j)));
    out.push_back(std::move(row));
  }
  return out;
}

json origin_json(const std::array<double, 3>& o) { return {o[0], o[1], o[2]}; }

json origin_json(const Vec3<Rational>& o) {
  return origin_json(std::array<double, 3>{o(0).convert_to<double>(), o(1).convert_to<double>(), o(2).convert_to<double>()});
}

json skipped_json(const std::vector<SkippedPair>& pairs) {
  json out = json::array();
  for (const SkippedPair& p : pairs)
    out.push_back({{"quadric", p.quadric},
                   {p.shadow ? "light" : "mirror", p.other},
                   {"reason", skipped_reason(p)}});
  return out;
}

json eval_json(const EvalReport& r) {
  json doc;
  doc["format"] = "qverify-eval/1";
  doc["scene"] = r.scene;
  doc["precision"] = r.precision.name();
  doc["method"] = method_name(r.method);
  doc["frame"] = r.frame == Frame::local ? "local" : "world";
  if (r.working_bits) doc["working_bits"] = *r.working_bits;
  if (r.precision.kind == Precision::Kind::interval)
    doc["certified"] = "every entry is an enclosure {lo, hi} of the exact result of the same formula; statuses "
                       "decided in exact arithmetic";
  if (r.adaptive) {
    json by_stage;  // null when there is no item
    for (const auto& [stage, n] : r.adaptive->items_by_stage) by_stage[stage] = n;
    doc["adaptive"] = {{"tolerance", r.adaptive->tolerance},
                       {"ladder", "double -> interval -> mpfr (MPFI intervals, 256 bits) -> exact"},
                       {"rule", "an item is certified when every output entry is within tolerance x (largest |entry|) "
                                "of the exact result of the same formula, for every point of a certified enclosure of "
                                "that result: the double result (against the interval enclosure), else the interval "
                                "midpoints, else the MPFI midpoints rounded to double, else the exact result rounded "
                                "to double; relative_error_bound is the certified bound"},
                       {"items_by_stage", by_stage}};
  }
  doc["accuracy"] = r.accuracy.target;
  doc["error_bound_rule"] = error_bound_rule(r.accuracy);
  doc["shadows"] = json::array();
  for (const EvalItem& it : r.shadows) doc["shadows"].push_back(item_json(it, true));
  doc["reflections"] = json::array();
  for (const EvalItem& it : r.reflections) doc["reflections"].push_back(item_json(it, false));
  doc["skipped"] = skipped_json(r.skipped);
  if (r.inputs_rounded) doc["inputs_rounded"] = *r.inputs_rounded;
  return doc;
}

std::string eval_text(const EvalReport& r) {
  std::string out = fmt::format("scene      {}\nprecision  {}   method {}\n", r.scene, r.precision.name(),
                                method_name(r.method));
  for (const EvalItem& s : r.shadows) {
    out += fmt::format("\nshadow  {} lit by {}: {}\n", s.quadric, s.other, s.status);
    for (const auto& [name, m] : s.results) out += matrix_text(name, m);
    out += accuracy_text(s, r.accuracy.target);
  }
  for (const EvalItem& b : r.reflections) {
    out += fmt::format("\nreflection  {} in {}: {}\n", b.quadric, b.other, b.status);
    for (const auto& [name, m] : b.results) out += matrix_text(name, m);
    out += accuracy_text(b, r.accuracy.target);
  }
  if (!r.skipped.empty()) {
    out += fmt::format("\nleft out ({}):\n", r.skipped.size());
    for (const SkippedPair& k : r.skipped)
      out += fmt::format("    {} / {}: {}\n", k.quadric, k.other, skipped_reason(k));
  }
  if (r.inputs_rounded && !r.inputs_rounded->empty())
    out += fmt::format("\n{} input number(s) are not exactly representable in {} and were rounded once to nearest.\n",
                       r.inputs_rounded->size(), r.precision.name());
  if (r.adaptive) {
    std::string stages;
    for (const auto& [stage, n] : r.adaptive->items_by_stage) stages += fmt::format("{}{} by {}", stages.empty() ? "" : ", ", n, stage);
    out += fmt::format("\nadaptive: every item certified within {:.3g} of the exact result of its formula ({})\n",
                       r.adaptive->tolerance, stages.empty() ? "no item" : stages);
  }
  return out;
}

}  // namespace qverify
