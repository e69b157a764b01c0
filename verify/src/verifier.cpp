#include <qverify/exact/number_text.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/verify/json_tree.hpp>
#include <qverify/verify/frames.hpp>
#include <qverify/verify/verifier.hpp>
#include <qverify/verify/accuracy.hpp>
#include <qverify/exact/statuses.hpp>

#include <limits>

namespace qverify {
namespace {

using Q = Rational;
using json = nlohmann::ordered_json;

double to_d(const Measure& m) { return m.convert_to<double>(); }
Measure max(const Measure& a, const Measure& b) { return a < b ? b : a; }

template <int R, int C> Eigen::Matrix<Q, R, C> abs_matrix(const Eigen::Matrix<Q, R, C>& m) {
  return m.unaryExpr([](const Q& x) { return x < 0 ? Q(-x) : x; });
}

/// Machine epsilon of a precision (0 for exact).
Measure epsilon_of(const Precision& p) {
  switch (p.kind) {
    case Precision::Kind::f32: return ldexp(Measure(1), -23);
    case Precision::Kind::f64:
    case Precision::Kind::interval: return ldexp(Measure(1), -52);
    case Precision::Kind::f80: return ldexp(Measure(1), -63);
    case Precision::Kind::f128: return ldexp(Measure(1), -112);
    case Precision::Kind::mpfr: return ldexp(Measure(1), 1 - static_cast<int>(set_mpfr_bits(p.bits)));
    case Precision::Kind::exact: return Measure(0);
  }
  return Measure(0);
}

/// Sign of the entry of X at the pivot (largest entry) of the reference.
template <int R, int C> bool same_orientation(const Eigen::Matrix<Q, R, C>& X, const Eigen::Matrix<Q, R, C>& ref) {
  const Eigen::Index p = pivot_index(ref);
  return sign_of<Q>(X(p)) == sign_of<Q>(ref(p));
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
    best = max(best, s);
  }
  return best;
}

json check_header(const char* kind, const std::string& quadric, const char* other_key, const std::string& other) {
  json j;
  j["kind"] = kind;
  j["quadric"] = quadric;
  j[other_key] = other;
  return j;
}

}  // namespace

