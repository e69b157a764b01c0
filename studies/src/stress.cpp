#include <qverify/exact/number_text.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/studies/audit.hpp>
#include <qverify/scene/files.hpp>
#include <qverify/studies/stress.hpp>
#include <qverify/verify/verifier.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <utility>

namespace qverify {

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

/// One of qverify's own runs at every point: a precision, a method and, for the naive run, the world frame.
struct RunSpec {
  Precision precision;
  Method method;
  std::optional<Frame> frame;
  std::string label;
};

std::vector<RunSpec> run_specs() {
  const auto p = [](const char* name) { return *parse_precision(name); };
  return {{p("float"), Method::direct, std::nullopt, "float/direct"},
          {p("float"), Method::paper, std::nullopt, "float/paper"},
          {p("double"), Method::direct, Frame::world, "double/direct/world (naive)"},
          {p("double"), Method::direct, std::nullopt, "double/direct (default, robust)"},
          {p("double"), Method::paper, std::nullopt, "double/paper"},
          {p("long-double"), Method::direct, std::nullopt, "long-double/direct"},
          {p("long-double"), Method::paper, std::nullopt, "long-double/paper"},
          {p("float128"), Method::direct, std::nullopt, "float128/direct"},
          {p("float128"), Method::paper, std::nullopt, "float128/paper"}};
}

/// Positions in run_specs() of the naive world-frame double run and of the default (robust) double run.
constexpr std::size_t kNaiveRun = 2, kDefaultRun = 3;

const char* kColors[] = {"#9edae5", "#17becf", "#d62728", "#1f77b4", "#ff7f0e", "#2ca02c", "#98df8a", "#9467bd", "#c5b0d5"};

/// The geometric error of a family's one result (given in the frame with origin o) over the item's points:
/// B on every reflected point; a shadow's P on the terminator's points but A's singular ones (P_points: P's
/// gradient vanishes there, as eval and verify measure it).
double geometric_error(const StressFamily& fam, const ItemPoints& pts, const std::optional<Vec3<Q>>& origin,
                       const Mat4<Q>& Qm) {
  const std::vector<RootPoint> local = in_frame(pts.points, origin);
  return relative(measure_quadric(fam.reflection ? local : P_points(local, pts), Qm), pts.size).convert_to<double>();
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
  m.geometric = geometric_error(fam, pts, m.origin, got);
  // the item's geometric error, over all its results (what eval's flag and a candidate's verdict are about)
  m.item_geometric = (fam.reflection ? reflection_error(pts, m.origin, got).geometric
                                     : shadow_error(pts, m.origin, got, rs.shadows[0].polar, rs.shadows[0].R).geometric)
                         .convert_to<double>();
  return m;
}

/// Least-squares slope of log10(y) against log10(x) over finite, positive points; none with fewer than two.
std::optional<double> slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(y[i]) && y[i] > 0 && x[i] > 0) {
      const double a = std::log10(x[i]), b = std::log10(y[i]);
      sx += a, sy += b, sxx += a * a, sxy += a * b, ++n;
    }
  if (n < 2 || n * sxx - sx * sx == 0) return std::nullopt;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

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

