#include <qverify/exact/number_text.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/studies/audit.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/studies/stress.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <filesystem>

namespace qverify {

using json = nlohmann::ordered_json;
using Q = Rational;

namespace {

Q pow10(int k) {
  Q r(1);
  for (int i = 0; i < std::abs(k); ++i) r *= 10;
  return k >= 0 ? r : Q(1) / r;
}
/// An exact number as a JSON string "p/q".
std::string q(const Q& x) { return "\"" + x.str() + "\""; }
std::string vec(const Q& a, const Q& b, const Q& c) { return "[" + q(a) + ", " + q(b) + ", " + q(c) + "]"; }
int exponent_of(double v) { return static_cast<int>(std::lround(std::log10(v))); }

std::vector<double> decades(int from, int to, int step = 1) {
  std::vector<double> v;
  for (int k = from; step > 0 ? k <= to : k >= to; k += step) v.push_back(std::pow(10.0, k));
  return v;
}

std::string scene_text(const std::string& name, const std::string& quadric, const std::string& light,
                       const std::string& mirror) {
  std::string s = R"({"format": "qverify-scene/1", "name": ")" + name + R"(", "quadrics": [)" + quadric + "]";
  if (!light.empty()) s += R"(, "lights": [)" + light + "]";
  if (!mirror.empty()) s += R"(, "mirrors": [)" + mirror + "]";
  return s + "}";
}

std::string sphere(const Q& cx, const Q& cy, const Q& cz, const Q& r) {
  return R"({"id": "obj", "sphere": {"center": )" + vec(cx, cy, cz) + R"(, "radius": )" + q(r) + "}}";
}
std::string point_light(const Q& x, const Q& y, const Q& z) {
  return R"({"id": "light", "position": )" + vec(x, y, z) + "}";
}

std::vector<StressFamily> make_families() {
  std::vector<StressFamily> f;
  f.push_back({"light-near-surface", "unit sphere; point light at (2,3,6)/7 (1 + eps) approaching the surface", "eps",
               decades(-1, -15, -1), [](double e) {
                 const Q s = Q(1) + pow10(exponent_of(e));
                 return scene_text("light-near-surface", sphere(0, 0, 0, 1), point_light(Q(2, 7) * s, Q(3, 7) * s, Q(6, 7) * s), "");
               }, false});
  f.push_back({"light-far", "unit sphere; point light at distance D along (2,3,6)/7, going to infinity", "D",
               decades(1, 15), [](double d) {
                 const Q D = pow10(exponent_of(d));
                 return scene_text("light-far", sphere(0, 0, 0, 1), point_light(Q(2, 7) * D, Q(3, 7) * D, Q(6, 7) * D), "");
               }, false});
  f.push_back({"light-near-z0", "sphere at (0,0,-3); light at (2,1,l_z), l_z -> 0: the paper's T (1/l_z) breaks", "l_z",
               decades(-1, -15, -1), [](double z) {
                 return scene_text("light-near-z0", sphere(0, 0, -3, 1), point_light(2, 1, pow10(exponent_of(z))), "");
               }, false});
  f.push_back({"thin-ellipsoid", "rotated ellipsoid with radii 1, 1/2 and 1/aspect; light at (2,3,6)", "aspect",
               decades(0, 12), [](double a) {
                 const std::string e = R"({"id": "obj", "ellipsoid": {"center": )" + vec(Q(1, 2), Q(-1, 4), 0) +
                                       R"(, "radii": )" + vec(1, Q(1, 2), Q(1) / pow10(exponent_of(a))) +
                                       R"(, "axes": [["3/5", "-4/5", 0], ["4/5", "3/5", 0], [0, 0, 1]]}})";
                 return scene_text("thin-ellipsoid", e, point_light(2, 3, 6), "");
               }, false});
  f.push_back({"far-from-origin", "unit sphere at (d, 2, 1); light at its centre + (2,3,6)", "d", decades(0, 12),
               [](double d) {
                 const Q D = pow10(exponent_of(d));
                 return scene_text("far-from-origin", sphere(D, 2, 1, 1), point_light(D + 2, 5, 7), "");
               }, false});
  f.push_back({"near-degenerate", "ellipsoid with radii 1, 1, R: det A -> 0, the ellipsoid becomes a cylinder", "R",
               decades(0, 14), [](double r) {
                 const std::string e = R"({"id": "obj", "ellipsoid": {"center": )" + vec(Q(1, 4), 0, Q(1, 2)) +
                                       R"(, "radii": )" + vec(1, 1, pow10(exponent_of(r))) +
                                       R"(, "axes": [[1, 0, 0], [0, "3/5", "-4/5"], [0, "4/5", "3/5"]]}})";
                 return scene_text("near-degenerate", e, point_light(2, 3, 6), "");
               }, false});
  f.push_back({"mirror-far", "unit sphere at (1/2, 1/4, 0); mirror 2x + 3y + 6z = 7 d, d -> infinity", "d", decades(0, 12),
               [](double d) {
                 const Q D = pow10(exponent_of(d));
                 return scene_text("mirror-far", sphere(Q(1, 2), Q(1, 4), 0, 1), "",
                                   R"({"id": "mirror", "plane": [2, 3, 6, )" + q(Q(-7) * D) + "]}");
               }, true});
  f.push_back({"scale-extremes", "sphere at (1,2,3), radius 1, as a matrix with every entry scaled by s", "s",
               decades(-150, 150, 25), [](double s) {
                 const Q S = pow10(exponent_of(s));
                 const int A[4][4] = {{1, 0, 0, -1}, {0, 1, 0, -2}, {0, 0, 1, -3}, {-1, -2, -3, 13}};
                 std::string m = R"({"id": "obj", "matrix": [)";
                 for (int i = 0; i < 4; ++i) {
                   m += i ? ", [" : "[";
                   for (int j = 0; j < 4; ++j) m += (j ? ", " : "") + q(S * A[i][j]);
                   m += "]";
                 }
                 return scene_text("scale-extremes", m + "]}", point_light(5, 1, 9), "");
               }, false});
  f.push_back({"decimal-inputs", "sphere of radius 7/10 s at (0.1, 0.2, 0.3), light at the centre + s (2,3,6): decimal "
               "inputs that binary cannot represent, the object shrinking", "s", decades(0, -12, -1),
               [](double s) {
                 const Q S = pow10(exponent_of(s));
                 const Q cx(1, 10), cy(2, 10), cz(3, 10);
                 return scene_text("decimal-inputs", sphere(cx, cy, cz, Q(7, 10) * S),
                                   point_light(cx + 2 * S, cy + 3 * S, cz + 6 * S), "");
               }, false});
  // Where another implementation breaks and the families above would not show it.
  f.push_back({"light-near-infinity", "unit sphere at (1/2, 1/4, 1/8); point light at the centre + D (2,3,6)/7, D -> "
               "1e300: a light almost at infinity given as a point (L^T A L ~ D^2 overflows a naive double)", "D",
               decades(20, 300, 20), [](double d) {
                 const Q D = pow10(exponent_of(d));
                 const Q cx(1, 2), cy(1, 4), cz(1, 8);
                 return scene_text("light-near-infinity", sphere(cx, cy, cz, 1),
                                   point_light(cx + Q(2, 7) * D, cy + Q(3, 7) * D, cz + Q(6, 7) * D), "");
               }, false});
  f.push_back({"mirror-through-object", "unit sphere at (0.3, 0.2, 0.1); mirror 2x + 3y + 6z + d = 0 (decimal d) at "
               "distance eps from the centre, eps -> 1e-15: the mirror almost through the object", "eps",
               decades(0, -15, -1), [](double e) {
                 const Q E = pow10(exponent_of(e));
                 const Q cx(3, 10), cy(2, 10), cz(1, 10);
                 const Q d = -(2 * cx + 3 * cy + 6 * cz) - 7 * E;  // signed distance (n.c + d) / |n| = -eps
                 return scene_text("mirror-through-object", sphere(cx, cy, cz, 1), "",
                                   R"({"id": "mirror", "plane": [2, 3, 6, )" + q(d) + "]}");
               }, true});
  f.push_back({"skewed-ellipsoid", "ellipsoid at (1/2, -1/4, 1), radii 1, 1, 1, axes given as the non-orthogonal "
               "columns (1,0,0), (1,s,0), (0,1/3,1): the second axis turns onto the first as s -> 1e-12; light at (2,3,6)",
               "s", decades(0, -12, -1), [](double sv) {
                 const Q S = pow10(exponent_of(sv));
                 const std::string e = R"({"id": "obj", "ellipsoid": {"center": )" + vec(Q(1, 2), Q(-1, 4), 1) +
                                       R"(, "radii": [1, 1, 1], "axes": [[1, 1, 0], [0, )" + q(S) +
                                       R"(, "1/3"], [0, 0, 1]]}})";
                 return scene_text("skewed-ellipsoid", e, point_light(2, 3, 6), "");
               }, false});
  f.push_back({"mixed-magnitudes", "ellipsoid s x'^2 + y'^2 + z'^2 / s = 1 centred at (1/2, 1/4, 1/8), given as a "
               "matrix whose entries range from s to 1/s, s -> 1e12; light at the centre + (2,3,6)", "s",
               decades(0, 12), [](double sv) {
                 const Q S = pow10(exponent_of(sv));
                 const Q c[3] = {Q(1, 2), Q(1, 4), Q(1, 8)};
                 const Q k[3] = {S, Q(1), Q(1) / S};
                 Q A[4][4];
                 for (int i = 0; i < 4; ++i)
                   for (int j = 0; j < 4; ++j) A[i][j] = 0;
                 Q c0 = -1;
                 for (int i = 0; i < 3; ++i) {
                   A[i][i] = k[i];
                   A[i][3] = A[3][i] = -k[i] * c[i];
                   c0 += k[i] * c[i] * c[i];
                 }
                 A[3][3] = c0;
                 std::string m = R"({"id": "obj", "matrix": [)";
                 for (int i = 0; i < 4; ++i) {
                   m += i ? ", [" : "[";
                   for (int j = 0; j < 4; ++j) m += (j ? ", " : "") + q(A[i][j]);
                   m += "]";
                 }
                 return scene_text("mixed-magnitudes", m + "]}",
                                   point_light(c[0] + 2, c[1] + 3, c[2] + 6), "");
               }, false});
  return f;
}

struct RunSpec {
  const char* precision;
  Method method;
  std::optional<Frame> frame;
  std::string label;
};

std::vector<RunSpec> run_specs() {
  return {{"float", Method::direct, std::nullopt, "float/direct"},
          {"float", Method::paper, std::nullopt, "float/paper"},
          {"double", Method::direct, Frame::world, "double/direct/world (naive)"},
          {"double", Method::direct, std::nullopt, "double/direct (default, robust)"},
          {"double", Method::paper, std::nullopt, "double/paper"},
          {"long-double", Method::direct, std::nullopt, "long-double/direct"},
          {"long-double", Method::paper, std::nullopt, "long-double/paper"},
          {"float128", Method::direct, std::nullopt, "float128/direct"},
          {"float128", Method::paper, std::nullopt, "float128/paper"}};
}

/// Positions in run_specs() of the naive world-frame double run and of the default (robust) double run.
constexpr std::size_t kNaiveRun = 2, kDefaultRun = 3;

const char* kColors[] = {"#9edae5", "#17becf", "#d62728", "#1f77b4", "#ff7f0e", "#2ca02c", "#98df8a", "#9467bd", "#c5b0d5"};

/// The geometric error of Qm (given in the frame with origin o) over the item's points.
double geometric_error(const ItemPoints& pts, const std::optional<Vec3<Q>>& origin, const Mat4<Q>& Qm) {
  return relative(measure_quadric(in_frame(pts.points, origin), Qm), pts.size).convert_to<double>();
}

/// One run's item measured against the exact result: the one measurement of every run, qverify's own and a
/// candidate's. Infinite errors when the run gave no finite item.
struct RunMeasure {
  double matrix = INFINITY;          ///< projective error of P (B) against the exact one
  double geometric = INFINITY;       ///< geometric error of P (B)
  double item_geometric = INFINITY;  ///< over every result of the item: P, polar plane and R, or B
  bool present = false;
  std::optional<Vec3<Q>> origin;
};

RunMeasure measure_run(const StressFamily& fam, const ResultSet& rs, const ItemPoints& pts, const Evaluation<Q>& ref) {
  RunMeasure m;
  m.present = fam.reflection ? rs.reflections[0].present : rs.shadows[0].present;
  if (!m.present) return m;
  m.origin = fam.reflection ? rs.reflections[0].origin : rs.shadows[0].origin;
  // the family's one item: B of a reflection or P of a shadow, in its own frame
  const Mat4<Q>& got = fam.reflection ? rs.reflections[0].B : rs.shadows[0].P;
  const Mat4<Q>& want = fam.reflection ? ref.reflections[0].result.B : ref.shadows[0].result.P;
  const Vec3<Q> o = m.origin ? *m.origin : Vec3<Q>::Zero();
  m.matrix = projective_error(quadric_from_local(got, o), want, true);
  m.geometric = geometric_error(pts, m.origin, got);
  // the item's geometric error, over all its results (what eval's flag and a candidate's verdict are about)
  m.item_geometric = (fam.reflection ? reflection_error(pts, m.origin, got).geometric
                                     : shadow_error(pts, m.origin, got, rs.shadows[0].polar, rs.shadows[0].R).geometric)
                         .convert_to<double>();
  return m;
}

/// Least-squares slope of log10(y) against log10(x) over finite, positive points.
json slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i]) && y[i] > 0 && x[i] > 0) {
      const double a = std::log10(x[i]), b = std::log10(y[i]);
      sx += a, sy += b, sxx += a * a, sxy += a * b, ++n;
    }
  if (n < 2 || n * sxx - sx * sx == 0) return nullptr;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