namespace {

json metric_json(const Metric& m, const Measure& size) {
  json j{{"max_residual", to_d(m.residual)}, {"max_distance", m.singular ? json(nullptr) : json(to_d(m.distance))}};
  const Measure r = relative(m, size);
  j["geometric_error"] = r < std::numeric_limits<Measure>::infinity() ? json(to_d(r)) : json(nullptr);
  if (m.singular) j["note"] = "a point lies off the result where its gradient vanishes: no first-order distance";
  return j;
}

/// y^T X y.
Q form(const Mat4<Q>& X, const Vec4<Q>& y) { return y.dot(X * y); }

/// Test points e_i and e_i +- e_j: for a non-zero symmetric X one of them has
/// |y^T X y| >= |X|_max, so the sign there is robust to small errors of X.
std::vector<Vec4<Q>> sign_probes() {
  std::vector<Vec4<Q>> ys;
  for (int i = 0; i < 4; ++i) {
    ys.push_back(Vec4<Q>::Unit(i));
    for (int j = i + 1; j < 4; ++j) {
      ys.push_back(Vec4<Q>(Vec4<Q>::Unit(i) + Vec4<Q>::Unit(j)));
      ys.push_back(Vec4<Q>(Vec4<Q>::Unit(i) - Vec4<Q>::Unit(j)));
    }
  }
  return ys;
}

/// Does `got` have the sign of the reference quadratic form `ref` (computed by
/// the verifier from A and L or M, not by the functions under test)? Judged
/// at the probe where |ref| is largest; true when ref vanishes at every probe.
template <class F> bool same_sign_as(const Mat4<Q>& got, F ref) {
  Q best = 0;
  Vec4<Q> at = Vec4<Q>::Zero();
  for (const Vec4<Q>& y : sign_probes()) {
    const Q r = ref(y);
    if (abs_of<Q>(r) > abs_of<Q>(best)) best = r, at = y;
  }
  if (best == 0) return true;
  return sign_of<Q>(form(got, at)) == sign_of<Q>(best);
}

/// Points on the generator lines of the cone through the terminator points:
/// x + b L for a few rational b, chosen so that the point lies about
/// tau * size from x (tau = 1/2, -1/2, 1/4). At most 8 terminator points are used.
std::vector<RootPoint> generator_points(const std::vector<RootPoint>& terminator, const Vec4<Q>& L, const Measure& size) {
  std::vector<RootPoint> out;
  const Q taus[] = {Q(1, 2), Q(-1, 2), Q(1, 4)};
  for (std::size_t i = 0; i < terminator.size() && i < 8; ++i) {
    const RootPoint& x = terminator[i];
    const auto c = x.coords();
    const Measure w = to_measure(c[3]);
    Measure d2 = 0;  // |L_xyz - L_w p|, p the Cartesian point
    for (int k = 0; k < 3; ++k) {
      const Measure dk = to_measure(L(k)) - to_measure(L(3)) * to_measure(c[k]) / w;
      d2 += dk * dk;
    }
    if (!(d2 > 0) || !(size > 0)) continue;
    const double scale = Measure(w * size / sqrt(d2)).convert_to<double>();
    if (!std::isfinite(scale) || scale == 0) continue;
    for (const Q& tau : taus) {
      const Q b = tau * to_rational(scale);
      out.emplace_back(Vec4<Q>(x.p() + b * L), x.q(), x.delta());
    }
  }
  return out;
}

/// Rational points of the polar plane inside the object: the rational parts p
/// (chord midpoints) of terminator points x = p + sqrt(d) q, and p + 2q, where
/// both lie on the plane.
std::vector<RootPoint> plane_points(const std::vector<RootPoint>& terminator, const Vec4<Q>& pi) {
  std::vector<RootPoint> out;
  for (const RootPoint& x : terminator) {
    if (out.size() >= 16) break;
    if (pi.dot(x.p()) != 0 || pi.dot(x.q()) != 0) continue;
    for (const Vec4<Q>& y : {x.p(), Vec4<Q>(x.p() + 2 * x.q())})
      if (y(3) != 0) out.emplace_back(y, Vec4<Q>::Zero(), Q(0));
  }
  return out;
}

/// R's second plane h (the plane the paper's frame sends to infinity: z = l_z
/// for a point light, the plane at infinity for a parallel one), in the
/// result's frame: R must vanish on it. Point light: rational points of h
/// near the object (its point nearest to `inside`, and that point moved by
/// `step` along x and y), the first-order distance divided by the larger of
/// the object size and the point's distance from `inside` (h may pass far from
/// the object: an angle, not a length, is what can be asked there). Parallel
/// light: points at infinity (d, 0), the relative residual |y^T R y| / (|R|_F |y|^2).
Measure second_plane_error(const Mat4<Q>& R, const Vec4<Q>& L, const Vec4<Q>& inside, const Q& step, const Measure& size,
                           bool& all_zero) {
  all_zero = true;
  Measure worst = 0;
  std::vector<Vec4<Q>> ys;
  if (L(3) == 0) {
    for (const Vec4<Q>& d : {Vec4<Q>(1, 0, 0, 0), Vec4<Q>(0, 1, 0, 0), Vec4<Q>(0, 0, 1, 0), Vec4<Q>(1, 2, 3, 0)}) ys.push_back(d);
  } else {
    const Vec4<Q> base(inside(0) / inside(3), inside(1) / inside(3), L(2) / L(3), 1);
    ys = {base, Vec4<Q>(base + Vec4<Q>(step, 0, 0, 0)), Vec4<Q>(base + Vec4<Q>(0, step, 0, 0))};
  }
  const Measure rn = frobenius(R);
  for (const Vec4<Q>& y : ys) {
    const Q f = form(R, y);
    if (f == 0) continue;
    all_zero = false;
    const Measure fm = abs(to_measure(f));
    if (L(3) == 0) {
      worst = max(worst, rn > 0 ? Measure(fm / (rn * to_measure(Q(y.squaredNorm())))) : Measure(INFINITY));
      continue;
    }
    const Vec4<Q> g = R * y;
    const Measure gn = sqrt(to_measure(Q(g.head<3>().squaredNorm())));
    const Measure dist = sqrt(to_measure(Q((y - inside / inside(3)).head<3>().squaredNorm())));
    worst = max(worst, gn > 0 ? Measure(fm / (2 * gn) / max(size, dist)) : Measure(INFINITY));
  }
  return worst;
}

/// The verdict of a metric: exact, every point exactly on; else geometric error <= T.
bool within(const Metric& m, const Measure& size, bool exact, const Measure& T) {
  return exact ? m.all_zero : !(relative(m, size) > T);
}

}  // namespace

