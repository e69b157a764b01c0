#include <qverify/exact/number_text.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/scene/json_tree.hpp>
#include <qverify/eval/frames.hpp>
#include <qverify/verify/verifier.hpp>
#include <qverify/verify/check.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/exact/statuses.hpp>

#include <qverify/batch/items.hpp>

#include <limits>

namespace qverify {
namespace {

using Q = Rational;

}  // namespace

VerifyReport verify_results(const Scene& sc, const ResultSet& rs, const VerifyOptions& opt) {
  const Measure eps = opt.prove ? Measure(0) : machine_epsilon(rs.precision);  // 0: proof mode
  // The exact scene: every reference is computed by the checks, in the result's own frame.
  const TypedScene<Q> exact_scene = typed_scene<Q>(sc);
  CheckOptions copt;
  copt.samples = opt.samples;
  copt.seed = opt.seed;
  copt.accuracy = opt.accuracy;
  copt.method = rs.method;

  VerifyReport out;
  out.precision = rs.precision;
  out.method = rs.method;
  out.source = rs.source;
  out.options = opt;
  out.notes = rs.notes;
  const std::size_t ns = sc.shadows.size(), n = ns + sc.reflections.size();
  std::vector<VerifyCheck> checks(n);
  auto check_shadow_item = [&](std::size_t k, VerifyCheck& c) {
    const Pair& pr = sc.shadows[k];
    c.kind = "shadow";
    c.quadric = sc.quadrics[pr.quadric].id;
    c.other = sc.lights[pr.other].id;
    const ShadowMatrices& got = rs.shadows[k];
    const Mat4<Q>& Aw = exact_scene.A[pr.quadric];
    const Vec4<Q>& Lw = exact_scene.L[pr.other];
    if (!got.present) {
      c.exact_status = exact_shadow_word(Aw, Lw, rs.method);
      c.missing = got.problem.empty() ? "missing" : got.problem;
      return;
    }
    ExactShadowCandidate cand;
    cand.P = got.P;
    if (got.polar_given) cand.polar_plane = got.polar;
    if (got.R_given) cand.R = got.R;
    cand.origin = got.origin;
    cand.status = got.status;
    cand.A = got.A ? *got.A : quadric_to_local(rs.A[pr.quadric], got.origin ? *got.origin : Vec3<Q>::Zero());
    c.report = check_shadow_exact(Aw, Lw, cand, copt, eps);
    c.exact_status = c.report->exact_status;
    c.inaccurate = got.accuracy && got.accuracy->inaccurate;
    c.origin = got.origin;
  };
  auto check_reflection_item = [&](std::size_t k, VerifyCheck& c) {
    const Pair& pr = sc.reflections[k];
    c.kind = "reflection";
    c.quadric = sc.quadrics[pr.quadric].id;
    c.other = sc.mirrors[pr.other].id;
    const ReflectionMatrices& got = rs.reflections[k];
    const Mat4<Q>& Aw = exact_scene.A[pr.quadric];
    const Vec4<Q>& plane = exact_scene.planes[pr.other];
    const std::optional<Vec3<Q>> center = natural_center(sc.quadrics[pr.quadric], Aw);
    if (!got.present) {
      c.exact_status = exact_reflection_word(Aw);
      c.missing = got.problem.empty() ? "missing" : got.problem;
      return;
    }
    ExactReflectionCandidate cand;
    if (got.M_given) cand.M = got.M;
    cand.B = got.B;
    cand.origin = got.origin;
    cand.status = got.status;
    c.report = check_reflection_exact(Aw, plane, cand, copt, eps, center);
    c.exact_status = c.report->exact_status;
    c.inaccurate = got.accuracy && got.accuracy->inaccurate;
    c.origin = got.origin;
  };
  // Items are independent (an item's points come from its own inputs, item_seed): threads over them,
  // the checks kept in the scene's order.
  for_each_item(n, opt.threads, opt.progress, [&](std::size_t i) {
    if (i < ns) check_shadow_item(i, checks[i]);
    else check_reflection_item(i - ns, checks[i]);
  });
  for (VerifyCheck& c : checks) {
    (c.skipped() ? out.skipped : c.passed() ? out.passed : out.failed)++;
    out.checks.push_back(std::move(c));
  }
  return out;
}

// ------------------------------------------------------------------ candidates

namespace {

class CandidateReader {
 public:
  CandidateReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const std::string& path, const std::string& what) const { throw InputError(file_, path, what); }