const char* const kCandidateColor = "#e377c2";

/// First-order condition estimate of the naive double computation (world frame) of the family's item:
/// | |P| computed from |A|, |L| | / |P| (|B| from |M|^T |A| |M| for a reflection).
Measure condition_estimate(const StressFamily& fam, const Evaluation<Q>& ref, const Mat4<Q>& Mw) {
  const Mat4<Q>& A = ref.scene.A[0];
  if (!fam.reflection) {
    const Mat4<Q> absA = A.cwiseAbs();
    const Vec4<Q> absL = ref.scene.L[0].cwiseAbs();
    const Vec4<Q> aAL = absA * absL;
    const Mat4<Q> Pabs = absL.dot(aAL) * absA + aAL * aAL.transpose();
    const Q nP = max_abs(ref.shadows[0].result.P);
    return nP != 0 ? to_measure(Q(max_abs(Pabs) / nP)) : Measure(1);
  }
  const Mat4<Q> aM = Mw.cwiseAbs();
  const Q nB = max_abs(ref.reflections[0].result.B);
  return nB != 0 ? to_measure(Q(max_abs(Mat4<Q>(aM.transpose() * A.cwiseAbs() * aM)) / nB)) : Measure(1);
}

/// The candidate's totals over every family (the document's "candidate" section).
struct CandidateTotals {
  json reproducers = json::array();
  std::vector<double> call_seconds;
  int failed_calls = 0, beyond_calls = 0;
};