VerifyOutcome verify_results(const Scene& sc, const ResultSet& rs, const VerifyOptions& opt) {
  const bool exact = rs.precision.kind == Precision::Kind::exact;
  const Measure eps = epsilon_of(rs.precision);
  const Measure T = exact ? Measure(0) : Measure(opt.accuracy);
  // The exact scene: every reference is computed here, in the result's own frame.
  const TypedScene<Q> exact_scene = typed_scene<Q>(sc);
  const bool paper = rs.method == Method::paper;

  VerifyOutcome out;
  json& doc = out.document;
  doc["format"] = "qverify-verify/1";
  doc["scene"] = sc.name;
  doc["precision"] = rs.precision.name();
  doc["method"] = method_name(rs.method);
  doc["samples"] = opt.samples;
  doc["seed"] = opt.seed;
  doc["source"] = rs.source;
  doc["accuracy"] = exact ? 0.0 : opt.accuracy;
  doc["tolerance_rule"] =
      exact ? "exact: every residual must be exactly zero (a proof)"
            : "pass: the geometric error of every checked result (largest first-order distance |x^T Q x| / |grad| of "
              "exact points from P, R, the polar plane or B, in the result's frame, divided by the object size: the "
              "largest distance of the points from A's centre) is at most the accuracy target; P also on exact points "
              "of its generator lines, R also on points of the polar plane, signs and M against references computed "
              "here from A, L and the mirror. consistent_with_precision (information only): every relative residual "
              "|x^T Q x| / (|Q|_F |x|^2) within 64 eps kappa, kappa the rounding amplification of the formulas";
  json checks = json::array();
  // A check's verdict: pass, or fail with every problem found.
  auto finish = [&](json& c, const std::vector<std::string>& problems) {
    if (!problems.empty()) {
      std::string r;
      for (const auto& p : problems) r += (r.empty() ? "" : "; ") + p;
      c["reason"] = r;
    }
    c["status"] = problems.empty() ? "pass" : "fail";
    (problems.empty() ? out.passed : out.failed)++;
    checks.push_back(c);
  };
  auto skip = [&](json& c, const std::string& reason) {
    c["status"] = "skipped";
    c["reason"] = reason;
    ++out.skipped;
    checks.push_back(c);
  };

  for (std::size_t k = 0; k < sc.shadows.size(); ++k) {
    const Pair& pr = sc.shadows[k];
    json c = check_header("shadow", sc.quadrics[pr.quadric].id, "light", sc.lights[pr.other].id);
    const ShadowMatrices& got = rs.shadows[k];
    const Mat4<Q>& Aw = exact_scene.A[pr.quadric];
    const Vec4<Q>& Lw = exact_scene.L[pr.other];
    StatusDecision status = exact_shadow_status(Aw, Lw);
    if (paper && Lw(2) == 0) status.flags |= static_cast<unsigned>(ShadowFlag::singular_frame);
    ShadowResult<Q> exact_status;
    exact_status.flags = status.flags;
    c["exact_status"] = exact_status.status();
    if (!got.present) {
      finish(c, {got.problem.empty() ? "missing" : got.problem});
      continue;
    }
    // Everything is judged in the frame the result is given in (local when it has an origin).
    const Vec3<Q> o = got.origin ? *got.origin : Vec3<Q>::Zero();
    const Mat4<Q> Ae = quadric_to_local(Aw, o);
    const Vec4<Q> Le = point_to_local(Lw, o);
    // The same world points for every frame: sampled on the world terminator, then moved exactly.
    const ItemPoints pts = terminator_points(Aw, Lw, opt.samples, item_seed(opt.seed, 1, k));
    if (pts.points.empty()) {
      skip(c, std::string("the terminator has no real point to sample (exact status: ") + exact_status.status() + ")");
      continue;
    }
    const std::vector<RootPoint> local = in_frame(pts.points, got.origin);
    const ShadowError err = shadow_error(pts, got.origin, got.P, got.polar, got.R);
    const Mat4<Q> Aused = got.A ? *got.A : quadric_to_local(rs.A[pr.quadric], o);
    const Metric onA = measure_quadric(local, Aused);
    // P is *the* cone with apex L: exact points of its generator lines.
    const Metric onGen = measure_quadric(in_frame(generator_points(pts.points, Lw, pts.size), got.origin), got.P);
    // R contains the polar plane (it is the plane S carried back, read as a quadric): points of the plane off A.
    const Vec4<Q> pi_ref = Ae * Le;  // A L, computed here
    const Metric onPlane = measure_quadric(in_frame(plane_points(pts.points, Vec4<Q>(Aw * Lw)), got.origin), got.R);

    std::vector<std::string> problems;
    auto judge = [&](const Metric& m, const char* name) {
      if (!within(m, pts.size, exact, T))
        problems.push_back(std::string(name) + (exact ? ": a point is not exactly on the result"
                                                      : ": geometric error beyond the accuracy target"));
    };
    judge(err.P, "on_P");
    judge(err.R, "on_R");
    judge(err.polar, "on_polar_plane");
    judge(onGen, "on_generators (P is not the cone from L through the terminator)");
    judge(onPlane, "R on the polar plane");
    bool h_zero = true;
    Measure h_err = 0;
    for (const RootPoint& x : local)  // a rational point inside the object: the chord midpoint p of x = p + sqrt(d) q
      if (x.p()(3) != 0) {
        h_err = second_plane_error(got.R, Le, x.p(), to_rational(pts.size.convert_to<double>()), pts.size, h_zero);
        break;
      }
    if (exact ? !h_zero : h_err > T)
      problems.push_back("R does not contain the plane h that the paper's frame sends to infinity (R must be the plane pair "
                         "polar plane + h)");
    if (!symmetric_within(got.P, exact ? Measure(0) : T)) problems.push_back("P is not symmetric");
    if (!symmetric_within(got.R, exact ? Measure(0) : T)) problems.push_back("R is not symmetric");
    const Q s = Le.dot(pi_ref);
    if (!same_sign_as(got.P, [&](const Vec4<Q>& y) { const Q t = pi_ref.dot(y); return Q(s * form(Ae, y) - t * t); }))
      problems.push_back("P has the wrong sign (the contract fixes (L^T A L) A - (A L)(A L)^T up to a positive factor)");
    if (!pi_ref.isZero() && !same_orientation(got.polar, pi_ref))
      problems.push_back("polar_plane has the wrong orientation (must be A L up to a positive factor)");
    if (got.P.isZero() != (s * Ae - pi_ref * pi_ref.transpose()).isZero())
      problems.push_back("P is zero where it should not be (or the converse)");
    const Vec4<Q> PL = got.P * Le;
    if (exact && !PL.isZero()) problems.push_back("P L != 0: L is not the apex of P");
    if (!got.status.empty() && got.status != exact_status.status() && got.status != "non-finite")
      problems.push_back("status \"" + got.status + "\" but the exact inputs give \"" + exact_status.status() + "\"");

    // The rounding verdict of earlier versions, kept as information.
    Measure kappa = 1;
    if (!exact) {
      const Mat4<Q> absA = abs_matrix(Ae);
      const Vec4<Q> absL = abs_matrix(Le);
      const Vec4<Q> absAL = absA * absL;
      const Mat4<Q> Pabs = absL.dot(absAL) * absA + absAL * absAL.transpose();
      const Vec4<Q> h = Le(3) == 0 ? Vec4<Q>(0, 0, 0, 1) : Vec4<Q>(0, 0, Le(3), -Le(2));
      const Mat4<Q> Rabs = abs_matrix(Vec4<Q>(h)) * absAL.transpose() + absAL * abs_matrix(h).transpose();
      const Mat4<Q> Pref = s * Ae - pi_ref * pi_ref.transpose();
      const Mat4<Q> Rref = h * pi_ref.transpose() + pi_ref * h.transpose();
      const Measure nP = frobenius(Pref), nR = frobenius(Rref), nPi = frobenius(pi_ref);
      if (nP > 0) kappa = max(kappa, Measure(frobenius(Pabs) / nP));
      if (nR > 0) kappa = max(kappa, Measure(frobenius(Rabs) / nR));
      if (nPi > 0) kappa = max(kappa, Measure(frobenius(absAL) / nPi));
      if (paper && Lw(2) != 0) {
        const PaperFrame<Q> f = paper_frame<Q>(Lw);
        const Measure cond = inf_norm(Mat4<Q>(f.T * f.M)) * inf_norm(Mat4<Q>(f.Minv * f.Tinv));
        kappa *= cond * cond;
      }
    }
    const Measure tol = 64 * eps * kappa;
    const bool consistent = exact ? (err.P.all_zero && err.R.all_zero && err.polar.all_zero)
                                  : !(err.P.residual > tol || err.R.residual > tol || err.polar.residual > tol);
    int proved = 0;
    if (exact)
      for (const RootPoint& x : local)
        if (CGAL::is_zero(x.form(Aused)) && CGAL::is_zero(x.form(got.P)) && CGAL::is_zero(x.form(got.R))) ++proved;

    c["points"] = pts.points.size();
    c["tolerance"] = to_d(T);
    c["accuracy"] = to_d(T);
    c["object_size"] = to_d(pts.size);
    const Measure geo = max(err.geometric, max(relative(onGen, pts.size), relative(onPlane, pts.size)));
    c["geometric_error"] = geo < std::numeric_limits<Measure>::infinity() ? json(to_d(geo)) : json(nullptr);
    c["on_A"] = metric_json(onA, pts.size);
    c["on_P"] = metric_json(err.P, pts.size);
    c["on_R"] = metric_json(err.R, pts.size);
    c["on_polar_plane"] = metric_json(err.polar, pts.size);
    c["on_generators"] = metric_json(onGen, pts.size);
    c["R_on_polar_plane"] = metric_json(onPlane, pts.size);
    c["R_on_second_plane"] = h_err < std::numeric_limits<Measure>::infinity() ? json(to_d(h_err)) : json(nullptr);
    if (exact) c["proved_exactly"] = proved;
    c["consistent_with_precision"] = consistent;
    c["rounding_tolerance"] = to_d(tol);
    c["kappa"] = to_d(kappa);
    c["item_status"] = got.status.empty() ? exact_status.status() : got.status;
    if (got.accuracy && got.accuracy->inaccurate) c["flags"] = json::array({"inaccurate"});
    if (got.origin) c["origin"] = origin_json(*got.origin);
    if (pts.exhausted) c["note"] = "only " + std::to_string(pts.points.size()) + " real point(s) found on this terminator";
    if (!(pts.size > 0))
      c["note"] = "the terminator is a single real point: no object size to measure distances against; judged by the "
                  "relative residual |x^T Q x| / (|Q|_F |x|^2) <= accuracy";
    finish(c, problems);
  }

  for (std::size_t k = 0; k < sc.reflections.size(); ++k) {
    const Pair& pr = sc.reflections[k];
    json c = check_header("reflection", sc.quadrics[pr.quadric].id, "mirror", sc.mirrors[pr.other].id);
    const ReflectionMatrices& got = rs.reflections[k];
    const Mat4<Q>& Aw = exact_scene.A[pr.quadric];
    const Mat4<Q> Mw = reference_mirror(exact_scene.planes[pr.other]);  // written out here, not the core's
    const char* exact_word = exact_degenerate(Aw) ? "degenerate-quadric" : "ok";
    c["exact_status"] = exact_word;
    if (!got.present) {
      finish(c, {got.problem.empty() ? "missing" : got.problem});
      continue;
    }
    const Vec3<Q> o = got.origin ? *got.origin : Vec3<Q>::Zero();
    // M and B of the reference, in the result's frame: M_local = T^-1 M T, B_local = T^T M^T A M T.
    const Mat4<Q> M_ref = translation<Q>(Vec3<Q>(-o)) * Mw * translation<Q>(o);
    const Mat4<Q> B_ref = quadric_to_local(Mat4<Q>(Mw.transpose() * Aw * Mw), o);
    const ItemPoints pts = reflected_points(Aw, Mw, opt.samples, item_seed(opt.seed, 2, k));
    if (pts.points.empty()) {
      skip(c, "the quadric has no real point to sample");
      continue;
    }
    const ReflectionError err = reflection_error(pts, got.origin, got.B);
    // M must be the reflection (exactly, or within the accuracy target relative to its largest entry).
    const Measure m_err = to_measure(max_abs(Mat4<Q>(got.M - M_ref))) / max(Measure(1), to_measure(max_abs(M_ref)));
    std::vector<std::string> problems;
    if (!within(err.B, pts.size, exact, T))
      problems.push_back(exact ? "on_B: a reflected point is not exactly on B" : "on_B: geometric error beyond the accuracy target");
    if (exact ? got.M != M_ref : (m_err > T)) problems.push_back("M is not the reflection in the mirror plane");
    if (!symmetric_within(got.B, exact ? Measure(0) : T)) problems.push_back("B is not symmetric");
    if (!same_sign_as(got.B, [&](const Vec4<Q>& y) { return form(B_ref, y); }))
      problems.push_back("B has the wrong sign (must be M^T A M up to a positive factor)");
    if (!got.status.empty() && got.status != exact_word && got.status != "non-finite")
      problems.push_back("status \"" + got.status + "\" but the exact inputs give \"" + exact_word + "\"");

    Measure kappa = 1;
    if (!exact) {
      // Conditioning of B in its own frame: B_local = G^T A_c G with A_c the quadric in the frame of its
      // own centre c (when it has one) and G = T_c^-1 M T_o mapping the image frame into it.
      std::optional<Vec3<Q>> cen = natural_center(sc.quadrics[pr.quadric], Aw);
      const Vec3<Q> cc = cen ? *cen : Vec3<Q>::Zero();
      const Mat4<Q> G = translation<Q>(Vec3<Q>(-cc)) * Mw * translation<Q>(o);
      const Mat4<Q> absG = abs_matrix(G);
      const Measure nB = frobenius(B_ref);
      if (nB > 0)
        kappa = max(kappa, Measure(frobenius(Mat4<Q>(absG.transpose() * abs_matrix(quadric_to_local(Aw, cc)) * absG)) / nB));
      const Measure m = inf_norm(G);
      kappa *= paper ? m * m * m * m : m * m;
    }
    const Measure tol = 64 * eps * kappa;
    int proved = 0;
    if (exact)
      for (const RootPoint& y : in_frame(pts.points, got.origin))
        if (CGAL::is_zero(y.form(got.B))) ++proved;
    c["points"] = pts.points.size();
    c["tolerance"] = to_d(T);
    c["accuracy"] = to_d(T);
    c["object_size"] = to_d(pts.size);
    c["geometric_error"] = err.geometric < std::numeric_limits<Measure>::infinity() ? json(to_d(err.geometric)) : json(nullptr);
    c["on_B"] = metric_json(err.B, pts.size);
    if (exact) c["proved_exactly"] = proved;
    c["consistent_with_precision"] = exact ? err.B.all_zero && got.M == M_ref : !(err.B.residual > tol) && !(m_err > tol);
    c["rounding_tolerance"] = to_d(tol);
    c["M_error"] = to_d(m_err);
    if (got.origin) c["origin"] = origin_json(*got.origin);
    c["kappa"] = to_d(kappa);
    c["item_status"] = got.status.empty() ? std::string(exact_word) : got.status;
    if (got.accuracy && got.accuracy->inaccurate) c["flags"] = json::array({"inaccurate"});
    finish(c, problems);
  }
  doc["checks"] = checks;
  doc["passed"] = out.passed;
  doc["failed"] = out.failed;
  doc["skipped"] = out.skipped;
  doc["left_out"] = skipped_json(sc);
  if (!rs.notes.empty()) doc["notes"] = rs.notes;
  return out;
}

