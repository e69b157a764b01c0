#pragma once
/// \file eval.hpp
/// Demand-driven evaluation of a scene in one scalar type: only the requested
/// (quadric, light) and (quadric, mirror) pairs are computed; a mirror matrix
/// is built only when some reflection needs it.

#include <qverify/verify/precision.hpp>
#include <qverify/verify/scalar_json.hpp>
#include <qverify/verify/scene.hpp>

#include <nlohmann/json.hpp>

#include <optional>

namespace qverify {

template <class S> struct ShadowItem {
  Pair pair;
  ShadowResult<S> result;
};
template <class S> struct ReflectionItem {
  Pair pair;
  Mat4<S> M;
  ReflectionResult<S> result;
};

template <class S> struct Evaluation {
  TypedScene<S> scene;
  std::vector<ShadowItem<S>> shadows;
  std::vector<ReflectionItem<S>> reflections;
};

/// Computes every requested item of `sc` from its typed scene by `method`
/// (the timed part of an audit: the inputs are already in S).
template <class S> void evaluate_items(const Scene& sc, Method method, Evaluation<S>& ev) {
  ev.shadows.clear();
  ev.reflections.clear();
  for (const Pair& p : sc.shadows)
    ev.shadows.push_back({p, shadow<S>(ev.scene.A[p.quadric], ev.scene.L[p.other], method)});
  std::vector<std::optional<Mat4<S>>> mirrors(sc.mirrors.size());
  for (const Pair& p : sc.reflections) {
    auto& M = mirrors[p.other];
    if (!M) M = mirror_matrix<S>(ev.scene.planes[p.other]);
    ev.reflections.push_back({p, *M, reflection<S>(ev.scene.A[p.quadric], *M, method)});
  }
}

/// Computes every requested item of `sc` in scalar type S by `method`.
template <class S> Evaluation<S> evaluate(const Scene& sc, Method method) {
  Evaluation<S> ev;
  ev.scene = typed_scene<S>(sc);
  evaluate_items<S>(sc, method, ev);
  return ev;
}

inline const char* method_name(Method m) { return m == Method::paper ? "paper" : "direct"; }

/// JSON of one shadow item (cli.md `shadows[]`), plus extra keys: `flags`
/// (every special case that applies), `fallback` and the paper route's
/// intermediates (`paper`: M, T, C, D, S).
template <class S> nlohmann::ordered_json shadow_json(const Scene& sc, const ShadowItem<S>& it) {
  nlohmann::ordered_json j;
  j["quadric"] = sc.quadrics[it.pair.quadric].id;
  j["light"] = sc.lights[it.pair.other].id;
  const ShadowResult<S>& r = it.result;
  bool finite = all_finite(r.P) && all_finite(r.polar_plane) && all_finite(r.R);
  j["status"] = finite ? r.status() : "non-finite";
  j["P"] = matrix_json(r.P);
  j["polar_plane"] = matrix_json(r.polar_plane);
  j["R"] = matrix_json(r.R);
  nlohmann::ordered_json flags = nlohmann::ordered_json::array();
  for (ShadowFlag f : kFlagOrder)
    if (r.has(f)) flags.push_back(flag_word(f));
  if (!finite) flags.push_back("non-finite");
  j["flags"] = flags;
  if (r.direct_fallback) j["fallback"] = "direct formulas (the paper's frame does not exist for this light)";
  if (r.has_paper) {
    j["paper"] = {{"M", matrix_json(r.paper.frame.M)},
                  {"T", matrix_json(r.paper.frame.T)},
                  {"C", matrix_json(r.paper.C)},
                  {"D", matrix_json(r.paper.D)},
                  {"S", matrix_json(r.paper.S_plane)}};
  }
  return j;
}

template <class S> nlohmann::ordered_json reflection_json(const Scene& sc, const ReflectionItem<S>& it) {
  nlohmann::ordered_json j;
  j["quadric"] = sc.quadrics[it.pair.quadric].id;
  j["mirror"] = sc.mirrors[it.pair.other].id;
  const bool finite = all_finite(it.M) && all_finite(it.result.B);
  j["status"] = finite ? it.result.status() : "non-finite";
  j["M"] = matrix_json(it.M);
  j["B"] = matrix_json(it.result.B);
  return j;
}

/// The `skipped` list: every pair that was not requested, with the reason.
nlohmann::ordered_json skipped_json(const Scene& sc);

/// The whole `qverify-eval/1` document.
template <class S>
nlohmann::ordered_json eval_document(const Scene& sc, const Precision& prec, Method method) {
  const Evaluation<S> ev = evaluate<S>(sc, method);
  nlohmann::ordered_json doc;
  doc["format"] = "qverify-eval/1";
  doc["scene"] = sc.name;
  doc["precision"] = prec.name();
  doc["method"] = method_name(method);
  if (prec.kind == Precision::Kind::mpfr) doc["working_bits"] = mpfr_working_bits();
  doc["shadows"] = nlohmann::ordered_json::array();
  for (const auto& it : ev.shadows) doc["shadows"].push_back(shadow_json(sc, it));
  doc["reflections"] = nlohmann::ordered_json::array();
  for (const auto& it : ev.reflections) doc["reflections"].push_back(reflection_json(sc, it));
  doc["skipped"] = skipped_json(sc);
  doc["inputs_rounded"] = ev.scene.rounded_inputs;
  return doc;
}

/// eval_document for a run-time precision (one explicit instantiation per
/// scalar type, each in its own translation unit).
nlohmann::ordered_json eval_document(const Scene& sc, const Precision& prec, Method method);

}  // namespace qverify