/// One family's sweep: every parameter value run in every precision (and by the candidate), measured against
/// exact on the same points; then the family's summary (slopes, breakdowns, the flag's self-check) and figure.
class FamilySweep {
 public:
  FamilySweep(const StressFamily& fam, const StressOptions& opt, const std::vector<RunSpec>& specs,
              const std::filesystem::path& failures_dir, CandidateTotals& totals)
      : fam_(fam), opt_(opt), specs_(specs), cand_(opt.candidate ? &*opt.candidate : nullptr),
        failures_dir_(failures_dir), totals_(totals), geo_(specs.size() + (cand_ ? 1 : 0)), mat_(geo_.size()),
        flags_(specs.size()) {}

  /// The family's point K (parameter value fam.values[K]).
  void point(std::size_t K) {
    const double v = fam_.values[K];
    const std::string text = fam_.scene(v);
    const Scene sc = parse_scene(text, fam_.name + ".json");
    const Evaluation<Q> ref = evaluate<Q>(sc, Method::direct);
    const Mat4<Q>& A = ref.scene.A[0];
    // exact sample points (world) of the item, and the object's size
    Mat4<Q> Mw = Mat4<Q>::Identity();
    if (fam_.reflection) Mw = ref.reflections[0].M;
    const ItemPoints pts = fam_.reflection ? reflected_points(A, Mw, opt_.samples, 11)
                                           : terminator_points(A, ref.scene.L[0], opt_.samples, 11);
    const Measure kappa = condition_estimate(fam_, ref, Mw);
    const double pred = (kappa * std::numeric_limits<double>::epsilon()).convert_to<double>();
    json runs = json::array();
    std::optional<Vec3<Q>> robust_origin;  // the frame of the default double run
    for (std::size_t r = 0; r < specs_.size(); ++r) runs.push_back(own_run(r, v, sc, pts, ref, robust_origin));
    if (cand_) runs.push_back(candidate_run(K, v, text, sc, pts, ref));
    const double floor_err = rounded_floor(ref, pts, robust_origin);
    const double target = std::max(1e-9, 10 * floor_err);
    params_.push_back(v);
    predicted_.push_back(pred);
    floors_.push_back(floor_err);
    const double robust = geo_[kDefaultRun].back();
    const bool meets = robust <= target;
    all_meet_ = all_meet_ && meets;
    points_.push_back({{"param", v},
                       {"exact_status", fam_.reflection ? ref.reflections[0].result.status() : ref.shadows[0].result.status()},
                       {"points", pts.points.size()},
                       {"kappa", kappa.convert_to<double>()},
                       {"predicted_double_error", pred},
                       {"rounded_exact_error", num(floor_err)},
                       {"target", target},
                       {"default_meets_target", meets},
                       {"runs", runs}});
  }