// ------------------------------------------------------------------ candidates

namespace {

class CandidateReader {
 public:
  CandidateReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& what) const { throw InputError(file_, path, what); }

  /// One entry: number, "p/q"/decimal string, {"lo","hi"} (midpoint); null -> nullopt.
  std::optional<Q> entry(const JsonNode& n, const std::string& path) const {
    std::string err;
    std::optional<Q> v;
    if (n.kind == JsonNode::Kind::null) return std::nullopt;
    if (n.kind == JsonNode::Kind::number) v = parse_decimal(n.text, err);
    else if (n.kind == JsonNode::Kind::string) v = parse_rational(n.text, err);
    else if (n.kind == JsonNode::Kind::object) {
      const JsonNode* lo = n.find("lo");
      const JsonNode* hi = n.find("hi");
      if (!lo || !hi) fail(path, "an interval entry needs \"lo\" and \"hi\"");
      const auto a = entry(*lo, path + ".lo"), b = entry(*hi, path + ".hi");
      if (!a || !b) return std::nullopt;
      if (*a > *b) fail(path, "interval with lo > hi");
      return Q((*a + *b) / 2);
    } else fail(path, std::string("expected a number, a \"p/q\" string or an interval, found ") + n.kind_name());
    if (!v) fail(path, err);
    return v;
  }

