#include <qverify/exact/sampling.hpp>
#include <qverify/exact/statuses.hpp>
#include <qverify/verify/check.hpp>
#include <qverify/eval/frames.hpp>
#include <qverify/batch/batch.hpp>  // gather_sym
#include <qverify/batch/items.hpp>


#include <cmath>
#include <iomanip>
#include <stdexcept>
#include <limits>
#include <sstream>

namespace qverify {
namespace {

using Q = Rational;

double to_d(const Measure& m) { return m.convert_to<double>(); }
Measure mmax(const Measure& a, const Measure& b) { return a < b ? b : a; }
const Measure kInf = std::numeric_limits<Measure>::infinity();

template <int R, int C> Eigen::Matrix<Q, R, C> abs_matrix(const Eigen::Matrix<Q, R, C>& m) {
  return m.unaryExpr([](const Q& x) { return x < 0 ? Q(-x) : x; });
}

bool symmetric_within(const Mat4<Q>& X, const Measure& tol) {
  const Mat4<Q> d = X - X.transpose();
  const Q big = max_abs(X);
  if (tol == 0) return d.isZero();
  return !(to_measure(max_abs(d)) > tol * to_measure(big));
}

Measure inf_norm(const Mat4<Q>& m) {
  Measure best = 0;
  for (int i = 0; i < 4; ++i) {
    Measure s = 0;
    for (int j = 0; j < 4; ++j) s += abs(to_measure(m(i, j)));
    best = mmax(best, s);
  }
  return best;
}

/// A candidate's status against the exact inputs' (none given, or "non-finite", is not judged): the problem, or "".
std::string status_problem(const std::string& got, const std::string& exact) {
  if (got.empty() || got == exact || got == "non-finite") return "";
  return "status \"" + got + "\" but the exact inputs give \"" + exact + "\"";
}

/// One measured quadric, judged (exact: every point exactly on; else geometric error <= T).
QuadricCheck judged(std::string name, const Metric& m, const std::vector<RootPoint>& pts, const Measure& size, bool exact,
                    const Measure& T, bool judge = true) {
  QuadricCheck c;
  c.name = std::move(name);
  c.metric = m;
  const Measure r = relative(m, size);
  c.geometric_error = r < kInf ? to_d(r) : std::numeric_limits<double>::infinity();
  c.judged = judge;
  c.passed = exact ? m.all_zero : !(r > T);
  if (m.worst && *m.worst < pts.size()) {
    c.worst = pts[*m.worst];
    if (!CGAL::is_zero(c.worst->coords()[3])) c.worst_approx = c.worst->approx_cartesian();
  }
  return c;
}

std::string fmt_double(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}

/// A floating candidate's verdict over every point of its geometry (not only the samples): it fails
/// when a point is certainly beyond the target, and when the bound cannot bring it within.
void certify(CheckReport& rep, CertifiedBound cb, double T, std::vector<std::string> what, const Measure& sampled) {
  std::string names;
  for (const std::string& w : what) names += (names.empty() ? "" : " and ") + w;
  // (checked part by part before, CoveredBound::check) a bound of the Euclidean distance near a point
  // where the reference's gradient vanishes may be below a first-order distance sampled there: both count
  if (sampled > Measure(cb.upper))
    cb.upper = std::nextafter(sampled.convert_to<double>(), std::numeric_limits<double>::infinity());
  rep.certified = cb;
  rep.certified_for = std::move(what);
  if (cb.attained > T)
    rep.problems.push_back("certified: points of the geometry between the samples lie " + fmt_double(cb.attained) +
                           " of the object's size from " + names + ", beyond the accuracy target");
  else if (cb.upper > T)
    rep.problems.push_back("the geometric error of " + names + " is not certified within the accuracy target (bound " +
                           fmt_double(cb.upper) + " over every point, " + fmt_double(cb.attained) + " attained)");
  rep.geometric_error = std::max(rep.geometric_error, cb.attained);
}

std::string fmt_matrix(const Mat4<Q>& m) {
  std::ostringstream s;
  s << std::setprecision(17);
  for (int i = 0; i < 4; ++i) {
    s << (i ? "\n     [" : "    [[");
    for (int j = 0; j < 4; ++j) s << (j ? ", " : "") << to_d(to_measure(m(i, j)));
    s << (i == 3 ? "]]" : "]");
  }
  return s.str();
}

/// The centre of A's quadratic part, -K^-1 k, when K is invertible.
std::optional<Vec3<Q>> matrix_center(const Mat4<Q>& A) {
  const Mat3<Q> K = A.topLeftCorner<3, 3>();
  if (K.determinant() == 0) return std::nullopt;
  return Vec3<Q>(-(K.inverse() * Vec3<Q>(A.topRightCorner<3, 1>())));
}

/// A report's header: what is checked, in which mode (eps 0: proof), against which status.
CheckReport begin_report(const char* kind, const std::optional<Vec3<Q>>& origin, const std::string& status,
                         std::string exact_status, const CheckOptions& opt, const Measure& eps) {
  CheckReport rep;
  rep.kind = kind;
  rep.exact = eps == 0;
  rep.accuracy = rep.exact ? 0.0 : opt.accuracy;
  rep.origin = origin;
  rep.exact_status = std::move(exact_status);
  rep.item_status = status.empty() ? rep.exact_status : status;
  return rep;
}

}  // namespace

const QuadricCheck* CheckReport::find(const std::string& name) const {
  for (const QuadricCheck& c : checks)
    if (c.name == name) return &c;
  return nullptr;
}

const QuadricCheck* CheckReport::worst_check() const {
  const QuadricCheck* w = nullptr;
  for (const QuadricCheck& c : checks)
    if (c.judged && !c.passed && (!w || c.geometric_error > w->geometric_error)) w = &c;
  return w;
}

std::string CheckReport::summary() const {
  std::ostringstream s;
  s << kind << " check: " << (skipped ? "SKIPPED" : passed ? "passed" : "FAILED");
  if (exact)
    s << " (exact proof mode: every residual must be exactly zero; " << points << " exact points)\n";
  else
    s << " (accuracy target " << fmt_double(accuracy) << " relative to the object size " << fmt_double(object_size)
      << "; " << points << " exact points; geometric error " << fmt_double(geometric_error) << ")\n";
  for (const std::string& p : problems) s << "  - " << p << "\n";
  if (const QuadricCheck* w = worst_check(); w && w->worst_approx) {
    const Vec3<double>& x = *w->worst_approx;
    s << "  worst point (" << w->name << "): (" << std::setprecision(17) << x(0) << ", " << x(1) << ", " << x(2) << ")";
    if (origin) s << " in the frame with origin (" << (*origin)(0) << ", " << (*origin)(1) << ", " << (*origin)(2) << ")";
    const Measure dist = w->metric.distance;
    s << std::setprecision(6) << " lies " << to_d(dist) << " from the result (" << w->geometric_error
      << " object sizes; target " << fmt_double(accuracy) << ")\n";
  }
  // the expected matrices of what was checked and failed: P (or B) where it was measured, M where it is off
  const bool P_or_B = find(kind == "shadow" ? "on_P" : "on_B") || find("as_matrices");
  if (reference && !passed && !skipped && P_or_B)
    s << "  expected " << (kind == "shadow" ? "P = (L^T A L) A - (A L)(A L)^T" : "B = M^T A M")
      << " up to a positive factor (exact, rounded to double):\n" << fmt_matrix(*reference) << "\n";
  if (M_off)  // (M given: mirror_reference and M_error are set with it)
    s << "  M's largest entry off the reflection: " << fmt_double(*M_error)
      << " (relative to max(1, |M|max)); expected M (exact, rounded to double):\n" << fmt_matrix(*mirror_reference) << "\n";
  for (const std::string& n : notes) s << "  note: " << n << "\n";
  return s.str();
}

std::string exact_shadow_word(const Mat4<Q>& A, const Vec4<Q>& L, Method method) {
  StatusDecision status = exact_shadow_status(A, L);
  if (method == Method::paper && L(2) == 0) status.flags |= static_cast<unsigned>(ShadowFlag::singular_frame);
  ShadowResult<Q> r;
  r.flags = status.flags;
  return r.status();
}

std::string exact_reflection_word(const Mat4<Q>& A) { return exact_degenerate(A) ? "degenerate-quadric" : "ok"; }

Measure machine_epsilon(const Precision& p) {
  const std::optional<unsigned> bits = p.significand_bits();
  return bits ? ldexp(Measure(1), 1 - static_cast<int>(*bits)) : Measure(0);
}

namespace {
/// A check of results judged as matrices (as_matrices): their largest relative cross residual e against
/// the exact ones, zero exactly when proportional, within the target (exactly zero when exact).
QuadricCheck matrices_check(const Measure& e, bool exact, const Measure& T) {
  QuadricCheck c;
  c.name = "as_matrices";
  c.metric.residual = c.metric.distance = e;
  c.metric.all_zero = e == 0;
  c.geometric_error = to_d(e);
  c.passed = exact ? e == 0 : !(e > T);
  return c;
}
}  // namespace

CheckReport check_shadow_exact(const Mat4<Q>& Aw, const Vec4<Q>& Lw, const ExactShadowCandidate& got,
                               const CheckOptions& opt, const Measure& eps) {
  CheckReport rep = begin_report("shadow", got.origin, got.status, exact_shadow_word(Aw, Lw, opt.method), opt, eps);
  const bool exact = rep.exact;
  const Measure T = exact ? Measure(0) : Measure(opt.accuracy);
  const bool paper = opt.method == Method::paper;

  // Everything is judged in the frame the result is given in (local when it has an origin).
  const Vec3<Q> o = got.origin ? *got.origin : Vec3<Q>::Zero();
  const Mat4<Q> Ae = quadric_to_local(Aw, o);
  const Vec4<Q> Le = point_to_local(Lw, o);
  const Vec4<Q> pi_ref = Ae * Le;  // A L, computed here
  const Q s = Le.dot(pi_ref);
  const Mat4<Q> P_ref = s * Ae - pi_ref * pi_ref.transpose();
  rep.reference = P_ref;
  for (const auto& [name, is] : {std::pair<const char*, bool>{"A", got.A.has_value()}, {"P", got.P.has_value()},
                                 {"polar_plane", got.polar_plane.has_value()}, {"R", got.R.has_value()}})
    if (is) rep.given.emplace_back(name);
  // The same world points for every frame: sampled on the world terminator, then moved exactly.
  // The results' cross residual against the exact ones in the item's frame (shadow_matrix_error),
  // computed once: the exact proof mode and the matrices' check both judge it.
  std::optional<Measure> matrix_err;
  const auto matrix_error = [&] {
    if (!matrix_err)
      matrix_err = shadow_matrix_error(Ae, Le, got.P ? &*got.P : nullptr, got.polar_plane ? &*got.polar_plane : nullptr,
                                       got.R ? &*got.R : nullptr, Vec3<Q>(item_base(1, Aw, Lw) - o));
    return *matrix_err;
  };
  // What is judged without points: also where the terminator has none to sample.
  const auto point_free_checks = [&] {
    std::vector<std::string>& problems = rep.problems;
    if (got.P && !symmetric_within(*got.P, T)) problems.push_back("P is not symmetric");
    if (got.R && !symmetric_within(*got.R, T)) problems.push_back("R is not symmetric");
    for (std::string& sign : shadow_sign_problems(Ae, Le, got.P ? &*got.P : nullptr, got.polar_plane ? &*got.polar_plane : nullptr))
      problems.push_back(std::move(sign));
    for (std::string& zero : shadow_zero_problems(Ae, Le, got.P ? &*got.P : nullptr,
                                                  got.polar_plane ? &*got.polar_plane : nullptr, got.R ? &*got.R : nullptr))
      problems.push_back(std::move(zero));
    if (got.P && exact && !Vec4<Q>(*got.P * Le).isZero()) problems.push_back("P L != 0: L is not the apex of P");
    // Exact proof mode: P (the cone from L through the terminator), the polar plane and R (the plane
    // pair of the polar plane and h) are each unique up to a factor, so proportional to the exact ones,
    // whatever the samples: on points alone an exact R wrong everywhere but on the one chord that
    // --samples 1 draws passed (an R vanishing on the terminator only where a plane w meets it).
    if (exact && rep.exact_status == "ok" && (got.P || got.polar_plane || got.R) && matrix_error() != 0)
      problems.push_back("P, the polar plane or R is not proportional to the exact one (exact proof mode)");
    if (std::string status = status_problem(got.status, rep.exact_status); !status.empty()) problems.push_back(std::move(status));
  };
  // The results judged as matrices against the exact ones, up to a factor (the largest relative cross
  // residual, exactly): where the terminator is a single point, or has real points at infinity only.
  const auto as_matrices = [&](const char* where) {
    const QuadricCheck c = matrices_check(matrix_error(), exact, T);
    if (!c.passed)
      rep.problems.push_back(std::string("the terminator is ") + where +
                             ", where the results are judged as matrices: P, the polar plane or R " +
                             (exact ? "is not proportional to the exact one"
                                    : "differs from the exact one, up to a factor, by more than the accuracy target"));
    return c;
  };
  const ItemPoints pts = terminator_points(Aw, Lw, opt.samples, item_seed(opt.seed, 1, Aw, Lw));
  // A terminator whose real points all lie at infinity (a cylinder lit from inside: its axis's direction;
  // an imaginary cylinder's) has no finite point to measure a distance at: the results are judged as
  // matrices, as eval measures them (a candidate with P, the polar plane and R all wrong was skipped,
  // exit 0, and audit called it a pass; a right one was skipped too, and check_shadow's passed was
  // false: audit 31b F1). One without any real point (no-real-silhouette) has nothing to judge.
  // (A L = 0, a cylinder lit along its axis, takes this path too: P, the polar plane and R are then zero,
  // which the zero problems judge; a candidate without any of the three has nothing to judge)
  // (CheckOptions::judge_without_points: also one without any real point, for a pass or fail verdict)
  const bool none = pts.points.empty() && silhouette_empty<Q>(Aw, Lw) != Truth::no;  // (no real point at all)
  if (pts.points.empty() && (got.P || got.polar_plane || got.R) && (opt.judge_without_points || !none)) {
    const bool zero = pi_ref.isZero();
    const QuadricCheck c = as_matrices(zero ? "all of A (A L = 0)" : none ? "without a real point" : "real only at infinity");
    rep.checks.push_back(c);
    rep.geometric_error = c.geometric_error;
    point_free_checks();
    rep.notes.push_back(zero ? "A L = 0: the exact P, polar plane and R are zero, and so must the results be"
                             : std::string(none ? "the terminator has no real point" : "the terminator's real points all lie at infinity") +
                                   ": P, the polar plane and R are judged as matrices, by their largest relative cross "
                                   "residual against the exact ones (zero exactly when proportional), which must be within "
                                   "the accuracy target");
    rep.passed = rep.problems.empty();
    return rep;
  }
  if (pts.points.empty()) {
    point_free_checks();  // a wrong status, sign or zero fails; else nothing to judge: skipped
    if (rep.problems.empty()) {
      rep.skipped = true;
      // (status ok with no point and no result given: real points at infinity only, nothing to judge)
      rep.problems.push_back(rep.exact_status == "ok"
                                 ? "the terminator has no real finite point to sample (its real points lie at infinity), "
                                   "and no P, polar plane or R is given to judge as matrices"
                                 : "the terminator has no real point to sample (exact status: " + rep.exact_status + ")");
    }
    return rep;
  }
  rep.points = pts.points.size();
  rep.exhausted = pts.exhausted;
  rep.object_size = to_d(pts.size);
  const std::vector<RootPoint> local = in_frame(pts.points, got.origin);
  std::vector<std::string>& problems = rep.problems;
  auto judge = [&](const QuadricCheck& c, const char* what) {
    if (!c.passed)
      problems.push_back(std::string(what) + (exact ? ": a point is not exactly on the result"
                                                    : ": geometric error beyond the accuracy target"));
  };
  if (got.A) rep.checks.push_back(judged("on_A", measure_quadric(local, *got.A), local, pts.size, exact, T, false));
  std::optional<QuadricCheck> onP, onR, onPolar, onGen, onPlane, asMatrices;
  // A terminator of one point says nothing of the results' shapes (single_point): they are judged
  // as matrices against the exact ones, up to a factor, instead of on points.
  const bool one_point = single_point(Aw, Lw, pts.points);
  if (one_point) asMatrices = as_matrices("a single point");
  // (at a single point they are measured as information only)
  if (got.P) {  // (not at A's singular points, where P's gradient vanishes: ItemPoints::singular)
    const std::vector<RootPoint> at = P_points(local, pts);
    onP = judged("on_P", measure_quadric(at, *got.P), at, pts.size, exact, T, !one_point);
    if (at.empty() && !one_point)
      rep.notes.push_back("P is measured on no terminator point: every point sampled is the cone's apex, where P's "
                          "gradient vanishes (take more samples)");
  }
  if (got.R) {  // (not on R's second plane, where its gradient vanishes: ItemPoints::crossing)
    const std::vector<RootPoint> at = R_points(local, pts);
    onR = judged("on_R", measure_quadric(at, *got.R), at, pts.size, exact, T, !one_point);
    if (at.empty() && !local.empty() && !one_point)
      rep.notes.push_back("R is measured on no terminator point: every point sampled lies on R's second plane h, "
                          "where R's gradient vanishes (R is still checked on h and, where certified, over the "
                          "whole terminator)");
  }
  if (got.polar_plane)
    onPolar = judged("on_polar_plane", measure_plane(local, *got.polar_plane), local, pts.size, exact, T, !one_point);
  if (got.P && !one_point) {  // P is *the* cone with apex L: exact points of its generator lines
    const auto gen = in_frame(pts.generators, got.origin);
    onGen = judged("on_generators", measure_quadric(gen, *got.P), gen, pts.size, exact, T);
  }
  if (got.R && !one_point) {  // R contains the polar plane (the plane S carried back, read as a quadric): points of the plane off A
    const auto pl = in_frame(pts.plane, got.origin);
    onPlane = judged("R_on_polar_plane", measure_quadric(pl, *got.R), pl, pts.size, exact, T);
  }
  for (auto* c : {&onP, &onR, &onPolar, &onGen, &onPlane, &asMatrices})
    if (*c) rep.checks.push_back(**c);
  if (onP && onP->judged) judge(*onP, "on_P");
  if (onR && onR->judged) judge(*onR, "on_R");
  if (onPolar && onPolar->judged) judge(*onPolar, "on_polar_plane");
  if (onGen) judge(*onGen, "on_generators (P is not the cone from L through the terminator)");
  if (onPlane) judge(*onPlane, "R on the polar plane");
  Measure h_err = 0;  // R on its second plane
  if (got.R) {  // (also at a single point: the matrices' cross residual does not see h's height off)
    bool h_zero = true;
    h_err = second_plane_error(local, pts.size, Ae, Le, *got.R, h_zero);  // (accuracy.hpp)
    rep.second_plane_error = h_err < kInf ? to_d(h_err) : std::numeric_limits<double>::infinity();
    if (exact ? !h_zero : h_err > T)
      problems.push_back("R does not contain the plane h that the paper's frame sends to infinity (R must be the plane "
                         "pair polar plane + h)");
  }
  point_free_checks();

  // The rounding verdict of earlier versions, kept as information.
  Measure kappa = 1;
  if (!exact) {
    const Mat4<Q> absA = abs_matrix(Ae);
    const Vec4<Q> absL = abs_matrix(Le);
    const Vec4<Q> absAL = absA * absL;
    const Mat4<Q> Pabs = absL.dot(absAL) * absA + absAL * absAL.transpose();
    const Vec4<Q> h = reference_second_plane(Le);
    const Mat4<Q> Rabs = abs_matrix(Vec4<Q>(h)) * absAL.transpose() + absAL * abs_matrix(h).transpose();
    const Mat4<Q> Rref = h * pi_ref.transpose() + pi_ref * h.transpose();
    const Measure nP = frobenius(P_ref), nR = frobenius(Rref), nPi = frobenius(pi_ref);
    if (nP > 0) kappa = mmax(kappa, Measure(frobenius(Pabs) / nP));
    if (nR > 0) kappa = mmax(kappa, Measure(frobenius(Rabs) / nR));
    if (nPi > 0) kappa = mmax(kappa, Measure(frobenius(absAL) / nPi));
    if (paper && Lw(2) != 0) {
      const PaperFrame<Q> f = paper_frame<Q>(Lw);
      const Measure cond = inf_norm(Mat4<Q>(f.T * f.M)) * inf_norm(Mat4<Q>(f.Minv * f.Tinv));
      kappa *= cond * cond;
    }
  }
  const Measure tol = 64 * eps * kappa;
  rep.consistent_with_precision = true;
  for (const auto* c : {&onP, &onR, &onPolar})
    if (*c) rep.consistent_with_precision &= exact ? (*c)->metric.all_zero : !((*c)->metric.residual > tol);
  if (exact)
    for (const RootPoint& x : local)
      if ((!got.A || CGAL::is_zero(x.form(*got.A))) && (!got.P || CGAL::is_zero(x.form(*got.P))) &&
          (!got.R || CGAL::is_zero(x.form(*got.R))))
        ++rep.proved_exactly;
  rep.rounding_tolerance = to_d(tol);
  rep.kappa = to_d(kappa);
  // The geometric error (cli.md): P, the polar plane and R on the terminator. The checks of their
  // shapes (P on its generator lines, R on the polar plane and on h) are judged beside it, each in its
  // own entry, and fail the check on their own.
  Measure geo = 0;
  for (const auto* c : {&onP, &onPolar, &onR})
    if (*c && (*c)->judged) geo = mmax(geo, relative((*c)->metric, pts.size));
  if (asMatrices) geo = mmax(geo, asMatrices->metric.distance);
  rep.geometric_error = geo < kInf ? to_d(geo) : std::numeric_limits<double>::infinity();
  if (pts.exhausted) rep.notes.push_back("only " + std::to_string(pts.points.size()) + " real point(s) found on this terminator");
  if (one_point)
    rep.notes.push_back("the terminator is a single real point, which says nothing of the results' shapes: P, the polar "
                        "plane and R are judged as matrices, by their largest relative cross residual against the exact "
                        "ones (zero exactly when proportional), which must be within the accuracy target");
  if (!exact && !one_point && (got.P || got.polar_plane || got.R)) {
    // the certified bound over every point of what it covers (ShadowBounds), never below the errors
    // measured on the same parts' sample points
    const ShadowBounds bounds(Aw, Lw, pts);
    const ShadowCover& c = bounds.cover();
    const Mat4<Q>* P = got.P && c.P ? &*got.P : nullptr;
    const Vec4<Q>* polar = got.polar_plane && c.polar ? &*got.polar_plane : nullptr;
    const Mat4<Q>* R = got.R && c.R ? &*got.R : nullptr;
    Measure sampled = 0;
    if (P) sampled = relative(onP->metric, pts.size);
    if (polar) sampled = mmax(sampled, relative(onPolar->metric, pts.size));
    if (R) sampled = mmax(sampled, relative(onR->metric, pts.size));
    if (P || polar || R) {
      CoveredBound b = bounds(got.origin, P, polar, R, size_down(pts.size), opt.accuracy);
      b.check([&](const std::string& n) {
        const auto at = [&](const std::optional<QuadricCheck>& c) { return c ? relative(c->metric, pts.size) : Measure(0); };
        if (n == "P") return at(onP);
        if (n == "polar_plane") return at(onPolar);
        return at(onR);
      });
      if (!b.certified.empty()) certify(rep, b.bound, opt.accuracy, std::move(b.certified), sampled);
    }
  }
  rep.passed = problems.empty();
  return rep;
}

CheckReport check_reflection_exact(const Mat4<Q>& Aw, const Vec4<Q>& plane, const ExactReflectionCandidate& got,
                                   const CheckOptions& opt, const Measure& eps, const std::optional<Vec3<Q>>& center) {
  CheckReport rep = begin_report("reflection", got.origin, got.status, exact_reflection_word(Aw), opt, eps);
  const bool exact = rep.exact;
  const Measure T = exact ? Measure(0) : Measure(opt.accuracy);
  const bool paper = opt.method == Method::paper;
  const Mat4<Q> Mw = reference_mirror(plane);  // written out here, not the core's
  const Vec3<Q> o = got.origin ? *got.origin : Vec3<Q>::Zero();
  // M and B of the reference, in the result's frame: M_local = T^-1 M T, B_local = T^T M^T A M T.
  const Mat4<Q> M_ref = translation<Q>(Vec3<Q>(-o)) * Mw * translation<Q>(o);
  if (got.M) rep.mirror_reference = M_ref;
  if (got.M) rep.given.emplace_back("M");
  if (got.B) rep.given.emplace_back("B");
  const Mat4<Q> B_ref = quadric_to_local(Mat4<Q>(Mw.transpose() * Aw * Mw), o);
  rep.reference = B_ref;
  // B's cross residual against M^T A M about the item's base point, computed once (the exact proof
  // mode and the matrices' check both judge it; got.B given).
  std::optional<Measure> B_err;
  const auto B_error = [&] {
    if (!B_err) B_err = reflection_matrix_error(*got.B, B_ref, reflected_item_base(Aw, plane, got.origin));
    return *B_err;
  };
  // What is judged without points: also where the quadric has none to sample.
  Measure m_err = 0;
  const auto point_free_checks = [&] {
    std::vector<std::string>& problems = rep.problems;
    if (got.M) {  // M must be the reflection (exactly, or within the accuracy target relative to its largest entry)
      m_err = mirror_error(*got.M, M_ref);  // (accuracy.hpp: eval's bound counts the same)
      rep.M_error = to_d(m_err);
      rep.M_off = exact ? *got.M != M_ref : m_err > T;
      if (rep.M_off) problems.push_back("M is not the reflection in the mirror plane");
    }
    // Exact proof mode: B is M^T A M up to a factor, whatever the samples (as for a shadow's results)
    if (exact && rep.exact_status == "ok" && got.B && B_error() != 0)
      problems.push_back("B is not proportional to M^T A M (exact proof mode)");
    if (got.B && !symmetric_within(*got.B, T)) problems.push_back("B is not symmetric");
    if (got.B)
      for (std::string p : {reflection_zero_problem(Aw, *got.B), reflection_real_points_problem(Aw, *got.B),
                            reflection_sign_problem(*got.B, B_ref)})
        if (!p.empty()) problems.push_back(std::move(p));
    if (std::string status = status_problem(got.status, rep.exact_status); !status.empty()) problems.push_back(std::move(status));
  };
  const ItemPoints pts = reflected_points(Aw, Mw, opt.samples, item_seed(opt.seed, 2, Aw, plane));
  // real points at infinity only (an imaginary cylinder): B against the exact one as a matrix, as eval
  // measures it (a B off by 7x in one entry was skipped, and audit called it a pass: audit 31b F1)
  // (CheckOptions::judge_without_points: also one without any real point, for a pass or fail verdict)
  if (pts.points.empty() && got.B && (opt.judge_without_points || !without_real_points(Aw))) {
    const std::string where = Aw.isZero()                ? "the quadric is zero (every point lies on it: none to sample)"
                              : without_real_points(Aw) ? "the quadric has no real point"
                                                        : "the quadric's real points all lie at infinity";
    const QuadricCheck c = matrices_check(B_error(), exact, T);
    if (!c.passed)
      rep.problems.push_back(where + ", where B is judged as a matrix: B " +
                             (exact ? "is not proportional to M^T A M"
                                    : "differs from M^T A M, up to a factor, by more than the accuracy target"));
    rep.checks.push_back(c);
    rep.geometric_error = c.geometric_error;
    point_free_checks();
    rep.notes.push_back(where + ": B is judged as a matrix, by its relative cross residual against M^T A M (zero exactly "
                                "when proportional), which must be within the accuracy target");
    rep.passed = rep.problems.empty();
    return rep;
  }
  if (pts.points.empty() && opt.judge_without_points) {  // (M alone: judged without points)
    point_free_checks();
    rep.passed = rep.problems.empty();
    return rep;
  }
  if (pts.points.empty()) {
    point_free_checks();  // a wrong status, sign, zero or M fails; else nothing to judge: skipped
    if (rep.problems.empty()) {
      rep.skipped = true;
      rep.problems.push_back("the quadric has no real point to sample");
    }
    return rep;
  }
  rep.points = pts.points.size();
  rep.exhausted = pts.exhausted;
  rep.object_size = to_d(pts.size);
  const std::vector<RootPoint> local = in_frame(pts.points, got.origin);
  std::vector<std::string>& problems = rep.problems;
  if (got.B) {
    rep.checks.push_back(judged("on_B", measure_quadric(local, *got.B), local, pts.size, exact, T));
    if (!rep.checks.back().passed)
      problems.push_back(exact ? "on_B: a reflected point is not exactly on B" : "on_B: geometric error beyond the accuracy target");
  }
  point_free_checks();

  Measure kappa = 1;
  if (!exact) {
    // Conditioning of B in its own frame: B_local = G^T A_c G with A_c the quadric in the frame of its
    // own centre c (else the point of its core eval's frame is about, quadric_base) and
    // G = T_c^-1 M T_o mapping the image frame into it.
    const Vec3<Q> cc = center ? *center : Vec3<Q>(quadric_base(Aw).head<3>());
    const Mat4<Q> G = translation<Q>(Vec3<Q>(-cc)) * Mw * translation<Q>(o);
    const Mat4<Q> absG = abs_matrix(G);
    const Measure nB = frobenius(B_ref);
    if (nB > 0)
      kappa = mmax(kappa, Measure(frobenius(Mat4<Q>(absG.transpose() * abs_matrix(quadric_to_local(Aw, cc)) * absG)) / nB));
    const Measure m = inf_norm(G);
    kappa *= paper ? m * m * m * m : m * m;
  }
  const Measure tol = 64 * eps * kappa;
  if (exact && got.B)
    for (const RootPoint& y : local)
      if (CGAL::is_zero(y.form(*got.B))) ++rep.proved_exactly;
  const QuadricCheck* onB = rep.find("on_B");
  rep.geometric_error = onB ? onB->geometric_error : 0;
  if (!exact && got.B)
    if (const ReflectionBounds bounds(Aw, Mw, pts); bounds.covers()) {
      CoveredBound b = bounds(got.origin, *got.B, size_down(pts.size), opt.accuracy);
      b.check([&](const std::string&) { return relative(onB->metric, pts.size); });
      certify(rep, b.bound, opt.accuracy, std::move(b.certified), relative(onB->metric, pts.size));
    }
  rep.consistent_with_precision = exact ? (!onB || onB->metric.all_zero) && (!got.M || *got.M == M_ref)
                                        : !(onB && onB->metric.residual > tol) && !(m_err > tol);
  rep.rounding_tolerance = to_d(tol);
  rep.kappa = to_d(kappa);
  rep.passed = problems.empty();
  return rep;
}

CheckReport check_reflection_exact(const Mat4<Q>& A, const Vec4<Q>& plane, const ExactReflectionCandidate& c,
                                   const CheckOptions& opt, const Measure& eps) {
  return check_reflection_exact(A, plane, c, opt, eps, matrix_center(A));
}

// ------------------------------------------------------------------ inputs

namespace {
/// Machine epsilon of the scalar a candidate was computed in (0: exact, proof
/// mode); an interval's results are judged at their midpoints, doubles.
template <class S> Measure epsilon_of() {
  if constexpr (std::is_same_v<S, Interval>) return machine_epsilon(Precision{Precision::Kind::interval});
  else return to_measure(exact_value(S(Eigen::NumTraits<S>::epsilon())));
}

std::string entry_name(const std::string& name, Eigen::Index i, Eigen::Index j, bool vector) {
  return vector ? name + "[" + std::to_string(i) + "]" : name + "[" + std::to_string(i) + "][" + std::to_string(j) + "]";
}
}  // namespace

void validate_quadric(const Mat4<Q>& A, const std::string& where, const std::string& name) {
  // A pair that differs is named at its entry below the diagonal (A[3][1] for the pair (1, 3)), the
  // message gives both. The zero matrix is no error: it is a degenerate quadric (status
  // degenerate-quadric), as in a scene.
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (A(i, j) != A(j, i))
        throw InputError(where, entry_name(name, j, i, false),
                         "not symmetric: " + name + "[" + std::to_string(j) + "][" + std::to_string(i) + "] = " +
                             A(j, i).str() + " but " + name + "[" + std::to_string(i) + "][" + std::to_string(j) +
                             "] = " + A(i, j).str() + " (a quadric's matrix is symmetric)");
}

void validate_light(const Vec4<Q>& L, const std::string& where, const std::string& name) {
  if (L.isZero()) throw InputError(where, name, "the light (0, 0, 0, 0) is no point: give (x, y, z, 1) or a direction (v, 0)");
}

void validate_plane(const Vec4<Q>& p, const std::string& where, const std::string& name) {
  if (p.head<3>().isZero()) throw InputError(where, name, "the mirror plane has a zero normal (a, b, c)");
}

namespace detail {
template <class S, int R, int C>
Eigen::Matrix<Q, R, C> exact_checked(const Eigen::Matrix<S, R, C>& m, const std::string& where, const std::string& name) {
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      if (!ScalarOps<S>::finite(m(i, j)))
        throw InputError(where, entry_name(name, i, j, C == 1), "not a finite number (NaN or infinite)");
  return exact_matrix(m);
}
}  // namespace detail

namespace {
/// The options every check takes: a positive finite accuracy target, 1 to kMaxSamples samples.
void validate_options(const CheckOptions& opt, const std::string& where) {
  if (!(opt.accuracy > 0) || !std::isfinite(opt.accuracy))
    throw InputError(where, "accuracy", "the accuracy target must be a positive number");
  if (opt.samples < 1 || opt.samples > kMaxSamples)
    throw InputError(where, "samples",
                     "expected 1 to " + std::to_string(kMaxSamples) + " sample points, found " + std::to_string(opt.samples));
}
}  // namespace

namespace {

/// The exact inputs of one shadow check, validated (InputError at `where`,
/// the argument named `prefix` + its name: "A[0][1]", or "[7].A[0][1]" for
/// item 7 of a batch).
struct ShadowInputs {
  Mat4<Q> A;
  Vec4<Q> L;
  ExactShadowCandidate c;
};
struct ReflectionInputs {
  Mat4<Q> A;
  Vec4<Q> plane;
  ExactReflectionCandidate c;
};

template <class S>
ShadowInputs shadow_inputs(const Mat4<S>& A, const Vec4<S>& L, const ShadowCandidate<S>& c, const std::string& where,
                           const std::string& prefix) {
  ShadowInputs in;
  in.A = detail::exact_checked(A, where, prefix + "A");
  in.L = detail::exact_checked(L, where, prefix + "L");
  validate_quadric(in.A, where, prefix + "A");
  validate_light(in.L, where, prefix + "L");
  if (!c.P && !c.polar_plane && !c.R)
    throw InputError(where, prefix + "candidate", "nothing to check: give P, polar_plane or R");
  if (c.P) in.c.P = detail::exact_checked(*c.P, where, prefix + "P");
  if (c.polar_plane) in.c.polar_plane = detail::exact_checked(*c.polar_plane, where, prefix + "polar_plane");
  if (c.R) in.c.R = detail::exact_checked(*c.R, where, prefix + "R");
  if (c.origin) in.c.origin = detail::exact_checked(*c.origin, where, prefix + "origin");
  if (c.A) in.c.A = detail::exact_checked(*c.A, where, prefix + "candidate.A");
  in.c.status = c.status;
  return in;
}

template <class S>
ReflectionInputs reflection_inputs(const Mat4<S>& A, const Vec4<S>& plane, const ReflectionCandidate<S>& c,
                                   const std::string& where, const std::string& prefix) {
  ReflectionInputs in;
  in.A = detail::exact_checked(A, where, prefix + "A");
  in.plane = detail::exact_checked(plane, where, prefix + "plane");
  validate_quadric(in.A, where, prefix + "A");
  validate_plane(in.plane, where, prefix + "plane");
  if (!c.M && !c.B) throw InputError(where, prefix + "candidate", "nothing to check: give M or B");
  if (c.M) in.c.M = detail::exact_checked(*c.M, where, prefix + "M");
  if (c.B) in.c.B = detail::exact_checked(*c.B, where, prefix + "B");
  if (c.origin) in.c.origin = detail::exact_checked(*c.origin, where, prefix + "origin");
  in.c.status = c.status;
  return in;
}

/// Every item's inputs validated before anything is computed, then the checks
/// on threads (each item as check_shadow / check_reflection would check it alone).
template <class Inputs, class Make, class Check>
std::vector<CheckReport> batch_of_checks(std::size_t n, const BatchCheckOptions& opt, const std::string& where, Make make,
                                         Check check) {
  validate_options(opt.check, where);
  if (opt.threads < 0) throw InputError(where, "threads", "expected 0 (one per processor) or more threads, found " + std::to_string(opt.threads));
  std::vector<Inputs> in;
  in.reserve(n);
  for (std::size_t k = 0; k < n; ++k) in.push_back(make(k, "[" + std::to_string(k) + "]."));
  std::vector<CheckReport> out(n);
  for_each_item(n, opt.threads, opt.progress, [&](std::size_t k) { out[k] = check(in[k]); });
  return out;
}

void same_count(std::size_t n, std::size_t m, const std::string& where, const std::string& name) {
  if (m != n)
    throw InputError(where, name, std::to_string(m) + " items where the quadrics A give " + std::to_string(n) +
                                      ": every argument needs one entry per item");
}

}  // namespace

template <class S> CheckReport check_shadow(const Mat4<S>& A, const Vec4<S>& L, const ShadowCandidate<S>& c, const CheckOptions& opt) {
  const std::string where = "check_shadow";
  validate_options(opt, where);
  const ShadowInputs in = shadow_inputs(A, L, c, where, "");
  return check_shadow_exact(in.A, in.L, in.c, opt, epsilon_of<S>());
}

template <class S>
CheckReport check_reflection(const Mat4<S>& A, const Vec4<S>& plane, const ReflectionCandidate<S>& c, const CheckOptions& opt) {
  const std::string where = "check_reflection";
  validate_options(opt, where);
  const ReflectionInputs in = reflection_inputs(A, plane, c, where, "");
  return check_reflection_exact(in.A, in.plane, in.c, opt, epsilon_of<S>());
}

namespace {
/// check_shadows under the name of the function the caller called (its errors name it).
template <class S>
std::vector<CheckReport> named_shadow_checks(const std::string& where, const std::vector<Mat4<S>>& A,
                                             const std::vector<Vec4<S>>& L, const std::vector<ShadowCandidate<S>>& c,
                                             const BatchCheckOptions& opt) {
  same_count(A.size(), L.size(), where, "L");
  same_count(A.size(), c.size(), where, "candidates");
  return batch_of_checks<ShadowInputs>(
      A.size(), opt, where, [&](std::size_t k, const std::string& prefix) { return shadow_inputs(A[k], L[k], c[k], where, prefix); },
      [&](const ShadowInputs& in) { return check_shadow_exact(in.A, in.L, in.c, opt.check, epsilon_of<S>()); });
}

/// check_reflections under the name of the function the caller called.
template <class S>
std::vector<CheckReport> named_reflection_checks(const std::string& where, const std::vector<Mat4<S>>& A,
                                                 const std::vector<Vec4<S>>& planes,
                                                 const std::vector<ReflectionCandidate<S>>& c, const BatchCheckOptions& opt) {
  same_count(A.size(), planes.size(), where, "planes");
  same_count(A.size(), c.size(), where, "candidates");
  return batch_of_checks<ReflectionInputs>(
      A.size(), opt, where,
      [&](std::size_t k, const std::string& prefix) { return reflection_inputs(A[k], planes[k], c[k], where, prefix); },
      [&](const ReflectionInputs& in) { return check_reflection_exact(in.A, in.plane, in.c, opt.check, epsilon_of<S>()); });
}
}  // namespace

template <class S>
std::vector<CheckReport> check_shadows(const std::vector<Mat4<S>>& A, const std::vector<Vec4<S>>& L,
                                       const std::vector<ShadowCandidate<S>>& c, const BatchCheckOptions& opt) {
  return named_shadow_checks("check_shadows", A, L, c, opt);
}

template <class S>
std::vector<CheckReport> check_reflections(const std::vector<Mat4<S>>& A, const std::vector<Vec4<S>>& planes,
                                           const std::vector<ReflectionCandidate<S>>& c, const BatchCheckOptions& opt) {
  return named_reflection_checks("check_reflections", A, planes, c, opt);
}

namespace {
void same_rows(Eigen::Index n, Eigen::Index m, const std::string& where, const std::string& name) {
  if (m != n)
    throw InputError(where, name, std::to_string(m) + " rows where A has " + std::to_string(n) +
                                      ": one row per item (an empty batch: that result is not checked)");
}
}  // namespace

std::vector<CheckReport> check_shadow_batch(const SymBatch<double>& A, const Vec4Batch<double>& L,
                                            const SymBatch<double>& P, const Vec4Batch<double>& polar_plane,
                                            const SymBatch<double>& R, const BatchCheckOptions& opt,
                                            const std::vector<std::string>& status) {
  const std::string where = "check_shadow_batch";
  const Eigen::Index n = A.rows();
  same_rows(n, L.rows(), where, "L");
  if (!status.empty()) same_rows(n, static_cast<Eigen::Index>(status.size()), where, "status");
  if (n == 0 && P.rows() + polar_plane.rows() + R.rows() == 0)  // no items: nothing to check, no error (options checked)
    return named_shadow_checks<double>(where, {}, {}, {}, opt);
  if (P.rows() + polar_plane.rows() + R.rows() == 0) throw InputError(where, "candidate", "nothing to check: give P, polar_plane or R");
  if (P.rows()) same_rows(n, P.rows(), where, "P");
  if (polar_plane.rows()) same_rows(n, polar_plane.rows(), where, "polar_plane");
  if (R.rows()) same_rows(n, R.rows(), where, "R");
  std::vector<Mat4<double>> As(static_cast<std::size_t>(n));
  std::vector<Vec4<double>> Ls(static_cast<std::size_t>(n));
  std::vector<ShadowCandidate<double>> cs(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    As[u] = gather_sym(A, i);
    Ls[u] = L.row(i).transpose();
    if (P.rows()) cs[u].P = gather_sym(P, i);
    if (polar_plane.rows()) cs[u].polar_plane = Vec4<double>(polar_plane.row(i).transpose());
    if (R.rows()) cs[u].R = gather_sym(R, i);
    if (!status.empty()) cs[u].status = status[u];
  }
  return named_shadow_checks(where, As, Ls, cs, opt);
}

std::vector<CheckReport> check_reflection_batch(const SymBatch<double>& A, const Vec4Batch<double>& planes,
                                                const AffineBatch<double>& M, const SymBatch<double>& B,
                                                const BatchCheckOptions& opt, const std::vector<std::string>& status) {
  const std::string where = "check_reflection_batch";
  const Eigen::Index n = A.rows();
  same_rows(n, planes.rows(), where, "planes");
  if (!status.empty()) same_rows(n, static_cast<Eigen::Index>(status.size()), where, "status");
  if (n == 0 && M.rows() + B.rows() == 0)  // no items: nothing to check, no error (options checked)
    return named_reflection_checks<double>(where, {}, {}, {}, opt);
  if (M.rows() + B.rows() == 0) throw InputError(where, "candidate", "nothing to check: give M or B");
  if (M.rows()) same_rows(n, M.rows(), where, "M");
  if (B.rows()) same_rows(n, B.rows(), where, "B");
  std::vector<Mat4<double>> As(static_cast<std::size_t>(n));
  std::vector<Vec4<double>> Ps(static_cast<std::size_t>(n));
  std::vector<ReflectionCandidate<double>> cs(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    As[u] = gather_sym(A, i);
    Ps[u] = planes.row(i).transpose();
    if (M.rows()) {
      Mat4<double> m = Mat4<double>::Identity();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) m(r, c) = M(i, 4 * r + c);
      cs[u].M = m;
    }
    if (B.rows()) cs[u].B = gather_sym(B, i);
    if (!status.empty()) cs[u].status = status[u];
  }
  return named_reflection_checks(where, As, Ps, cs, opt);
}