  /// The family's entry of the document, after every point.
  json summary() {
    totals_.failed_calls += fam_failed_;
    totals_.beyond_calls += fam_beyond_;
    json slopes;
    slopes["predicted_double_error (eps * kappa)"] = slope(params_, predicted_);
    for (std::size_t r = 0; r < specs_.size(); ++r) {
      slopes[specs_[r].label] = {{"matrix_error", slope(params_, mat_[r])}, {"geometric_error", slope(params_, geo_[r])}};
      json at = nullptr;
      for (std::size_t i = 0; i < params_.size(); ++i)
        if (!(geo_[r][i] <= 1e-9)) {
          at = params_[i];
          break;
        }
      breakdown_[specs_[r].label] = at;
    }
    if (cand_) {
      const std::size_t c = specs_.size();
      slopes[cand_->name] = {{"matrix_error", slope(params_, mat_[c])}, {"geometric_error", slope(params_, geo_[c])}};
      for (std::size_t i = 0; i < params_.size(); ++i)
        if (cand_bad_[i]) {
          cand_at_ = params_[i];
          break;
        }
      breakdown_[cand_->name] = cand_at_;
    }
    json famj{{"name", fam_.name},     {"description", fam_.description}, {"parameter", fam_.parameter},
              {"item", fam_.reflection ? "reflection B" : "shadow P"},
              {"geometric_target", "max(1e-9, 10 x rounded_exact_error): the default double path must be within 1e-9 "
                                   "of the object's size, or within 10x of a correctly rounded matrix in its own frame"},
              {"default_meets_target", all_meet_},
              {"flag_check",
               {{"rule", "every run whose item geometric error (P, polar plane and R, or B) measured on these exact "
                         "points (seed 11) exceeds the accuracy target 1e-9 carries the flag inaccurate (from eval's "
                         "error bound on other points); flagged_below lists flagged runs measured below 1e-11 here "
                         "(information: a sample bounds the true error only from below)"},
                {"ok", missed_.empty()}, {"missed", missed_}, {"flagged_below", flagged_below_}}},
              {"points", points_}, {"slopes", slopes},
              {"breakdown", breakdown_}};
    if (cand_)
      famj["candidate"] = {{"name", cand_->name},
                           {"breakdown", cand_at_},
                           {"breakdown_reason", cand_first_reason_},
                           {"failed_calls", fam_failed_},
                           {"beyond_accuracy", fam_beyond_},
                           {"reproducers", fam_failed_ + fam_beyond_}};
    return famj;
  }