  /// A list of `count` entries into out[0..count); false if any entry is null (non-finite).
  template <class Out> bool entries(const JsonNode& n, const std::string& path, int count, Out out, const char* what) const {
    if (n.kind != JsonNode::Kind::array || n.items.size() != static_cast<std::size_t>(count)) fail(path, what);
    bool ok = true;
    for (int i = 0; i < count; ++i) {
      auto v = entry(n.items[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]");
      if (v) out(i, *v);
      else ok = false;
    }
    return ok;
  }

  /// A 4x4 matrix; nullopt if absent or any entry is null (non-finite).
  std::optional<Mat4<Q>> mat4(const JsonNode* n, const std::string& path) const {
    if (!n) return std::nullopt;
    if (n->kind != JsonNode::Kind::array || n->items.size() != 4) fail(path, "expected 4 rows of 4 numbers");
    Mat4<Q> m;
    bool ok = true;
    for (int i = 0; i < 4; ++i)
      ok = entries(n->items[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]", 4,
                   [&](int j, const Q& v) { m(i, j) = v; }, "expected a row of 4 numbers") && ok;
    if (!ok) return std::nullopt;
    return m;
  }

  /// A plane (4 numbers); nullopt if absent or any entry is null.
  std::optional<Vec4<Q>> vec4(const JsonNode* n, const std::string& path) const {
    if (!n) return std::nullopt;
    Vec4<Q> v;
    if (!entries(*n, path, 4, [&](int i, const Q& x) { v(i) = x; }, "expected 4 numbers")) return std::nullopt;
    return v;
  }

  std::string text(const JsonNode& obj, const std::string& path, const char* key) const {
    const JsonNode* n = obj.find(key);
    if (!n || n->kind != JsonNode::Kind::string) fail(path + "." + key, "expected a string");
    return n->text;
  }

 private:
  std::string file_;
};

}  // namespace