/// One family's sweep: every parameter value run in every precision (and by the candidate), measured against
/// exact on the same points; then the family's summary (slopes, breakdowns, the flag's self-check) and figure.
class FamilySweep {
 public:
  FamilySweep(const StressFamily& fam, const StressOptions& opt, const std::vector<RunSpec>& specs,
              const std::filesystem::path& failures_dir, std::optional<StressCandidateSummary>& totals)
      : fam_(fam), opt_(opt), specs_(specs), cand_(opt.candidate ? &*opt.candidate : nullptr),
        failures_dir_(failures_dir), totals_(totals), geo_(specs.size() + (cand_ ? 1 : 0)), mat_(geo_.size()),
        flags_(specs.size()) {
    result_.name = fam.name;
    result_.description = fam.description;
    result_.parameter = fam.parameter;
    result_.reflection = fam.reflection;
    if (cand_) result_.candidate = StressCandidateFamily{cand_->name, std::nullopt, std::nullopt, 0, 0};
  }

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
    StressPoint p;
    p.param = v;
    p.exact_status = fam_.reflection ? ref.reflections[0].result.status() : ref.shadows[0].result.status();
    p.sample_points = pts.points.size();
    p.kappa = kappa.convert_to<double>();
    p.predicted_double_error = (kappa * std::numeric_limits<double>::epsilon()).convert_to<double>();
    std::optional<Vec3<Q>> robust_origin;  // the frame of the default double run
    for (std::size_t r = 0; r < specs_.size(); ++r) p.runs.push_back(own_run(r, v, sc, pts, ref, robust_origin));
    if (cand_) p.runs.push_back(candidate_run(K, v, text, sc, pts, ref));
    p.rounded_exact_error = rounded_floor(ref, pts, robust_origin);
    p.target = std::max(1e-9, 10 * p.rounded_exact_error);
    params_.push_back(v);
    predicted_.push_back(p.predicted_double_error);
    floors_.push_back(p.rounded_exact_error);
    // Judged on the whole item and from above: eval's error bound (certified over every point of the
    // geometry for what its certified_for names, where the terminator is an ellipse; measured on samples, with a
    // margin, for the rest) within the target, and no error beyond it on these points or in what eval
    // proves the item reaches. (P's error on these points alone only bounds the truth from below.)
    const StressRun& def = p.runs[kDefaultRun];
    p.default_meets_target = def.error_bound && *def.error_bound <= p.target && def.item_geometric_error <= p.target;
    result_.default_meets_target = result_.default_meets_target && p.default_meets_target;
    result_.points.push_back(std::move(p));
  }

  /// The family's summary, after every point: slopes and breakdowns per run, the candidate's totals.
  void summarize() {
    result_.predicted_slope = slope(params_, predicted_);
    for (std::size_t r = 0; r < specs_.size(); ++r) {
      StressRunSummary s{specs_[r].label, slope(params_, mat_[r]), slope(params_, geo_[r]), std::nullopt};
      for (std::size_t i = 0; i < params_.size(); ++i)
        if (!(geo_[r][i] <= 1e-9)) {
          s.breakdown = params_[i];
          break;
        }
      result_.runs.push_back(std::move(s));
    }
    if (cand_) {
      const std::size_t c = specs_.size();
      StressCandidateFamily& fc = *result_.candidate;
      for (std::size_t i = 0; i < params_.size(); ++i)
        if (cand_bad_[i]) {
          fc.breakdown = params_[i];
          break;
        }
      result_.runs.push_back({cand_->name, slope(params_, mat_[c]), slope(params_, geo_[c]), fc.breakdown});
      totals_->failed_calls += fc.failed_calls;
      totals_->beyond_accuracy += fc.beyond_accuracy;
      totals_->failed_checks += fc.failed_checks;
    }
  }

  /// The family's figure (after summarize()): geometric error against the parameter for every run.
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
    if (const auto naive_at = result_.runs[kNaiveRun].breakdown) plot.x_marks.emplace_back(*naive_at, "naive double > 1e-9");
    if (cand_ && result_.candidate->breakdown) {
      const double x = *result_.candidate->breakdown;
      auto same = std::find_if(plot.x_marks.begin(), plot.x_marks.end(), [&](const auto& m) { return m.first == x; });
      if (same != plot.x_marks.end()) same->second += "; " + cand_->name + " breaks";  // one label per line
      else plot.x_marks.emplace_back(x, cand_->name + " breaks");
    }
    plot.height = 520;
    plot.width = 900;
    return plot;
  }

  /// The family's result (after summarize()), moved out.
  StressFamilyResult take_result() { return std::move(result_); }

 private:
  /// qverify's own run r at the point: computed as eval computes it, measured, and its flag self-checked.
  StressRun own_run(std::size_t r, double v, const Scene& sc, const ItemPoints& pts, const Evaluation<Q>& ref,
                    std::optional<Vec3<Q>>& robust_origin) {
    const RunSpec& spec = specs_[r];
    StressRun run;
    run.run = spec.label;
    run.precision = spec.precision;
    run.method = spec.method;
    RunMeasure m;
    try {
      const ResultSet rs = computed_results(sc, spec.precision, spec.method, spec.frame);
      run.status = fam_.reflection ? rs.reflections[0].status : rs.shadows[0].status;
      const auto& acc = fam_.reflection ? rs.reflections[0].accuracy : rs.shadows[0].accuracy;
      if (acc) {  // also for a non-finite result, which eval flags
        run.returned = true;
        run.inaccurate = acc->inaccurate;
        run.error_bound = acc->bound;
      }
      m = measure_run(fam_, rs, pts, ref);
      // what eval itself proved the item reaches (its certified branch and bound sees the whole terminator,
      // these points only a few of it): the item's error is at least that
      if (acc && m.present) m.item_geometric = std::max(m.item_geometric, acc->attained);
      if (m.present) {
        run.frame = m.origin ? Frame::local : Frame::world;
        if (r == kDefaultRun) robust_origin = m.origin;
      }
    } catch (const InputError& e) {
      run.status = std::string("refused: ") + e.problem;
    }
    run.matrix_error = m.matrix;
    run.geometric_error = m.geometric;
    run.item_geometric_error = m.item_geometric;
    // The flag's self-check. These points are not eval's, and a sample only bounds the true error from
    // below (as does eval's attained error, taken in above): an error above the target here proves the
    // flag missing; a flag where the item is known to reach less than target / 100 proves nothing (the
    // error may sit elsewhere) and is listed as information.
    const FlaggedRun at{v, spec.label, m.item_geometric};
    if (run.returned && !(m.item_geometric <= kDefaultAccuracy) && !run.inaccurate) result_.flag_check.missed.push_back(at);
    if (m.item_geometric < kDefaultAccuracy / 100 && run.inaccurate) result_.flag_check.flagged_below.push_back(at);
    geo_[r].push_back(m.geometric);
    flags_[r].push_back(run.inaccurate);
    mat_[r].push_back(m.matrix);
    return run;
  }

  /// The candidate at point K, on the very scene text, measured by the same code as qverify's runs; a failed
  /// call or a result beyond the accuracy target leaves a reproducer.
  StressRun candidate_run(std::size_t K, double v, const std::string& text, const Scene& sc, const ItemPoints& pts,
                          const Evaluation<Q>& ref) {
    const CandidateCall call = call_candidate(*cand_, sc, text, fam_.name + "-" + std::to_string(K));
    StressRun run;
    run.run = cand_->name;
    run.candidate = true;
    RunMeasure m;
    if (call.ok) {
      run.precision = call.results.precision;
      run.method = call.results.method;
      m = measure_run(fam_, call.results, pts, ref);
      run.frame = m.origin ? Frame::local : Frame::world;
      const std::string& claimed = fam_.reflection ? call.results.reflections[0].status : call.results.shadows[0].status;
      run.status = claimed.empty() ? std::string("unstated") : claimed;
    } else {
      run.status = "candidate-failed";
      run.failed_call = true;
      run.error = call.error;
    }
    run.seconds = call.seconds;
    run.matrix_error = m.matrix;
    run.geometric_error = m.geometric;
    run.item_geometric_error = m.item_geometric;
    run.beyond_accuracy = call.ok && !(m.item_geometric <= opt_.accuracy);
    if (call.ok) run.problems = check_problems(sc, call.results);  // as audit and verify --candidate judge it
    totals_->call_seconds.push_back(call.seconds);
    const bool bad = !call.ok || run.beyond_accuracy || !run.problems.empty();
    if (bad) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.3g", m.item_geometric);
      char tbuf[32];
      std::snprintf(tbuf, sizeof tbuf, "%.3g", opt_.accuracy);
      std::string reason = !call.ok ? "candidate-failed: " + call.error
                           : run.beyond_accuracy
                               ? std::string("item geometric error ") + (std::isfinite(m.item_geometric) ? buf : "infinite") +
                                     " of the object size exceeds the accuracy target " + tbuf
                               : std::string("a check failed");
      for (const std::string& p : run.problems) reason += "; " + p;
      const char* status = !call.ok ? "candidate-failed" : run.beyond_accuracy ? "beyond-accuracy" : "failed-checks";
      StressReproducer rep{write_reproducer(failures_dir_, cand_->name, fam_.name, K, v, text, call, reason), status,
                           m.item_geometric};
      run.reproducer = rep.written.scene;
      totals_->reproducers.push_back(std::move(rep));
      StressCandidateFamily& fc = *result_.candidate;
      if (!fc.breakdown_reason) fc.breakdown_reason = reason;
      (!call.ok ? fc.failed_calls : run.beyond_accuracy ? fc.beyond_accuracy : fc.failed_checks) += 1;
    }
    cand_failed_.push_back(!call.ok);
    cand_bad_.push_back(bad);
    geo_[specs_.size()].push_back(m.geometric);
    mat_[specs_.size()].push_back(m.matrix);
    return run;
  }

  /// What verify --candidate finds wrong in the candidate's item (its own samples, seed 1, the accuracy
  /// target): every problem of a failed check; none when it passes or has nothing to sample.
  std::vector<std::string> check_problems(const Scene& sc, const ResultSet& results) const {
    VerifyOptions vo{opt_.samples, 1, opt_.accuracy};
    vo.threads = 1;
    std::vector<std::string> out;
    for (const VerifyCheck& c : verify_results(sc, results, vo).checks) {
      if (c.passed() || c.skipped()) continue;
      if (!c.report) out.push_back(c.missing.empty() ? std::string("no result") : c.missing);
      else out.insert(out.end(), c.report->problems.begin(), c.report->problems.end());
    }
    return out;
  }

  /// The floor: the exact results correctly rounded to double in the default run's frame, measured as the
  /// runs are: P's (B's) error on these points, and the item's error as eval measures it (what it proves
  /// the rounding alone reaches, certified over the whole terminator or quadric where it certifies); the
  /// larger. (On these points alone the floor of a thin, long terminator is far below what its tips show.)
  double rounded_floor(const Evaluation<Q>& ref, const ItemPoints& pts, const std::optional<Vec3<Q>>& robust_origin) const {
    const Vec3<Q> o = robust_origin ? *robust_origin : Vec3<Q>::Zero();
    auto rounded = [](const auto& exact) { return rounded_scaled<double>(exact); };
    const AccuracyOptions eval_options;  // eval's defaults: its samples, its seed
    if (fam_.reflection) {
      const Mat4<double> B = rounded(quadric_to_local(ref.reflections[0].result.B, o));
      if (!all_finite(B)) return INFINITY;
      ReflectionMeter meter(ref.scene.A[0], ref.scene.planes[0], eval_options);
      return std::max(geometric_error(fam_, pts, robust_origin, exact_matrix(B)), meter(robust_origin, exact_matrix(B)).attained);
    }
    const ShadowResult<Q>& r = ref.shadows[0].result;
    const Mat4<double> P = rounded(quadric_to_local(r.P, o)), R = rounded(quadric_to_local(r.R, o));
    const Vec4<double> polar = rounded(Vec4<Q>(translation<Q>(o).transpose() * r.polar_plane));  // the plane in the frame
    if (!all_finite(P) || !all_finite(R) || !all_finite(polar)) return INFINITY;
    ShadowMeter meter(ref.scene.A[0], ref.scene.L[0], eval_options);
    const ItemAccuracy acc = meter(robust_origin, exact_matrix(P), exact_matrix(polar), exact_matrix(R));
    return std::max(geometric_error(fam_, pts, robust_origin, exact_matrix(P)), acc.attained);
  }

  const StressFamily& fam_;
  const StressOptions& opt_;
  const std::vector<RunSpec>& specs_;
  const Candidate* cand_;
  std::filesystem::path failures_dir_;
  std::optional<StressCandidateSummary>& totals_;  ///< the candidate's totals over every family (set with a candidate)
  StressFamilyResult result_;
  std::vector<std::vector<double>> geo_, mat_;  ///< per run (the candidate's last), per point
  std::vector<std::vector<bool>> flags_;        ///< per own run, per point: flagged inaccurate by eval
  std::vector<bool> cand_failed_, cand_bad_;    ///< per point: the call failed; failed or beyond the accuracy target
  std::vector<double> params_, predicted_, floors_;
};

}  // namespace