  /// The family's figure (after summary()): geometric error against the parameter for every run.
  Plot plot() const {
    Plot plot;
    plot.title = fam_.name + ": geometric error of " + (fam_.reflection ? "B" : "P") + " relative to the object size";
    plot.x_label = fam_.parameter;
    plot.y_label = "max distance of exact points / object size";
    for (std::size_t r = 0; r < specs_.size(); ++r) {
      PlotSeries s{specs_[r].label, kColors[r], {}, true, true, r == kNaiveRun, {}};
      for (std::size_t i = 0; i < params_.size(); ++i) s.points.emplace_back(params_[i], geo_[r][i]);
      plot.series.push_back(s);
    }
    if (cand_) {
      PlotSeries s{cand_->name + " (candidate)", kCandidateColor, {}, true, true, false, {}};
      for (std::size_t i = 0; i < params_.size(); ++i) s.points.emplace_back(params_[i], geo_[specs_.size()][i]);
      plot.series.push_back(s);
      // failed calls have no error: marked above every measured value
      double top = 1;
      for (const auto& g : geo_)
        for (double y : g)
          if (std::isfinite(y)) top = std::max(top, y);
      PlotSeries failed{cand_->name + " failed (candidate-failed)", kCandidateColor, {}, false, true, false, {}};
      for (std::size_t i = 0; i < params_.size(); ++i)
        if (cand_failed_[i] || !std::isfinite(geo_[specs_.size()][i])) {
          failed.points.emplace_back(params_[i], top * 10);
          failed.labels.push_back(cand_failed_[i] ? "failed" : "non-finite");
        }
      if (!failed.points.empty()) plot.series.push_back(failed);
    }
    PlotSeries flagged{"flagged inaccurate by eval", "#d62728", {}, false, true, false, {}};
    for (std::size_t r = 0; r < specs_.size(); ++r)
      for (std::size_t i = 0; i < params_.size(); ++i)
        if (flags_[r][i] && std::isfinite(geo_[r][i])) flagged.points.emplace_back(params_[i], geo_[r][i]);
    if (!flagged.points.empty()) plot.series.push_back(flagged);
    PlotSeries floor_series{"exact, correctly rounded to double (floor)", "#000000", {}, true, true, true, {}};
    for (std::size_t i = 0; i < params_.size(); ++i) floor_series.points.emplace_back(params_[i], floors_[i]);
    plot.series.push_back(floor_series);
    PlotSeries pred_series{"eps_double * kappa (first-order estimate)", "#7f7f7f", {}, true, false, true, {}};
    for (std::size_t i = 0; i < params_.size(); ++i) pred_series.points.emplace_back(params_[i], predicted_[i]);
    plot.series.push_back(pred_series);
    const json& naive_at = breakdown_[specs_[kNaiveRun].label];
    if (!naive_at.is_null()) plot.x_marks.emplace_back(naive_at.get<double>(), "naive double > 1e-9");
    if (!cand_at_.is_null()) {
      const double x = cand_at_.get<double>();
      auto same = std::find_if(plot.x_marks.begin(), plot.x_marks.end(), [&](const auto& m) { return m.first == x; });
      if (same != plot.x_marks.end()) same->second += "; " + cand_->name + " breaks";  // one label per line
      else plot.x_marks.emplace_back(x, cand_->name + " breaks");
    }
    plot.height = 520;
    plot.width = 900;
    return plot;
  }

