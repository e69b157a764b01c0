#pragma once
/// \file eval_report.hpp
/// What `qverify eval` says about a scene, as a typed value: every requested
/// item's results with their numbers as the documents carry them (number.hpp),
/// its status and flags, its error bound, and what was left out. It is the same
/// for every precision (the scalar type is erased into Number), so the command
/// line, the Python module and the adaptive mode share it;
/// report/eval_document.hpp writes it as the `qverify-eval/1` document and as
/// text.

#include <qverify/eval/eval.hpp>
#include <qverify/eval/number.hpp>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace qverify {

/// One named result of an item ("P", "polar_plane", "R"; "M", "B"; the paper's "M", "T", "C", "D", "S").
using NamedMatrix = std::pair<std::string, NumberMatrix>;

/// How the adaptive mode (`eval --tolerance`) certified an item: the stage of
/// its ladder whose double values are within the tolerance of the exact result
/// of the same formula, and the certified relative bound.
struct StageCertificate {
  std::string by;  ///< "double", "interval", "mpfr" or "exact"
  double relative_error_bound = 0;
};

/// One requested item: a shadow (quadric, light) or a reflection (quadric, mirror).
struct EvalItem {
  std::string quadric, other;  ///< the ids of the quadric and of the light or mirror
  std::string status;          ///< the status word of the exact inputs (also when the result overflowed: flag "non-finite")
  std::optional<std::array<double, 3>> origin;  ///< the results' frame (local coordinates x - origin)
  const char* escalated = nullptr;              ///< the wider type the item was recomputed in, if any
  std::vector<NamedMatrix> results;             ///< P, polar_plane, R (shadow) or M, B (reflection)
  std::vector<std::string> flags;               ///< every special case that applies, then "inaccurate"
  std::optional<ItemAccuracy> accuracy;         ///< error_bound and what it is certified for
  bool direct_fallback = false;                 ///< the paper's frame does not exist for this light
  std::vector<NamedMatrix> paper;               ///< the paper route's intermediates M, T, C, D, S
  std::optional<StageCertificate> certified;    ///< adaptive mode only
};

/// A pair of the scene that was not requested.
struct SkippedPair {
  bool shadow = true;  ///< a (quadric, light) pair, else a (quadric, mirror) pair
  std::string quadric, other;
};

/// The adaptive mode's facts: its tolerance and how many items each stage certified.
struct AdaptiveFacts {
  double tolerance = 0;
  std::map<std::string, int> items_by_stage;
};

/// A whole evaluation of a scene.
struct EvalReport {
  std::string scene;  ///< the scene's name
  Precision precision;
  Method method = Method::direct;
  Frame frame = Frame::world;
  std::optional<unsigned> working_bits;  ///< the MPFR working precision (mpfr only)
  std::optional<AdaptiveFacts> adaptive;  ///< set by `eval --tolerance`
  AccuracyOptions accuracy;
  std::vector<EvalItem> shadows, reflections;
  std::vector<SkippedPair> skipped;
  /// The inputs not exactly representable in the precision (rounded once to nearest), by scene path;
  /// nullopt where the results are not computed from rounded inputs (the adaptive mode).
  std::optional<std::vector<std::string>> inputs_rounded;
};

/// The pairs of `sc` that were not requested.
std::vector<SkippedPair> skipped_pairs(const Scene& sc);

/// A shadow item of an evaluation in S (acc: its accuracy, if assessed).
template <class S> EvalItem shadow_item(const Scene& sc, const ShadowItem<S>& it, const ItemAccuracy* acc = nullptr) {
  EvalItem e;
  e.quadric = sc.quadrics[it.pair.quadric].id;
  e.other = sc.lights[it.pair.other].id;
  const ShadowResult<S>& r = it.result;
  const bool finite = all_finite(r.P) && all_finite(r.polar_plane) && all_finite(r.R);
  e.status = r.status();  // a predicate of the exact inputs, whatever the precision made of the result
  if (it.origin)
    e.origin = {(*it.origin)(0).template convert_to<double>(), (*it.origin)(1).template convert_to<double>(),
                (*it.origin)(2).template convert_to<double>()};
  e.escalated = it.escalated;
  e.results = {{"P", numbers_of(r.P)}, {"polar_plane", numbers_of(r.polar_plane)}, {"R", numbers_of(r.R)}};
  for (ShadowFlag f : kFlagOrder)
    if (r.has(f)) e.flags.emplace_back(flag_word(f));
  if (!finite) e.flags.emplace_back("non-finite");
  if (acc) {
    if (acc->inaccurate) e.flags.emplace_back("inaccurate");
    e.accuracy = *acc;
  }
  e.direct_fallback = r.direct_fallback;
  if (r.has_paper)
    e.paper = {{"M", numbers_of(r.paper.frame.M)},
               {"T", numbers_of(r.paper.frame.T)},
               {"C", numbers_of(r.paper.C)},
               {"D", numbers_of(r.paper.D)},
               {"S", numbers_of(r.paper.S_plane)}};
  return e;
}

/// A reflection item of an evaluation in S.
template <class S>
EvalItem reflection_item(const Scene& sc, const ReflectionItem<S>& it, const ItemAccuracy* acc = nullptr) {
  EvalItem e;
  e.quadric = sc.quadrics[it.pair.quadric].id;
  e.other = sc.mirrors[it.pair.other].id;
  const bool finite = all_finite(it.M) && all_finite(it.result.B);
  e.status = it.result.status();
  if (it.origin)
    e.origin = {(*it.origin)(0).template convert_to<double>(), (*it.origin)(1).template convert_to<double>(),
                (*it.origin)(2).template convert_to<double>()};
  e.escalated = it.escalated;
  e.results = {{"M", numbers_of(it.M)}, {"B", numbers_of(it.result.B)}};
  if (it.result.degenerate) e.flags.emplace_back("degenerate-quadric");
  if (!finite) e.flags.emplace_back("non-finite");
  if (acc) {
    if (acc->inaccurate) e.flags.emplace_back("inaccurate");
    e.accuracy = *acc;
  }
  return e;
}

/// The scene evaluated in S as `qverify eval` does: the items, their exact
/// statuses and their error bounds.
template <class S>
EvalReport eval_report(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame,
                       const AccuracyOptions& accuracy) {
  const Evaluation<S> ev = evaluate_checked<S>(sc, method, frame, accuracy);
  EvalReport rep;
  rep.scene = sc.name;
  rep.precision = prec;
  rep.method = method;
  rep.frame = ev.frame;
  if (prec.kind == Precision::Kind::mpfr) rep.working_bits = mpfr_working_bits();
  rep.accuracy = accuracy;
  for (std::size_t k = 0; k < ev.shadows.size(); ++k)
    rep.shadows.push_back(shadow_item(sc, ev.shadows[k], &ev.shadow_accuracy[k]));
  for (std::size_t k = 0; k < ev.reflections.size(); ++k)
    rep.reflections.push_back(reflection_item(sc, ev.reflections[k], &ev.reflection_accuracy[k]));
  rep.skipped = skipped_pairs(sc);
  rep.inputs_rounded = ev.scene.rounded_inputs;
  return rep;
}

/// eval_report for a run-time precision (one explicit instantiation per scalar
/// type, each in its own translation unit).
EvalReport eval_report(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame = std::nullopt,
                       const AccuracyOptions& accuracy = {});

}  // namespace qverify
