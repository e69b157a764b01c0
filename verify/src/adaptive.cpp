#include <qverify/verify/adaptive.hpp>
#include <qverify/verify/verifier.hpp>

#include <cmath>
#include <stdexcept>
#include <functional>
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

using IntervalMatrix = Eigen::Matrix<Interval, Eigen::Dynamic, Eigen::Dynamic>;
using ExactMatrix = Eigen::Matrix<Q, Eigen::Dynamic, Eigen::Dynamic>;

/// One output of an item (a 4x4 matrix or a plane) at every stage of the ladder.
struct Part {
  const char* key;
  Eigen::MatrixXd dbl;
  IntervalMatrix enc;
  std::function<ExactMatrix()> exact;  ///< evaluated only when the item reaches the exact stage
};

/// Certifies one item within tol: its double result if every part lies in its enclosure widened by
/// tol x scale (and the enclosures are that narrow), else the enclosures' midpoints if their half-width
/// is that small, else the exact result rounded to double. Writes the parts and `certified` into j and
/// returns the stage.
std::string certify(json& j, const std::vector<Part>& parts, double tol) {
  double hw = 0;
  bool dbl_ok = true;
  for (const Part& p : parts) {
    hw = std::max(hw, relative_halfwidth(p.enc));
    dbl_ok = dbl_ok && all_finite(p.dbl) && inside(p.dbl, p.enc, tol);
  }
  std::string by;
  double bound = 0;
  if (dbl_ok && hw <= tol) {
    by = "double";
    bound = 2 * hw + tol;
  } else if (hw <= tol) {
    by = "interval";
    bound = hw;
    for (const Part& p : parts) j[p.key] = matrix_json(midpoints(p.enc));
  } else {
    by = "exact";
    bound = std::ldexp(1.0, -53);
    for (const Part& p : parts) j[p.key] = matrix_json(rounded(p.exact()));
  }
  j["certified"] = {{"by", by}, {"relative_error_bound", bound}};
  return by;
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
    ++count[certify(j,
                    {{"P", dd.result.P, ii.P, [&] { return ExactMatrix(exact().shadows[k].result.P); }},
                     {"polar_plane", dd.result.polar_plane, ii.polar_plane,
                      [&] { return ExactMatrix(exact().shadows[k].result.polar_plane); }},
                     {"R", dd.result.R, ii.R, [&] { return ExactMatrix(exact().shadows[k].result.R); }}},
                    tol)];
    shadows.push_back(j);
  }
  json reflections = json::array();
  for (std::size_t k = 0; k < sc.reflections.size(); ++k) {
    const ReflectionItem<double>& dd = d.reflections[k];
    const ReflectionItem<Interval>& ii = iv.reflections[k];
    json j = reflection_json(sc, dd);
    j["status"] = exact().reflections[k].result.status();
    ++count[certify(j,
                    {{"M", dd.M, ii.M, [&] { return ExactMatrix(exact().reflections[k].M); }},
                     {"B", dd.result.B, ii.result.B, [&] { return ExactMatrix(exact().reflections[k].result.B); }}},
                    tol)];
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