 private:
  /// qverify's own run r at the point: computed as eval computes it, measured, and its flag self-checked.
  json own_run(std::size_t r, double v, const Scene& sc, const ItemPoints& pts, const Evaluation<Q>& ref,
               std::optional<Vec3<Q>>& robust_origin) {
    const RunSpec& spec = specs_[r];
    json run{{"run", spec.label}, {"source", "qverify"}, {"precision", spec.precision}, {"method", method_name(spec.method)}};
    RunMeasure m;
    bool flagged = false, returned = false;  // returned: the run gave a result (not refused)
    std::string status;
    try {
      const ResultSet rs = computed_results(sc, *parse_precision(spec.precision), spec.method, spec.frame);
      status = fam_.reflection ? rs.reflections[0].status : rs.shadows[0].status;
      const auto& acc = fam_.reflection ? rs.reflections[0].accuracy : rs.shadows[0].accuracy;
      if (acc) {  // also for a non-finite result, which eval flags
        returned = true;
        flagged = acc->inaccurate;
        run["error_bound"] = acc->bound ? json(*acc->bound) : json(nullptr);
      }
      m = measure_run(fam_, rs, pts, ref);
      if (m.present) {
        run["frame"] = m.origin ? "local" : "world";
        if (r == kDefaultRun) robust_origin = m.origin;
      }
    } catch (const InputError& e) {
      status = std::string("refused: ") + e.problem;
    }
    run["status"] = status;
    run["matrix_error"] = num(m.matrix);
    run["geometric_error"] = num(m.geometric);
    run["item_geometric_error"] = num(m.item_geometric);
    run["flags"] = flagged ? json::array({"inaccurate"}) : json::array();
    // The flag's self-check. These points are not eval's, and a sample only bounds the true error from
    // below: an error above the target here proves the flag missing; a flag where these points show less
    // than target / 100 proves nothing (the error may sit between them) and is listed as information.
    const json at{{"param", v}, {"run", spec.label}, {"item_geometric_error", num(m.item_geometric)}};
    if (returned && !(m.item_geometric <= kDefaultAccuracy) && !flagged) missed_.push_back(at);
    if (m.item_geometric < kDefaultAccuracy / 100 && flagged) flagged_below_.push_back(at);
    geo_[r].push_back(m.geometric);
    flags_[r].push_back(flagged);
    mat_[r].push_back(m.matrix);
    return run;
  }