  /// The document's precision: its numbers are the values of that format the
  /// writer held (the contract: float and double entries are JSON numbers that
  /// round-trip, long double, float128 and mpfr entries decimal strings that
  /// round-trip), so each is read as the nearest value of the format, not as
  /// the decimal it spells (0.1 in a double document is the double 0.1). "p/q"
  /// strings and exact documents are read exactly. (An mpfr:128 entry is 40
  /// digits, off its binary value by up to 10^-40 of it, as much as the
  /// rounding: read as the decimal, B of a cone 2^100 from the origin was 10^18
  /// object sizes off where eval had certified 4e-27 for the value it held.)
  void number_format(const Precision& p) {
    format_ = p.kind;
    if (p.kind == Precision::Kind::mpfr) mpfr_bits_ = digits_for_bits(p.bits).bits;
  }

  /// One entry: number, "p/q"/decimal string, {"lo","hi"} (midpoint); null -> nullopt.
  /// (`as_double`: a JSON number is read as its nearest double whatever the document's format, as
  /// an origin's coordinates are written.)
  std::optional<Q> entry(const JsonNode& n, const std::string& path, bool as_double = false) const {
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
    using K = Precision::Kind;
    if (as_double && n.kind == JsonNode::Kind::number) {
      RoundingReport rep;
      v = exact_value(round_rational<double>(*v, rep));
      if (rep.overflow) fail(path, "beyond the range of a double (" + n.text.substr(0, 40) + ")");
      return v;
    }
    const bool binary_number = n.kind == JsonNode::Kind::number && (format_ == K::f32 || format_ == K::f64 || format_ == K::interval);
    const bool binary_text = n.kind == JsonNode::Kind::string && n.text.find('/') == std::string::npos &&
                             (format_ == K::f80 || format_ == K::f128 || format_ == K::mpfr);
    if (binary_number || binary_text) {
      RoundingReport rep;
      switch (format_) {
        case K::f32: v = exact_value(round_rational<float>(*v, rep)); break;
        case K::f80: v = exact_value(round_rational<long double>(*v, rep)); break;
        case K::f128: v = exact_value(round_rational<Float128>(*v, rep)); break;
        case K::mpfr: v = rounded_to_bits(*v, mpfr_bits_); break;
        default: v = exact_value(round_rational<double>(*v, rep)); break;
      }
      if (rep.overflow) fail(path, "beyond the range of the document's precision (" + n.text.substr(0, 40) + ")");
    }
    return v;
  }

  /// A list of `count` entries into out[0..count); false if any entry is null (non-finite).
  template <class Out>
  bool entries(const JsonNode& n, const std::string& path, int count, Out out, const char* what, bool as_double = false) const {
    if (n.kind != JsonNode::Kind::array || n.items.size() != static_cast<std::size_t>(count)) fail(path, what);
    bool ok = true;
    for (int i = 0; i < count; ++i) {
      auto v = entry(n.items[static_cast<std::size_t>(i)], path + "[" + std::to_string(i) + "]", as_double);
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
  Precision::Kind format_ = Precision::Kind::exact;
  unsigned mpfr_bits_ = 0;  ///< an mpfr document's working precision (as eval sets it: set_mpfr_bits)

  /// q rounded to nearest with `bits` bits of significand (MPFR's exponent range holds any
  /// document's number), exactly.
  static Q rounded_to_bits(const Q& q, unsigned bits) {
    Mpfr x;
    mpfr_set_prec(x.backend().data(), static_cast<mpfr_prec_t>(bits));
    mpfr_set_q(x.backend().data(), q.backend().data(), MPFR_RNDN);
    return exact_value(x);
  }
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
  r.number_format(rs.precision);
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
        // An origin written as a JSON number is the double that the number's text denotes (a
        // program's origin is a double, and JSON writes the shortest text that reads back as it;
        // that text, taken exactly, can be 1e-5 off for an origin of 1e11, many object sizes for a
        // small object), in a float document too. A string ("p/q" or decimal) is taken exactly.
        Vec3<Q> v;
        if (!r.entries(*o, path + ".origin", 3, [&](int i, const Q& x) { v(i) = x; }, "expected 3 numbers", true))
          r.fail(path + ".origin", "origin must be finite");
        origin = v;
      }
      const JsonNode* st = it.find("status");  // (null: not given)
      if (st && st->kind != JsonNode::Kind::string && st->kind != JsonNode::Kind::null)
        r.fail(path + ".status", "expected a status word (a string)");
      if (st && st->kind == JsonNode::Kind::string && st->text.empty())  // ("" is no word; null: none given)
        r.fail(path + ".status", "expected a status word, found \"\"");
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