ResultSet candidate_results(const Scene& sc, const std::string& file, const Precision& fallback) {
  return candidate_results_text(sc, read_text_file(file, JsonLimits{}.max_bytes), file, fallback);
}

ResultSet candidate_results_text(const Scene& sc, const std::string& text, const std::string& file,
                                 const Precision& fallback) {
  const JsonNode root = parse_json_tree(text, file);
  CandidateReader r(file);
  if (root.kind != JsonNode::Kind::object) r.fail("", "expected a qverify-eval/1 object");
  const JsonNode* format = root.find("format");
  if (!format || format->kind != JsonNode::Kind::string || format->text != "qverify-eval/1")
    r.fail("format", "expected \"qverify-eval/1\"");
  ResultSet rs;
  rs.source = file;
  rs.precision = fallback;
  if (const JsonNode* p = root.find("precision")) {
    if (p->kind != JsonNode::Kind::string) r.fail("precision", "expected a string");
    if (auto parsed = parse_precision(p->text)) rs.precision = *parsed;
    else r.fail("precision", "unknown precision \"" + p->text + "\"");
  }
  if (const JsonNode* m = root.find("method")) {
    if (m->kind != JsonNode::Kind::string || (m->text != "direct" && m->text != "paper"))
      r.fail("method", "expected \"direct\" or \"paper\"");
    rs.method = m->text == "paper" ? Method::paper : Method::direct;
  }
  // The quadrics as represented in the candidate's precision (for on_A).
  const Precision rep = rs.precision.kind == Precision::Kind::interval ? *parse_precision("double") : rs.precision;
  rs.A = computed_results(sc, rep, Method::direct, std::nullopt, std::nullopt).A;
  rs.shadows.resize(sc.shadows.size());
  rs.reflections.resize(sc.reflections.size());

  auto index_of = [](const auto& items, const std::string& id) -> long {
    for (std::size_t i = 0; i < items.size(); ++i)
      if (items[i].id == id) return static_cast<long>(i);
    return -1;
  };
  for (const char* kind : {"shadows", "reflections"}) {
    const bool shadow = std::string(kind) == "shadows";
    const JsonNode* list = root.find(kind);
    if (!list) continue;
    if (list->kind != JsonNode::Kind::array) r.fail(kind, "expected an array");
    for (std::size_t i = 0; i < list->items.size(); ++i) {
      const std::string path = std::string(kind) + "[" + std::to_string(i) + "]";
      const JsonNode& it = list->items[i];
      if (it.kind != JsonNode::Kind::object) r.fail(path, "expected an object");
      const std::string qid = r.text(it, path, "quadric");
      const std::string oid = r.text(it, path, shadow ? "light" : "mirror");
      const long qi = index_of(sc.quadrics, qid);
      if (qi < 0) r.fail(path + ".quadric", "no quadric with id \"" + qid + "\" in the scene");
      const long oi = shadow ? index_of(sc.lights, oid) : index_of(sc.mirrors, oid);
      if (oi < 0) r.fail(path + (shadow ? ".light" : ".mirror"), "no such id \"" + oid + "\" in the scene");
      const auto& pairs = shadow ? sc.shadows : sc.reflections;
      long slot = -1;
      for (std::size_t k = 0; k < pairs.size(); ++k)
        if (pairs[k].quadric == static_cast<std::size_t>(qi) && pairs[k].other == static_cast<std::size_t>(oi))
          slot = static_cast<long>(k);
      if (slot < 0) {
        rs.notes.push_back(path + " (" + qid + ", " + oid + ") is not requested by the scene: ignored");
        continue;
      }
      std::optional<Vec3<Q>> origin;
      if (const JsonNode* o = it.find("origin")) {
        Vec3<Q> v;
        if (!r.entries(*o, path + ".origin", 3, [&](int i, const Q& x) { v(i) = x; }, "expected 3 numbers"))
          r.fail(path + ".origin", "origin must be finite");
        origin = v;
      }
      const JsonNode* st = it.find("status");
      const std::string status = st && st->kind == JsonNode::Kind::string ? st->text : "";
      if (shadow) {
        ShadowMatrices& m = rs.shadows[static_cast<std::size_t>(slot)];
        if (m.present) r.fail(path, "duplicate item (" + qid + ", " + oid + ")");
        m.status = status;
        auto P = r.mat4(it.find("P"), path + ".P");
        auto R = r.mat4(it.find("R"), path + ".R");
        auto pi = r.vec4(it.find("polar_plane"), path + ".polar_plane");
        if (P && R && pi) {
          m.present = true;
          m.origin = origin;
          m.P = *P;
          m.R = *R;
          m.polar = *pi;
        } else m.problem = "P, R or polar_plane missing or not finite in the candidate";
      } else {
        ReflectionMatrices& m = rs.reflections[static_cast<std::size_t>(slot)];
        if (m.present) r.fail(path, "duplicate item (" + qid + ", " + oid + ")");
        m.status = status;
        auto M = r.mat4(it.find("M"), path + ".M");
        auto B = r.mat4(it.find("B"), path + ".B");
        if (M && B) {
          m.present = true;
          m.origin = origin;
          m.M = *M;
          m.B = *B;
        } else m.problem = "M or B missing or not finite in the candidate";
      }
    }
  }
  for (auto& m : rs.shadows)
    if (!m.present && m.problem.empty()) m.problem = "requested item missing from the candidate";
  for (auto& m : rs.reflections)
    if (!m.present && m.problem.empty()) m.problem = "requested item missing from the candidate";
  return rs;
}

}  // namespace qverify