  /// The candidate at point K, on the very scene text, measured by the same code as qverify's runs; a failed
  /// call or a result beyond the accuracy target leaves a reproducer.
  json candidate_run(std::size_t K, double v, const std::string& text, const Scene& sc, const ItemPoints& pts,
                     const Evaluation<Q>& ref) {
    const CandidateCall call = call_candidate(*cand_, sc, text, fam_.name + "-" + std::to_string(K));
    json run{{"run", cand_->name}, {"source", "candidate"}};
    RunMeasure m;
    if (call.ok) {
      run["precision"] = call.results.precision.name();
      run["method"] = method_name(call.results.method);
      m = measure_run(fam_, call.results, pts, ref);
      run["frame"] = m.origin ? "local" : "world";
      const std::string& claimed = fam_.reflection ? call.results.reflections[0].status : call.results.shadows[0].status;
      run["status"] = claimed.empty() ? std::string("unstated") : claimed;
    } else {
      run["precision"] = nullptr;
      run["method"] = nullptr;
      run["status"] = "candidate-failed";
      run["error"] = call.error;
    }
    run["seconds"] = call.seconds;
    run["matrix_error"] = num(m.matrix);
    run["geometric_error"] = num(m.geometric);
    run["item_geometric_error"] = num(m.item_geometric);
    run["flags"] = json::array();
    const bool beyond = call.ok && !(m.item_geometric <= opt_.accuracy);
    run["beyond_accuracy"] = beyond;
    totals_.call_seconds.push_back(call.seconds);
    if (!call.ok || beyond) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3g", m.item_geometric);
      char tbuf[32];
      std::snprintf(tbuf, sizeof tbuf, "%.3g", opt_.accuracy);
      const std::string reason =
          !call.ok ? "candidate-failed: " + call.error
                   : std::string("item geometric error ") + (std::isfinite(m.item_geometric) ? buf : "infinite") +
                         " of the object size exceeds the accuracy target " + tbuf;
      json rep = write_candidate_reproducer(failures_dir_, cand_->name, fam_.name, K, v, text, call, reason);
      run["reproducer"] = rep["scene"];
      rep["status"] = call.ok ? "beyond-accuracy" : "candidate-failed";
      rep["item_geometric_error"] = num(m.item_geometric);
      totals_.reproducers.push_back(rep);
      if (cand_first_reason_.is_null()) cand_first_reason_ = reason;
      (call.ok ? fam_beyond_ : fam_failed_) += 1;
    }
    cand_failed_.push_back(!call.ok);
    cand_bad_.push_back(!call.ok || beyond);
    geo_[specs_.size()].push_back(m.geometric);
    mat_[specs_.size()].push_back(m.matrix);
    return run;
  }

  /// The floor: the exact result in the default run's frame, correctly rounded to double (with the same exact
  /// power-of-two scaling). "What a correctly rounded matrix in the object's own frame can reach".
  double rounded_floor(const Evaluation<Q>& ref, const ItemPoints& pts, const std::optional<Vec3<Q>>& robust_origin) const {
    const Vec3<Q> o = robust_origin ? *robust_origin : Vec3<Q>::Zero();
    const Mat4<Q> exact_local = fam_.reflection ? quadric_to_local(ref.reflections[0].result.B, o)
                                                : quadric_to_local(ref.shadows[0].result.P, o);
    const Mat4<double> rounded = rounded_scaled<double>(exact_local);
    return all_finite(rounded) ? geometric_error(pts, robust_origin, exact_matrix(rounded)) : INFINITY;
  }

  const StressFamily& fam_;
  const StressOptions& opt_;
  const std::vector<RunSpec>& specs_;
  const Candidate* cand_;
  std::filesystem::path failures_dir_;
  CandidateTotals& totals_;
  json points_ = json::array();
  std::vector<std::vector<double>> geo_, mat_;  ///< per run (the candidate's last), per point
  std::vector<std::vector<bool>> flags_;        ///< per own run, per point: flagged inaccurate by eval
  std::vector<bool> cand_failed_, cand_bad_;    ///< per point: the call failed; failed or beyond the accuracy target
  json cand_first_reason_ = nullptr, cand_at_ = nullptr, breakdown_;
  int fam_failed_ = 0, fam_beyond_ = 0;
  json missed_ = json::array(), flagged_below_ = json::array();
  std::vector<double> params_, predicted_, floors_;
  bool all_meet_ = true;
};