const std::vector<StressFamily>& stress_families() {
  static const std::vector<StressFamily> f = make_families();
  return f;
}

StressReport run_stress(const StressOptions& opt) {
  create_output_directory(opt.out_dir);  // before the sweeps: a bad --out fails at once
  const auto specs = run_specs();
  const std::filesystem::path failures_dir = std::filesystem::path(opt.out_dir) / "failures";
  StressReport report;
  if (opt.candidate) {
    remove_candidate_reproducers(failures_dir, opt.candidate->name);
    // who it was, without its function (which may hold another language's objects: they stay with the caller)
    const Candidate& c = *opt.candidate;
    report.candidate.emplace();
    report.candidate->candidate = Candidate{c.name, c.description, c.timeout_seconds, {}};
    report.candidate->accuracy = opt.accuracy;
  }
  for (const StressFamily& fam : stress_families()) {
    if (!opt.families.empty() && std::find(opt.families.begin(), opt.families.end(), fam.name) == opt.families.end())
      continue;
    if (opt.progress) opt.progress("stress: " + fam.name);
    FamilySweep sweep(fam, opt, specs, failures_dir, report.candidate);
    for (std::size_t K = opt.worst_only ? fam.values.size() - 1 : 0; K < fam.values.size(); ++K) sweep.point(K);
    sweep.summarize();
    report.plots.emplace_back(fam.name, sweep.plot());
    report.families.push_back(sweep.take_result());
  }
  return report;
}

}  // namespace qverify
