#include <qverify/exact/number_text.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/verify/json_tree.hpp>
#include <qverify/verify/frames.hpp>
#include <qverify/verify/verifier.hpp>

#include <limits>

namespace qverify {
namespace {

using Q = Rational;
using json = nlohmann::ordered_json;

double to_d(const Measure& m) { return m.convert_to<double>(); }
Measure max(const Measure& a, const Measure& b) { return a < b ? b : a; }

template <int R, int C> Measure frobenius(const Eigen::Matrix<Q, R, C>& m) {
  Measure s = 0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const Measure v = to_measure(m(i));
    s += v * v;
  }
  return sqrt(s);
}

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

/// Largest residual and first-order distance over the sampled points.
struct Metric {
  Measure residual = 0, distance = 0;
  bool all_zero = true;
  json to_json() const { return {{"max_residual", to_d(residual)}, {"max_distance", to_d(distance)}}; }
};

Measure point_norm2(const RootPoint& x) {
  Measure s = 0;
  for (const RootNumber& c : x.coords()) {
    const Measure v = to_measure(c);
    s += v * v;
  }
  return s;
}

/// |x^T Q x| / (|Q|_F |x|^2) and |x^T Q x| / |grad| at the Cartesian point x/w.
void measure_quadric(Metric& m, const RootPoint& x, const Mat4<Q>& Qm, const Measure& qnorm, const Measure& xnorm2,
                     bool& exact_zero) {
  const RootNumber f = x.form(Qm);
  if (CGAL::is_zero(f)) return;
  exact_zero = false;
  m.all_zero = false;
  const Measure fm = abs(to_measure(f));
  if (qnorm > 0) m.residual = max(m.residual, Measure(fm / (qnorm * xnorm2)));
  Measure g = 0;
  for (int i = 0; i < 3; ++i) {
    const Measure gi = to_measure(x.linear(Qm.row(i).transpose()));
    g += gi * gi;
  }
  const Measure w = abs(to_measure(x.coords()[3]));
  if (g > 0 && w > 0) m.distance = max(m.distance, Measure(fm / (w * 2 * sqrt(g))));
}

void measure_plane(Metric& m, const RootPoint& x, const Vec4<Q>& pi, const Measure& xnorm2, bool& exact_zero) {
  const RootNumber f = x.linear(pi);
  if (CGAL::is_zero(f)) return;
  exact_zero = false;
  m.all_zero = false;
  const Measure fm = abs(to_measure(f));
  const Measure pn = frobenius(pi), pxyz = frobenius(Vec3<Q>(pi.head<3>()));
  if (pn > 0) m.residual = max(m.residual, Measure(fm / (pn * sqrt(xnorm2))));
  const Measure w = abs(to_measure(x.coords()[3]));
  if (pxyz > 0 && w > 0) m.distance = max(m.distance, Measure(fm / (w * pxyz)));
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

std::uint64_t item_seed(std::uint64_t seed, int kind, std::size_t index) {
  return seed * 1000003ull + static_cast<std::uint64_t>(kind) * 7919ull + index;
}

json check_header(const char* kind, const std::string& quadric, const char* other_key, const std::string& other) {
  json j;
  j["kind"] = kind;
  j["quadric"] = quadric;
  j[other_key] = other;
  return j;
}

}  // namespace

json verify_document(const Scene& sc, const ResultSet& rs, const VerifyOptions& opt, int& failed) {
  const bool exact = rs.precision.kind == Precision::Kind::exact;
  const Measure eps = epsilon_of(rs.precision);
  // The exact scene: each check computes its exact reference in the result's own frame.
  const TypedScene<Q> exact_scene = typed_scene<Q>(sc);
  const bool paper = rs.method == "paper";

  json doc;
  doc["format"] = "qverify-verify/1";
  doc["scene"] = sc.name;
  doc["precision"] = rs.precision.name();
  doc["method"] = rs.method;
  doc["samples"] = opt.samples;
  doc["seed"] = opt.seed;
  doc["source"] = rs.source;
  doc["tolerance_rule"] = exact ? "exact: every residual must be exactly zero (a proof)"
                                : "64 * eps * kappa, kappa = |F|(|A|, |L|) / |F(A, L)| (Frobenius), F = P, R and the polar "
                                  "plane evaluated with absolute values: the rounding amplification of the formulas; "
                                  "times cond_inf(T M)^2 for method paper, |M|_inf^2 for reflections";
  json checks = json::array();
  int passed = 0, skipped = 0;
  failed = 0;
  // A check's verdict: pass, or fail with every problem found.
  auto finish = [&](json& c, const std::vector<std::string>& problems) {
    if (!problems.empty()) {
      std::string r;
      for (const auto& p : problems) r += (r.empty() ? "" : "; ") + p;
      c["reason"] = r;
    }
    (problems.empty() ? passed : failed)++;
    checks.push_back(c);
  };

  for (std::size_t k = 0; k < sc.shadows.size(); ++k) {
    const Pair& pr = sc.shadows[k];
    json c = check_header("shadow", sc.quadrics[pr.quadric].id, "light", sc.lights[pr.other].id);
    const ShadowMatrices& got = rs.shadows[k];
    const Mat4<Q>& Aw = exact_scene.A[pr.quadric];
    const Vec4<Q>& Lw = exact_scene.L[pr.other];
    // Everything is judged in the frame the result is given in (local when it has an origin).
    const Vec3<Q> o = got.origin ? *got.origin : Vec3<Q>::Zero();
    const Mat4<Q> Ae = quadric_to_local(Aw, o);
    const Vec4<Q> Le = point_to_local(Lw, o);
    const Mat4<Q> to_frame = translation<Q>(Vec3<Q>(-o));
    ShadowItem<Q> want{pr, shadow<Q>(Ae, Le, Method::direct), std::nullopt, Ae};
    if (!got.present) {
      c["status"] = "fail";
      finish(c, {got.problem.empty() ? "missing" : got.problem});
      continue;
    }
    // The same world points for every frame: sampled on the world terminator, then moved exactly.
    SampleReport samples = sample_section(Aw, Vec4<Q>(Aw * Lw), opt.samples, item_seed(opt.seed, 1, k));
    for (RootPoint& x : samples.points) x = x.mapped(to_frame);
    if (samples.points.empty()) {
      c["status"] = "skipped";
      c["reason"] = std::string("the terminator has no real point to sample (exact status: ") + want.result.status() + ")";
      ++skipped;
      checks.push_back(c);
      continue;
    }
    // Tolerance from the conditioning of the formulas at the exact data.
    Measure kappa = 1;
    if (!exact) {
      const Mat4<Q> absA = abs_matrix(Ae);
      const Vec4<Q> absL = abs_matrix(Le);
      const Vec4<Q> absAL = absA * absL;
      const Mat4<Q> Pabs = absL.dot(absAL) * absA + absAL * absAL.transpose();
      const Vec4<Q> h = frame_plane<Q>(Le);
      const Mat4<Q> Rabs = plane_pair<Q>(absAL, abs_matrix(h));
      const Measure nP = frobenius(want.result.P), nR = frobenius(want.result.R), nPi = frobenius(want.result.polar_plane);
      if (nP > 0) kappa = max(kappa, Measure(frobenius(Pabs) / nP));
      if (nR > 0) kappa = max(kappa, Measure(frobenius(Rabs) / nR));
      if (nPi > 0) kappa = max(kappa, Measure(frobenius(absAL) / nPi));
      if (paper) {
        const PaperFrame<Q> f = paper_frame<Q>(Lw);
        if (!f.singular) {
          const Measure cond = inf_norm(Mat4<Q>(f.T * f.M)) * inf_norm(Mat4<Q>(f.Minv * f.Tinv));
          kappa *= cond * cond;
        }
      }
    }
    const Measure tol = 64 * eps * kappa;
    Metric onA, onP, onR, onPi;
    const Mat4<Q> Aused = got.A ? *got.A : quadric_to_local(rs.A[pr.quadric], o);
    const Measure nA = frobenius(Aused), nP = frobenius(got.P), nR = frobenius(got.R);
    int proved = 0;
    for (const RootPoint& x : samples.points) {
      const Measure x2 = point_norm2(x);
      bool zero = true;
      measure_quadric(onA, x, Aused, nA, x2, zero);
      measure_quadric(onP, x, got.P, nP, x2, zero);
      measure_quadric(onR, x, got.R, nR, x2, zero);
      bool pzero = true;
      measure_plane(onPi, x, got.polar, x2, pzero);
      if (zero) ++proved;
    }
    std::vector<std::string> problems;
    auto within = [&](const Metric& m, const char* name) {
      if (exact ? !m.all_zero : (m.residual > tol)) problems.push_back(std::string(name) + " residual beyond tolerance");
    };
    within(onA, "on_A");
    within(onP, "on_P");
    within(onR, "on_R");
    within(onPi, "on_polar_plane");
    if (!symmetric_within(got.P, tol)) problems.push_back("P is not symmetric");
    if (!symmetric_within(got.R, tol)) problems.push_back("R is not symmetric");
    if (!want.result.P.isZero() && !same_orientation(got.P, want.result.P))
      problems.push_back("P has the wrong sign (the contract fixes the factor to be positive)");
    if (!want.result.polar_plane.isZero() && !same_orientation(got.polar, want.result.polar_plane))
      problems.push_back("polar_plane has the wrong orientation (must be A L up to a positive factor)");
    if (got.P.isZero() != want.result.P.isZero()) problems.push_back("P is zero where it should not be (or the converse)");
    c["status"] = problems.empty() ? "pass" : "fail";
    c["points"] = samples.points.size();
    c["tolerance"] = to_d(tol);
    c["on_A"] = onA.to_json();
    c["on_P"] = onP.to_json();
    c["on_R"] = onR.to_json();
    c["on_polar_plane"] = onPi.to_json();
    if (exact) c["proved_exactly"] = proved;
    c["kappa"] = to_d(kappa);
    c["item_status"] = got.status.empty() ? want.result.status() : got.status;
    if (got.origin) c["origin"] = origin_json(*got.origin);
    if (samples.exhausted)
      c["note"] = "only " + std::to_string(samples.points.size()) + " real point(s) found on this terminator";
    finish(c, problems);
  }

  for (std::size_t k = 0; k < sc.reflections.size(); ++k) {
    const Pair& pr = sc.reflections[k];
    json c = check_header("reflection", sc.quadrics[pr.quadric].id, "mirror", sc.mirrors[pr.other].id);
    const ReflectionMatrices& got = rs.reflections[k];
    const Mat4<Q>& Ae = exact_scene.A[pr.quadric];
    const Vec3<Q> o = got.origin ? *got.origin : Vec3<Q>::Zero();
    const Mat4<Q> Mw = mirror_matrix<Q>(exact_scene.planes[pr.other]);
    const ReflectionResult<Q> exact_world = reflection<Q>(Ae, Mw, Method::direct);
    // The exact M and B in the result's frame: M_local = T^-1 M T, B_local = T^T B T.
    struct {
      Mat4<Q> M;
      ReflectionResult<Q> result;
    } want{translation<Q>(Vec3<Q>(-o)) * Mw * translation<Q>(o), {}};
    want.result.B = quadric_to_local(exact_world.B, o);
    want.result.degenerate = exact_world.degenerate;
    if (!got.present) {
      c["status"] = "fail";
      finish(c, {got.problem.empty() ? "missing" : got.problem});
      continue;
    }
    const SampleReport samples = sample_quadric(Ae, opt.samples, item_seed(opt.seed, 2, k));
    if (samples.points.empty()) {
      c["status"] = "skipped";
      c["reason"] = "the quadric has no real point to sample";
      ++skipped;
      checks.push_back(c);
      continue;
    }
    Measure kappa = 1;
    if (!exact) {
      // Conditioning of B in its own frame: B_local = G^T A_c G with A_c the quadric in the frame of its
      // own centre c (when it has one) and G = T_c^-1 M T_o mapping the image frame into it.
      std::optional<Vec3<Q>> c = natural_center(sc.quadrics[pr.quadric], Ae);
      const Vec3<Q> cc = c ? *c : Vec3<Q>::Zero();
      const Mat4<Q> G = translation<Q>(Vec3<Q>(-cc)) * Mw * translation<Q>(o);
      const Mat4<Q> absG = abs_matrix(G);
      const Measure nB = frobenius(want.result.B);
      if (nB > 0)
        kappa = max(kappa, Measure(frobenius(Mat4<Q>(absG.transpose() * abs_matrix(quadric_to_local(Ae, cc)) * absG)) / nB));
      const Measure m = inf_norm(G);
      kappa *= paper ? m * m * m * m : m * m;
    }
    const Measure tol = 64 * eps * kappa;
    Metric onB;
    const Measure nB = frobenius(got.B);
    int proved = 0;
    for (const RootPoint& x : samples.points) {
      const RootPoint y = x.mapped(Mat4<Q>(translation<Q>(Vec3<Q>(-o)) * Mw));  // exact image, in the result's frame
      bool zero = true;
      measure_quadric(onB, y, got.B, nB, point_norm2(y), zero);
      if (zero) ++proved;
    }
    // M must be the reflection (exactly, up to the precision's rounding).
    const Measure m_err = to_measure(max_abs(Mat4<Q>(got.M - want.M))) / max(Measure(1), to_measure(max_abs(want.M)));
    std::vector<std::string> problems;
    if (exact ? !onB.all_zero : (onB.residual > tol)) problems.push_back("on_B residual beyond tolerance");
    if (exact ? got.M != want.M : (m_err > tol)) problems.push_back("M is not the reflection in the mirror plane");
    if (!symmetric_within(got.B, tol)) problems.push_back("B is not symmetric");
    if (!want.result.B.isZero() && !same_orientation(got.B, want.result.B))
      problems.push_back("B has the wrong sign (must be M^T A M up to a positive factor)");
    c["status"] = problems.empty() ? "pass" : "fail";
    c["points"] = samples.points.size();
    c["tolerance"] = to_d(tol);
    c["on_B"] = onB.to_json();
    if (exact) c["proved_exactly"] = proved;
    c["M_error"] = to_d(m_err);
    if (got.origin) c["origin"] = origin_json(*got.origin);
    c["kappa"] = to_d(kappa);
    c["item_status"] = got.status.empty() ? want.result.status() : got.status;
    finish(c, problems);
  }
  doc["checks"] = checks;
  doc["passed"] = passed;
  doc["failed"] = failed;
  doc["skipped"] = skipped;
  doc["left_out"] = skipped_json(sc);
  if (!rs.notes.empty()) doc["notes"] = rs.notes;
  return doc;
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
    rs.method = m->text;
  }
  // The quadrics as represented in the candidate's precision (for on_A).
  const Precision rep = rs.precision.kind == Precision::Kind::interval ? *parse_precision("double") : rs.precision;
  rs.A = computed_results(sc, rep, Method::direct).A;
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