/// The document's "candidate" section.
json candidate_section(const Candidate& cand, const StressOptions& opt, const CandidateTotals& t) {
  std::vector<double> sorted = t.call_seconds;
  std::sort(sorted.begin(), sorted.end());
  json c = candidate_section_head(cand, opt.accuracy);
  c["rule"] = "the candidate is given each point's scene (the file of its reproducer) and must return a qverify-eval/1 "
              "document with the family's item; its results are measured like every run (matrix and geometric error "
              "against exact on the same points); a point is a reproducer when the call failed (status "
              "candidate-failed, with error) or the item's geometric error over all its results (P, polar plane and R, "
              "or B) exceeds accuracy; breakdown is the first such parameter value";
  c["calls"] = t.call_seconds.size();
  c["failed_calls"] = t.failed_calls;
  c["beyond_accuracy"] = t.beyond_calls;
  c["median_seconds_per_call"] = sorted.empty() ? json(nullptr) : json(sorted[sorted.size() / 2]);
  c["failures_dir"] = t.reproducers.empty() ? json(nullptr) : json("failures");
  c["reproducers"] = t.reproducers;
  return c;
}

}  // namespace

const std::vector<StressFamily>& stress_families() {
  static const std::vector<StressFamily> f = make_families();
  return f;
}

StressReport run_stress(const StressOptions& opt) {
  create_output_directory(opt.out_dir);  // before the sweeps: a bad --out fails at once
  const auto specs = run_specs();
  const std::filesystem::path failures_dir = std::filesystem::path(opt.out_dir) / "failures";
  if (opt.candidate) remove_candidate_reproducers(failures_dir, opt.candidate->name);
  CandidateTotals totals;
  json families = json::array();
  std::vector<std::pair<std::string, Plot>> plots;
  for (const StressFamily& fam : stress_families()) {
    if (!opt.families.empty() && std::find(opt.families.begin(), opt.families.end(), fam.name) == opt.families.end())
      continue;
    if (opt.progress) opt.progress("stress: " + fam.name);
    FamilySweep sweep(fam, opt, specs, failures_dir, totals);
    for (std::size_t K = opt.worst_only ? fam.values.size() - 1 : 0; K < fam.values.size(); ++K) sweep.point(K);
    families.push_back(sweep.summary());
    plots.emplace_back(fam.name, sweep.plot());
  }
  json doc{{"format", "qverify-stress/1"},
           {"reference", "exact"},
           {"geometric_error", "max over exact sample points (terminator points for P, reflected points of A for B, "
                               "sampled in Q(sqrt d)) of the first-order distance |x^T Q x| / |grad|, in the result's own "
                               "frame, divided by the object's size"},
           {"matrix_error", "projective error against the exact matrix (cross-multiplication, see qverify audit)"}};
  if (opt.candidate) doc["candidate"] = candidate_section(*opt.candidate, opt, totals);
  doc["families"] = families;
  return {std::move(doc), std::move(plots)};
}

}  // namespace qverify