#define QVERIFY_CHECK_INSTANTIATE(S)                                                                              \
  template CheckReport check_shadow<S>(const Mat4<S>&, const Vec4<S>&, const ShadowCandidate<S>&, const CheckOptions&); \
  template CheckReport check_reflection<S>(const Mat4<S>&, const Vec4<S>&, const ReflectionCandidate<S>&,               \
                                           const CheckOptions&);                                                        \
  template std::vector<CheckReport> check_shadows<S>(const std::vector<Mat4<S>>&, const std::vector<Vec4<S>>&,          \
                                                     const std::vector<ShadowCandidate<S>>&, const BatchCheckOptions&); \
  template std::vector<CheckReport> check_reflections<S>(const std::vector<Mat4<S>>&, const std::vector<Vec4<S>>&,      \
                                                         const std::vector<ReflectionCandidate<S>>&,                  \
                                                         const BatchCheckOptions&);
QVERIFY_CHECK_INSTANTIATE(float)
QVERIFY_CHECK_INSTANTIATE(double)
QVERIFY_CHECK_INSTANTIATE(long double)
QVERIFY_CHECK_INSTANTIATE(Float128)
QVERIFY_CHECK_INSTANTIATE(Mpfr)
QVERIFY_CHECK_INSTANTIATE(Interval)
QVERIFY_CHECK_INSTANTIATE(Rational)
#undef QVERIFY_CHECK_INSTANTIATE

}  // namespace qverify
