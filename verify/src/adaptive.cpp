#include <qverify/verify/adaptive.hpp>
#include <qverify/verify/verifier.hpp>

#include <cmath>
#include <stdexcept>
#include <map>
#include <optional>

namespace qverify {

using json = nlohmann::ordered_json;
using Q = Rational;

namespace {

/// Largest |entry| of an interval matrix (upper bounds).
template <class D> double interval_scale(const Eigen::MatrixBase<D>& m) {
  double s = 0;
  for (Eigen::Index i = 0; i < m.size(); ++i) s = std::max({s, std::abs(m(i).inf()), std::abs(m(i).sup())});
  return s;
}

/// Largest half-width of an interval matrix relative to its scale.
template <class D> double relative_halfwidth(const Eigen::MatrixBase<D>& m) {
  const double s = interval_scale(m);
  if (s == 0) return 0;
  double w = 0;
  for (Eigen::Index i = 0; i < m.size(); ++i) w = std::max(w, (m(i).sup() - m(i).inf()) / 2);
  return w / s;
}

/// Is every entry of x within the enclosure widened by tol * scale?
template <class DX, class DI> bool inside(const Eigen::MatrixBase<DX>& x, const Eigen::MatrixBase<DI>& enc, double tol) {
  const double slack = tol * interval_scale(enc);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double v = x(i);
    if (!(v >= enc(i).inf() - slack && v <= enc(i).sup() + slack)) return false;
  }
  return true;
}

template <class D> auto midpoints(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const Interval& x) { return (x.inf() + x.sup()) / 2; }).eval();
}

template <class D> auto rounded(const Eigen::MatrixBase<D>& m) {
  return m.unaryExpr([](const Q& x) {
             RoundingReport rep;
             return round_rational<double>(x, rep);
           })
      .eval();
}

}  // namespace

json adaptive_eval_document(const Scene& sc, Method method, double tol) {
  if (!(tol >= std::ldexp(1.0, -53))) throw std::invalid_argument("adaptive tolerance below 2^-53 cannot be certified in double");
  // Every stage in world coordinates and without rescaling, so that the stages are comparable.
  const Evaluation<double> d = evaluate<double>(sc, method, Frame::world);
  const Evaluation<Interval> iv = evaluate<Interval>(sc, method, Frame::world);
  std::optional<Evaluation<Q>> ex;  // only when some item needs it
  auto exact = [&]() -> const Evaluation<Q>& {
    if (!ex) ex = evaluate<Q>(sc, method, Frame::world);
    return *ex;
  };
  json doc;
  doc["format"] = "qverify-eval/1";
  doc["scene"] = sc.name;
  doc["precision"] = "double";
  doc["method"] = method_name(method);
  doc["frame"] = "world";
  doc["adaptive"] = {{"tolerance", tol},
                     {"ladder", "double -> interval -> exact"},
                     {"rule", "an item is certified when every entry is within tolerance x (largest |entry|) of the "
                              "exact result of the same formula: the double result if it lies in the interval "
                              "enclosure widened by that amount, else the enclosure's midpoints if its half-width is "
                              "that small, else the exact result rounded to double"}};
  json shadows = json::array();
  std::map<std::string, int> count;
  for (std::size_t k = 0; k < sc.shadows.size(); ++k) {
    const ShadowItem<double>& dd = d.shadows[k];
    const ShadowResult<Interval>& ii = iv.shadows[k].result;
    json j = shadow_json(sc, dd);
    j["status"] = exact().shadows[k].result.status();  // statuses: exact
    std::string by;
    double bound = 0;
    const double hw = std::max({relative_halfwidth(ii.P), relative_halfwidth(ii.polar_plane), relative_halfwidth(ii.R)});
    if (all_finite(dd.result.P) && inside(dd.result.P, ii.P, tol) && inside(dd.result.polar_plane, ii.polar_plane, tol) &&
        inside(dd.result.R, ii.R, tol) && hw <= tol) {
      by = "double";
      bound = 2 * hw + tol;
    } else if (hw <= tol) {
      by = "interval";
      bound = hw;
      j["P"] = matrix_json(midpoints(ii.P));
      j["polar_plane"] = matrix_json(midpoints(ii.polar_plane));
      j["R"] = matrix_json(midpoints(ii.R));
    } else {
      by = "exact";
      bound = std::ldexp(1.0, -53);
      const ShadowResult<Q>& e = exact().shadows[k].result;
      j["P"] = matrix_json(rounded(e.P));
      j["polar_plane"] = matrix_json(rounded(e.polar_plane));
      j["R"] = matrix_json(rounded(e.R));
    }
    ++count[by];
    j["certified"] = {{"by", by}, {"relative_error_bound", bound}};
    shadows.push_back(j);
  }
  json reflections = json::array();
  for (std::size_t k = 0; k < sc.reflections.size(); ++k) {
    const ReflectionItem<double>& dd = d.reflections[k];
    const ReflectionItem<Interval>& ii = iv.reflections[k];
    json j = reflection_json(sc, dd);
    j["status"] = exact().reflections[k].result.status();
    std::string by;
    double bound = 0;
    const double hw = std::max(relative_halfwidth(ii.M), relative_halfwidth(ii.result.B));
    if (all_finite(dd.result.B) && inside(dd.M, ii.M, tol) && inside(dd.result.B, ii.result.B, tol) && hw <= tol) {
      by = "double";
      bound = 2 * hw + tol;
    } else if (hw <= tol) {
      by = "interval";
      bound = hw;
      j["M"] = matrix_json(midpoints(ii.M));
      j["B"] = matrix_json(midpoints(ii.result.B));
    } else {
      by = "exact";
      bound = std::ldexp(1.0, -53);
      j["M"] = matrix_json(rounded(exact().reflections[k].M));
      j["B"] = matrix_json(rounded(exact().reflections[k].result.B));
    }
    ++count[by];
    j["certified"] = {{"by", by}, {"relative_error_bound", bound}};
    reflections.push_back(j);
  }
  doc["shadows"] = shadows;
  doc["reflections"] = reflections;
  doc["skipped"] = skipped_json(sc);
  json esc;
  for (const auto& [k, v] : count) esc[k] = v;
  doc["adaptive"]["items_by_stage"] = esc;
  return doc;
}

}  // namespace qverify
