// Verdicts to trust: status words are exact predicates in every precision and
// method under any units and placement; the filter never decides wrongly; the
// inaccurate flag is raised exactly where the geometric error may exceed the
// target; verify never passes a geometrically wrong result.
#include <qverify/eval/certified_bound.hpp>
#include <qverify/exact/statuses.hpp>
#include <qverify/verify/adaptive.hpp>
#include <qverify/scene/json_tree.hpp>
#include <qverify/report/eval_document.hpp>
#include <qverify/report/verify_document.hpp>
#include <qverify/verify/verifier.hpp>

#include "audit_scenes.hpp"
#include "laws.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

using namespace qverify;
using qverify::test::pow10;
using Q = Rational;

namespace {

std::string text(const Q& x) { return "\"" + x.str() + "\""; }
std::string vec3(const Vec3<Q>& v) { return "[" + text(v(0)) + ", " + text(v(1)) + ", " + text(v(2)) + "]"; }

/// x -> s x + t, exactly.
struct Placement {
  Q s;
  Vec3<Q> t;
  Vec3<Q> point(const Vec3<Q>& p) const { return Vec3<Q>(s * p + t); }
  /// The matrix of a unit-frame quadric in the world frame: H^T A H, H = the inverse placement.
  Mat4<Q> quadric(const Mat4<Q>& A) const {
    Mat4<Q> H = Mat4<Q>::Identity();
    for (int i = 0; i < 3; ++i) {
      H(i, i) = Q(1) / s;
      H(i, 3) = -t(i) / s;
    }
    return H.transpose() * A * H;
  }
};

std::string matrix_text(const Mat4<Q>& A) {
  std::string m = "[";
  for (int i = 0; i < 4; ++i) {
    m += i ? ", [" : "[";
    for (int j = 0; j < 4; ++j) m += (j ? ", " : "") + text(A(i, j));
    m += "]";
  }
  return m + "]";
}

/// One shape of the scene format in the unit frame, written for a placement, with lights of every kind.
struct Case {
  std::string name;
  std::function<std::string(const Placement&)> quadric;  ///< the "quadrics" entry
  std::vector<Vec3<Q>> points;                             ///< point lights (unit frame): outside, inside, on the surface
};

std::vector<Case> cases() {
  const Vec3<Q> c(Q(1, 2), Q(-1, 4), Q(1, 3));
  std::vector<Case> out;
  out.push_back({"sphere",
                 [c](const Placement& pl) {
                   return R"({"id": "q", "sphere": {"center": )" + vec3(pl.point(c)) + R"(, "radius": )" + text(pl.s) + "}}";
                 },
                 {Vec3<Q>(3, 4, 5), c, Vec3<Q>(c + Vec3<Q>(Q(3, 5), Q(4, 5), 0))}});
  out.push_back({"ellipsoid (non-orthogonal axes)",
                 [c](const Placement& pl) {
                   return R"({"id": "q", "ellipsoid": {"center": )" + vec3(pl.point(c)) + R"(, "radii": )" +
                          vec3(Vec3<Q>(pl.s, pl.s / 2, pl.s / 3)) +
                          R"(, "axes": [[1, "1/5", 0], [0, 1, "1/7"], ["1/3", 0, 1]]}})";
                 },
                 {Vec3<Q>(3, 4, 5), c, Vec3<Q>(c + Vec3<Q>(1, 0, Q(1, 3)))}});
  out.push_back({"cylinder",
                 [](const Placement& pl) {
                   return R"({"id": "q", "cylinder": {"point": )" + vec3(pl.point(Vec3<Q>(0, 1, 0))) +
                          R"(, "axis": [1, 2, 2], "radius": )" + text(pl.s / 2) + "}}";
                 },
                 {Vec3<Q>(3, -4, 5), Vec3<Q>(0, 1, 0), Vec3<Q>(Q(0), Q(1), Q(0)) + Vec3<Q>(0, Q(3, 10), Q(-3, 10)) * Q(1)}});
  out.push_back({"cone (light at the apex too)",
                 [](const Placement& pl) {
                   return R"({"id": "q", "cone": {"apex": )" + vec3(pl.point(Vec3<Q>(0, 0, 1))) +
                          R"(, "axis": [0, 0, 1], "tan_half_angle": "1/2"}})";
                 },
                 {Vec3<Q>(3, 4, 5), Vec3<Q>(0, 0, 1), Vec3<Q>(0, 0, 3), Vec3<Q>(1, 0, 3)}});
  out.push_back({"plane pair (degenerate)",
                 [](const Placement& pl) {
                   const Vec4<Q> u(1, 0, 0, -1), v(0, 1, 0, -2);
                   return R"({"id": "q", "matrix": )" +
                          matrix_text(pl.quadric(Mat4<Q>(u * v.transpose() + v * u.transpose()))) + "}";
                 },
                 {Vec3<Q>(3, 4, 5), Vec3<Q>(1, 5, 7), Vec3<Q>(1, 2, 0)}});
  out.push_back({"hyperboloid of one sheet",
                 [](const Placement& pl) {
                   Mat4<Q> A = Mat4<Q>::Zero();
                   A(0, 0) = 1, A(1, 1) = 1, A(2, 2) = -1, A(3, 3) = -1;
                   return R"({"id": "q", "matrix": )" + matrix_text(pl.quadric(A)) + "}";
                 },
                 {Vec3<Q>(3, 4, 5), Vec3<Q>(0, 0, 0), Vec3<Q>(1, 0, 0), Vec3<Q>(0, 0, 7)}});
  return out;
}

std::string scene_for(const Case& k, const Placement& pl) {
  std::string lights;
  for (std::size_t i = 0; i < k.points.size(); ++i)
    lights += R"({"id": "p)" + std::to_string(i) + R"(", "position": )" + vec3(pl.point(k.points[i])) + "}, ";
  lights += R"({"id": "sun", "direction": [1, 2, -3]}, {"id": "flat", "direction": [1, 2, 0]})";
  return R"({"format": "qverify-scene/1", "name": "case", "quadrics": [)" + k.quadric(pl) + R"(], "lights": [)" + lights +
         R"(], "mirrors": [{"id": "m", "plane": [1, 2, 2, 3]}]})";
}


}  // namespace

TEST_CASE("status words are the exact ones in every precision and method, under any units and placement",
          "[verdicts][status]") {
  const char* precisions[] = {"float", "double", "long-double", "float128", "mpfr:64", "interval"};
  std::map<std::string, int> seen;  // every status word must occur in the sweep
  int compared = 0;
  for (const Case& k : cases())
    for (int e : {-9, -3, 0, 3, 9})
      for (const Vec3<Q>& t : {Vec3<Q>(0, 0, 0), Vec3<Q>(pow10(9), Q(-1, 3) * pow10(8), Q(7))}) {
        const Placement pl{pow10(e), t};
        const Scene sc = parse_scene(scene_for(k, pl), "case.json");
        for (Method m : {Method::direct, Method::paper}) {
          const ResultSet ex = computed_results(sc, *parse_precision("exact"), m, std::nullopt, std::nullopt);
          for (const char* p : precisions) {
            INFO(k.name << " scale 1e" << e << " translated " << (t.isZero() ? "no" : "yes") << " method "
                        << method_name(m) << " precision " << p);
            const ResultSet rs = computed_results(sc, *parse_precision(p), m, std::nullopt, std::nullopt);
            for (std::size_t i = 0; i < rs.shadows.size(); ++i) {
              INFO("light " << sc.lights[sc.shadows[i].other].id);
              CHECK(rs.shadows[i].status == ex.shadows[i].status);
              seen[ex.shadows[i].status]++;
              ++compared;
            }
            for (std::size_t i = 0; i < rs.reflections.size(); ++i) CHECK(rs.reflections[i].status == ex.reflections[i].status);
          }
        }
      }
  for (const char* w : {"ok", "degenerate-quadric", "light-on-surface", "no-real-silhouette", "singular-frame"}) {
    INFO(w);
    CHECK(seen[w] > 0);
  }
  CHECK(compared > 2000);
}

TEST_CASE("the floating filter never decides a predicate wrongly, and settling gives the exact answer",
          "[verdicts][status][filter]") {
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<int> small(-4, 4), expo(-60, 60);
  auto dyadic = [&](int k) { return std::ldexp(static_cast<double>(small(rng)), k); };
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int decided_by_filter = 0, settled = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Mat4<double> A;
    Vec4<double> L;
    const int kind = trial % 6;
    const int k = expo(rng);
    if (kind == 0) {  // exactly rank 2 in doubles: a plane pair of small dyadic vectors
      Vec4<double> u, v;
      for (int i = 0; i < 4; ++i) u(i) = dyadic(k), v(i) = dyadic(-k / 2);
      A = u * v.transpose() + v * u.transpose();
    } else if (kind == 5) {  // a plane pair of full-mantissa vectors, rounded: rank 4 by a hair, adj A rounding noise
      Vec4<double> u, v;
      for (int i = 0; i < 4; ++i) u(i) = std::ldexp(unit(rng), k), v(i) = unit(rng);
      A = u * v.transpose() + v * u.transpose();
    } else if (kind == 4) {  // a sphere; below, a light on it in full-mantissa doubles (L^T A L tiny, either sign)
      A = Vec4<double>(1, 1, 1, -1).asDiagonal();
      A *= std::ldexp(1.0, k);
    } else {  // a random symmetric matrix, sometimes nudged by one ulp off a degenerate one
      for (int i = 0; i < 4; ++i)
        for (int j = i; j < 4; ++j) A(i, j) = A(j, i) = dyadic(k) + (kind == 2 ? std::ldexp(1.0, k - 60) : 0.0);
    }
    for (int i = 0; i < 4; ++i) L(i) = dyadic(0);
    if (kind == 3) L(3) = 0;  // a light at infinity
    if (kind == 4) {
      const double a = 3 * unit(rng), b = 1.5 * unit(rng);
      L = Vec4<double>(std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b), 1);
    }
    const ShadowResult<double> r = shadow<double>(A, L, Method::direct);
    const StatusDecision exact = shadow_status<Q>(exact_matrix(A), exact_matrix(L));
    INFO("trial " << trial);
    // what the filter decided is exact
    CHECK((r.flags & ~r.undecided) == (exact.flags & ~r.undecided));
    if (r.undecided == 0) ++decided_by_filter;
    ShadowResult<double> s = r;
    settle_status(s, A, L);
    if (r.undecided != 0) ++settled;
    CHECK(s.undecided == 0);
    CHECK(s.flags == exact.flags);
    ReflectionResult<double> b = reflection_in_plane<double>(A, Vec4<double>(1, 2, 2, 3), Method::direct);
    settle_status(b, A);
    CHECK(b.degenerate == (degenerate_quadric<Q>(exact_matrix(A)) == Truth::yes));
  }
  CHECK(decided_by_filter > 1000);  // the filter does most of the work ...
  CHECK(settled > 500);             // ... and the exact fall-back is exercised, on rounding noise too
}

namespace {

/// The geometric error of every item as verify measures it on other points (seed 99, 128 per item).
std::vector<double> measured_errors(const Scene& sc, const ResultSet& rs) {
  VerifyOptions opt;
  opt.samples = 128;
  opt.seed = 99;
  const VerifyReport v = verify_results(sc, rs, opt);
  std::vector<double> out;
  const auto v_doc = verify_document(sc, v);
  for (const auto& c : v_doc["checks"]) {
    if (c["status"] == "skipped") out.push_back(-1);
    else out.push_back(c["geometric_error"].is_null() ? INFINITY : c["geometric_error"].get<double>());
  }
  return out;
}

/// Every item's flag against its measured error: raised where the error exceeds T, not raised below T/100.
void check_flags(const Scene& sc, const ResultSet& rs, int& raised) {
  const std::vector<double> err = measured_errors(sc, rs);
  std::size_t i = 0;
  auto check = [&](const std::optional<ItemAccuracy>& acc) {
    const double e = err[i++];
    REQUIRE(acc);
    if (e < 0) return;  // nothing to measure on
    INFO("item " << i - 1 << " measured geometric error " << e << " bound " << (acc->bound ? *acc->bound : -1.0));
    if (e > kDefaultAccuracy) CHECK(acc->inaccurate);
    if (e < kDefaultAccuracy / 100) CHECK(!acc->inaccurate);
    if (acc->bound) CHECK(*acc->bound >= e / 2);  // the bound is measured on other points than e
    raised += acc->inaccurate;
  };
  for (const auto& s : rs.shadows) check(s.accuracy);
  for (const auto& r : rs.reflections) check(r.accuracy);
}

}  // namespace

TEST_CASE("the paper route as l_z -> 0 is flagged exactly where its geometric error exceeds the target",
          "[verdicts][accuracy]") {
  int raised = 0;
  for (int k = 1; k <= 14; ++k) {
    INFO("l_z = 1e-" << k);
    const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "lz", "quadrics": [{"id": "ball", "sphere":
        {"center": [0, 0, -3], "radius": 1}}], "lights": [{"id": "lamp", "position": [2, 1, "1e-)" +
                                     std::to_string(k) + R"("]}]})",
                                 "lz.json");
    check_flags(sc, computed_results(sc, *parse_precision("double"), Method::paper), raised);
  }
  CHECK(raised >= 3);  // the paper's 1/l_z does break
}

TEST_CASE("flags are right for float, the naive world frame far away, and not raised on the default path",
          "[verdicts][accuracy]") {
  int raised = 0;
  for (const char* name : {"ball-lamp-floor.json", "egg-sun-wall.json", "mixed-requests.json"}) {
    INFO(name);
    const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/" + name);
    int none = 0;
    check_flags(sc, computed_results(sc, *parse_precision("double"), Method::direct), none);
    CHECK(none == 0);  // the robust default path is accurate on the examples
    check_flags(sc, computed_results(sc, *parse_precision("float"), Method::direct), raised);
  }
  CHECK(raised > 0);
  const Scene far = parse_scene(R"({"format": "qverify-scene/1", "name": "far", "quadrics": [{"id": "ball", "sphere":
      {"center": [37000000.25, 1.5, -2], "radius": 0.001}}], "lights": [{"id": "lamp", "position": [37000000.5, 2, 3]}],
      "mirrors": [{"id": "m", "plane": [1, 0, 0, -37000010]}]})",
                                "far.json");
  int world = 0, local = 0;
  check_flags(far, computed_results(far, *parse_precision("double"), Method::direct, Frame::world), world);
  CHECK(world == 2);
  check_flags(far, computed_results(far, *parse_precision("double"), Method::direct), local);
  CHECK(local == 0);
}

TEST_CASE("no flag on accurate results where R's planes cross: a paraboloid, a hyperboloid lit from inside its waist",
          "[verdicts][accuracy][frames]") {
  // Both were flagged (bounds 1.9e-8 and 5.5e-9, about 1e-17 attained on the sampled points) in their own
  // frames: the paraboloid's terminator meets h; the hyperboloid's does not, but R's crossing line passes
  // through the ball its unbounded terminator is bounded in. The frame at the light's height makes R exact.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "crossing", "quadrics": [
      {"id": "par", "coefficients": {"xx": 1, "yy": 1, "z": -1}},
      {"id": "hyp", "coefficients": {"xx": 1, "yy": 1, "zz": -1, "c": -1}}],
      "lights": [{"id": "high", "position": [3.3, 4.1, 7.9]}, {"id": "waist", "position": [0.8, 0.2, 0.3]}],
      "requests": {"shadows": [{"quadric": "par", "light": "high"}, {"quadric": "hyp", "light": "waist"}]}})",
                               "crossing.json");
  const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
  REQUIRE(rs.shadows.size() == 2);
  for (const ShadowMatrices& s : rs.shadows) {
    REQUIRE(s.accuracy);
    REQUIRE(s.origin);
    CHECK((*s.origin)(0) == 0);
    CHECK_FALSE(s.accuracy->inaccurate);
  }
  CHECK((*rs.shadows[0].origin)(2) == to_rational(7.9));
  CHECK((*rs.shadows[1].origin)(2) == to_rational(0.3));
  int raised = 0;
  check_flags(sc, rs, raised);
  CHECK(raised == 0);
  CHECK(verify_results(sc, rs, VerifyOptions{}).failed == 0);
}

TEST_CASE("eval --tolerance: every item has an error_bound, and its flag agrees with verify", "[verdicts][accuracy]") {
  // Entries certified to 1e-12 of the exact ones are no geometric guarantee: a small sphere far away
  // needs more digits than a double entry of its world matrix has (issue 15's far sphere).
  const char* far = R"({"format": "qverify-scene/1", "name": "far", "quadrics": [{"id": "ball", "sphere":
      {"center": [37000000.1, 0.3, 0.7], "radius": 0.001}}], "lights": [{"id": "lamp", "position": [37000000.3, 0.5, 2.1]}],
      "mirrors": [{"id": "m", "plane": [0.3, 0.1, 1, -0.2]}]})";
  int flagged = 0;
  for (const std::string& text : {std::string(far), read_text_file(std::string(QVERIFY_SCENES) + "/mixed-requests.json", 1 << 20)}) {
    const Scene sc = parse_scene(text, "scene.json");
    const auto doc = eval_json(adaptive_eval_report(sc, Method::direct, 1e-12));
    const ResultSet rs = candidate_results_text(sc, doc.dump(), "adaptive.json", *parse_precision("double"));
    const auto checks = verify_document(sc, verify_results(sc, rs, VerifyOptions{}))["checks"];
    std::size_t k = 0;
    for (const char* kind : {"shadows", "reflections"})
      for (const auto& item : doc[kind]) {
        INFO(sc.name << " " << kind << " " << item.dump());
        REQUIRE(item.contains("error_bound"));
        const bool inaccurate = std::find(item["flags"].begin(), item["flags"].end(), "inaccurate") != item["flags"].end();
        CHECK(inaccurate == (item["error_bound"].get<double>() > kDefaultAccuracy));
        CHECK(inaccurate == (checks[k++]["status"] == "fail"));
        flagged += inaccurate;
      }
  }
  // the far sphere's shadow and reflection. (The example's pipe: its R in world coordinates, this
  // evaluation's frame, is 9.04e-10 of its size off where its planes cross the terminator, at the
  // lamp's height, 6.7 along the axis from the lamp's foot, within the 8 sampled either side
  // (ParallelPair): of the order of sqrt(eps), just within the target. Bounded at 9.0375e-10 in small
  // balls about those points (crossing_split), it is not flagged; bounded about the ball's centre, at
  // 2.8e-9, it was.)
  CHECK(flagged == 2);
}

TEST_CASE("eval --tolerance: statuses and their flags are the exact predicates, as in every mode", "[verdicts][accuracy]") {
  // A light exactly on an ellipsoid at a point of non-dyadic coordinates, and one 1e-30 inside it: the
  // floating filter cannot decide either, the exact stage does. The adaptive mode took the status
  // word from it but the flags from double's undecided ones: [] (audit 37b F1).
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "quadrics": [{"id": "egg", "matrix":
      [["1/4", 0, 0, 0], [0, "1/9", 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]}], "lights": [{"id": "on", "position":
      ["4/3", 2, "1/3"]}, {"id": "in", "position": ["4/3", 2, "0.333333333333333333333333333333323333"]}],
      "mirrors": [{"id": "m", "plane": [0, 0, 1, 0]}]})", "scene.json");
  const auto plain = eval_json(eval_report(sc, *parse_precision("double"), Method::direct, std::nullopt, AccuracyOptions{}));
  const auto adaptive = eval_json(adaptive_eval_report(sc, Method::direct, 1e-6));
  REQUIRE(plain["shadows"].size() == 2);
  CHECK(plain["shadows"][0]["status"] == "light-on-surface");
  CHECK(plain["shadows"][1]["status"] == "no-real-silhouette");
  for (const char* kind : {"shadows", "reflections"})
    for (std::size_t k = 0; k < plain[kind].size(); ++k) {
      INFO(kind << " " << k);
      CHECK(adaptive[kind][k]["status"] == plain[kind][k]["status"]);
      CHECK(adaptive[kind][k]["flags"] == plain[kind][k]["flags"]);
    }
  CHECK(adaptive["shadows"][0]["flags"] == nlohmann::ordered_json::array({"light-on-surface"}));
}

TEST_CASE("qverify's own eval document, read back as a candidate, passes: far origins survive the JSON text",
          "[verdicts][verify]") {
  // A unit sphere reflected 1e12 away: eval writes the image in a local frame whose origin (a double of
  // about 5.7e11) is written as its shortest text; taken exactly, that text is 1e-5 off the double.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "far mirror", "quadrics": [{"id": "ball",
      "sphere": {"center": ["1/2", "1/4", 0], "radius": 1}}], "lights": [{"id": "lamp", "position": [3, 4, 8]}],
      "mirrors": [{"id": "m", "plane": [2, 3, 6, "-7000000000000"]}]})",
                               "far-mirror.json");
  const auto doc = eval_json(eval_report(sc, *parse_precision("double"), Method::direct, std::nullopt, AccuracyOptions{}));
  REQUIRE(doc["reflections"][0].contains("origin"));
  const ResultSet rs = candidate_results_text(sc, doc.dump(), "eval.json", *parse_precision("double"));
  const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
  INFO(verify_document(sc, v).dump(1));
  CHECK(v.failed == 0);
  CHECK(v.passed == 2);
}

TEST_CASE("a candidate's numbers are the values of its precision: eval's document read back is judged as computed",
          "[verdicts][verify][candidate]") {
  // A double document holds doubles written as the shortest text that round-trips (0.01484375 for the
  // double nearest 19/1280); read as the decimals they spell, the results judged were other numbers
  // than the program's (mixed-requests' pipe: on_P 0 where the doubles are 8.6e-18 off).
  for (const char* name : {"mixed-requests", "ball-lamp-floor", "egg-sun-wall", "far-ball-lamp-floor"}) {
    for (const char* precision : {"float", "double", "long-double", "float128"}) {
      INFO(name << " " << precision);
      const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/" + name + ".json");
      const Precision prec = *parse_precision(precision);
      const auto doc = eval_json(eval_report(sc, prec, Method::direct, std::nullopt, AccuracyOptions{}));
      const VerifyReport computed = verify_results(sc, computed_results(sc, prec, Method::direct), VerifyOptions{16, 3});
      const VerifyReport read =
          verify_results(sc, candidate_results_text(sc, doc.dump(), "eval.json", prec), VerifyOptions{16, 3});
      REQUIRE(read.checks.size() == computed.checks.size());
      for (std::size_t k = 0; k < read.checks.size(); ++k) {
        const auto& a = computed.checks[k].report;
        const auto& b = read.checks[k].report;
        REQUIRE(a.has_value() == b.has_value());
        if (!a) continue;
        CHECK(a->passed == b->passed);
        for (const QuadricCheck& q : a->checks) {
          if (!q.judged) continue;  // on_A: the quadric as each side holds it
          const QuadricCheck* r = b->find(q.name);
          REQUIRE(r);
          CHECK(q.geometric_error == r->geometric_error);
          CHECK(q.metric.residual == r->metric.residual);
        }
      }
    }
  }
}

TEST_CASE("an origin in a float document is the double it is written as", "[verdicts][verify][candidate]") {
  // A sphere lit from the side at height 0.3: eval computes the item in a frame at the light's height,
  // the double nearest 0.3 (not a float). Read back from eval's float document, that origin stays the
  // double: rounded to the document's float it moved the frame by 1.2e-8 and the results judged were
  // not the ones computed.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "side light",
      "quadrics": [{"id": "ball", "sphere": {"center": [0, 0, 0], "radius": 1}}],
      "lights": [{"id": "lamp", "position": [3, 0, 0.3]}], "requests": {"reflections": []}})",
                               "side.json");
  const Precision flt = *parse_precision("float");
  const auto doc = eval_json(eval_report(sc, flt, Method::direct, std::nullopt, AccuracyOptions{}));
  REQUIRE(doc["shadows"][0].contains("origin"));
  const ResultSet read = candidate_results_text(sc, doc.dump(), "eval.json", flt);
  REQUIRE(read.shadows.size() == 1);
  REQUIRE(read.shadows[0].origin);
  CHECK((*read.shadows[0].origin)(2) == to_rational(0.3));
  const VerifyReport computed = verify_results(sc, computed_results(sc, flt, Method::direct), VerifyOptions{16, 3});
  const VerifyReport judged = verify_results(sc, read, VerifyOptions{16, 3});
  REQUIRE(computed.checks[0].report);
  REQUIRE(judged.checks[0].report);
  CHECK(computed.checks[0].report->geometric_error == judged.checks[0].report->geometric_error);
}

namespace {

ResultSet exact_results(const Scene& sc, std::optional<Frame> frame = std::nullopt) {
  return computed_results(sc, *parse_precision("exact"), Method::direct, frame, std::nullopt);
}

/// The exact results rounded to nearest double, entry by entry: a double candidate.
ResultSet rounded(ResultSet rs) {
  rs.precision = *parse_precision("double");
  auto round = [](auto& m) {
    RoundingReport rep;
    for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = to_rational(round_rational<double>(m(i), rep));
  };
  for (auto& s : rs.shadows) round(s.P), round(s.R), round(s.polar);
  for (auto& r : rs.reflections) round(r.M), round(r.B);
  return rs;
}

int failures(const Scene& sc, const ResultSet& rs) { return verify_results(sc, rs, VerifyOptions{}).failed; }

}  // namespace

TEST_CASE("eval flags a result of the wrong sign, which no geometric error sees, as verify fails it",
          "[verdicts][accuracy]") {
  // A light on a cylinder 1e9 away, by the paper's route in world coordinates: P = -(A L)(A L)^T (s = 0)
  // came out with the opposite sign, its zero set right (error_bound 1.2e-16), unflagged.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "sign", "quadrics": [{"id": "cy", "cylinder":
      {"point": [1000000000.1, -999999999.8, 1000000000.3], "axis": [0, 0, 1], "radius": 0.7}}],
      "lights": [{"id": "on", "position": [1000000000.8, -999999999.8, 1000000000.3]}]})",
                               "sign.json");
  const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::paper);
  REQUIRE(rs.shadows.size() == 1);
  const ShadowMatrices& s = rs.shadows[0];
  REQUIRE(s.accuracy);
  INFO(s.accuracy->reason);
  CHECK(s.accuracy->inaccurate);
  CHECK_FALSE(s.accuracy->bound);
  CHECK(s.accuracy->reason.find("wrong sign") != std::string::npos);
  CHECK(failures(sc, rs) == 1);
  // the sign judged directly: -P fails where P passes, for every example item
  for (const char* name : {"ball-lamp-floor.json", "mixed-requests.json"}) {
    const Scene ex = load_scene(std::string(QVERIFY_SCENES) + "/" + name);
    const ResultSet good = exact_results(ex);
    const TypedScene<Q> t = typed_scene<Q>(ex);
    for (std::size_t k = 0; k < good.shadows.size(); ++k) {
      if (!good.shadows[k].present) continue;
      const Pair& p = ex.shadows[k];
      const ShadowMatrices& g = good.shadows[k];
      CHECK(shadow_sign_problems(t.A[p.quadric], t.L[p.other], &g.P, &g.polar).empty());
      const Mat4<Q> minus = -g.P;
      const Vec4<Q> flipped = -g.polar;
      CHECK(shadow_sign_problems(t.A[p.quadric], t.L[p.other], &minus, nullptr).size() == 1);
      CHECK(shadow_sign_problems(t.A[p.quadric], t.L[p.other], nullptr, &flipped).size() == 1);
      CHECK(shadow_sign_problems(t.A[p.quadric], t.L[p.other], &minus, &flipped).size() == 2);  // both named
    }
  }
}

TEST_CASE("eval's own results pass verify at every seed: a cylinder's frame at the light's height", "[verdicts][verify]") {
  // The pipe of mixed-requests.json (axis (0, 1, 1), radius 1/2, its lamp's foot on the axis 4.75 below
  // the lamp): computed on the axis at the foot, its R rounded there is about sqrt(eps) off where h
  // crosses the terminator, inside the ball about the samples at seeds 2, 3, 4, 6 and 8 (bounds about
  // 7e-9), and verify failed eval's own double results there; at the light's height R rounds as pi does.
  const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/mixed-requests.json");
  const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    INFO("seed " << seed);
    VerifyOptions opt;
    opt.seed = seed;
    CHECK(verify_results(sc, rs, opt).failed == 0);
  }
}

TEST_CASE("eval's own results pass verify on a cylinder whose axis is 1e-9 from level", "[verdicts][verify]") {
  // Random chords met its terminator lines as far out as they were near parallel to them: a chord
  // along x met them 3e8 out, the object size was that, and the double results' bounds over a ball of
  // 3e8 (1.3e-9 to 0.13) flagged them and failed verify against errors of 1e-25 sampled (audit 32a).
  // Now a parallel pair is sampled within 16 half-widths of its middle.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "nearh", "quadrics": [{"id": "c",
      "cylinder": {"point": [1, 2, 3], "axis": [1, 0, "1e-9"], "radius": 1}}], "lights": [
      {"id": "near", "position": [2, 1, 5]}, {"id": "level", "position": [3, -2, 3]},
      {"id": "far", "position": [100000000, 20000000, 30000000]}, {"id": "high", "position": [0, 0, 100000000]},
      {"id": "sun", "direction": [1, 1, -2]}]})", "nearh.json");
  const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
  for (std::size_t k = 0; k < rs.shadows.size(); ++k) {
    INFO("shadow " << k);
    REQUIRE(rs.shadows[k].accuracy);
    CHECK(!rs.shadows[k].accuracy->inaccurate);
  }
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    INFO("seed " << seed);
    VerifyOptions opt;
    opt.seed = seed;
    const auto report = verify_results(sc, rs, opt);
    CHECK(report.failed == 0);
  }
}

TEST_CASE("verify: the correctly rounded result passes, one entry off by 1e-7 fails", "[verdicts][verify]") {
  for (const char* name : {"ball-lamp-floor.json", "egg-sun-wall.json", "mixed-requests.json"}) {
    INFO(name);
    const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/" + name);
    // rounded in eval's own frame: in world coordinates the pipe's R, a plane pair, is about sqrt(eps)
    // off where its planes cross the terminator (at the lamp's height, within the stretch sampled),
    // truly, and fails; the world R passed only while the samples happened to stop short of there
    const ResultSet good = rounded(exact_results(sc, Frame::local));
    CHECK(failures(sc, good) == 0);
    if (std::string(name) == "mixed-requests.json") CHECK(failures(sc, rounded(exact_results(sc))) == 1);
    for (std::size_t k = 0; k < good.shadows.size(); ++k) {
      if (!good.shadows[k].present) continue;
      ResultSet bad = good;
      Mat4<Q>& P = bad.shadows[k].P;
      const Eigen::Index p = pivot_index(P);
      // one off-pivot entry (and its mirror) moved by 1e-7 of the largest entry
      const int i = static_cast<int>(p % 4), j = (i + 1) % 4;
      const Q d = max_abs(P) / 10000000;
      P(i, j) += d;
      P(j, i) += d;
      INFO("shadow " << k);
      CHECK(verify_document(sc, verify_results(sc, bad, VerifyOptions{}))["checks"][k]["status"] == "fail");
    }
  }
}

TEST_CASE("verify: wrong cones, planes and signs fail - also in exact arithmetic", "[verdicts][verify]") {
  const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/ball-lamp-floor.json");
  const ResultSet good = exact_results(sc);
  REQUIRE(failures(sc, good) == 0);
  for (int bug = 0; bug < 8; ++bug) {
    ResultSet bad = good;
    for (auto& s : bad.shadows) {
      const Vec4<Q> pi = s.polar;
      const Mat4<Q> ppT = pi * pi.transpose();
      switch (bug) {
        case 0: s.P = s.P - ppT; break;                  // s A - 2 (AL)(AL)^T: P L != 0, not a cone
        case 1: s.P = s.P + Q(2) * ppT; break;           // s A + (AL)(AL)^T: the sign of the outer product flipped
        case 2: s.P = -s.P; break;                       // negative factor
        case 3: s.polar = -s.polar; break;               // polar plane of the wrong orientation
        case 4: s.R = s.R + Q(1, 1000) * ppT; break;     // R through the terminator but not the plane pair
        case 5: s.status = "no-real-silhouette"; break;  // a status the exact inputs do not give
        default: break;
      }
    }
    for (auto& r : bad.reflections) {
      if (bug == 6) r.B = -r.B;  // B with a negative factor
      if (bug == 7) r.M(0, 3) += 1;  // M not the reflection (B itself right)
    }
    INFO("bug " << bug);
    CHECK(failures(sc, bad) > 0);
    // the same slips, rounded to double, fail too
    CHECK(failures(sc, rounded(bad)) > 0);
  }
}

TEST_CASE("verify: R's second plane is checked away from the line where R's planes cross", "[verdicts][verify]") {
  // A vertical cylinder's polar plane is vertical: the point of h above the section's centre lies on
  // the line where R's planes cross, where R's gradient vanishes and a first-order distance from a rounded R
  // measured 0.096: accurate double results failed. The same for a point sphere (one terminator point, size 0).
  for (const char* quadric : {R"({"id": "q", "cylinder": {"point": [0.1, 0.2, 0.3], "axis": [0, 0, 1], "radius": 0.7}})",
                              R"({"id": "q", "sphere": {"center": [0.1, 0.2, 0.3], "radius": 0}})"}) {
    INFO(quadric);
    const Scene sc = parse_scene(std::string(R"({"format": "qverify-scene/1", "name": "h", "quadrics": [)") + quadric +
                                     R"(], "lights": [{"id": "lamp", "position": [3.3, 4.1, 7.9]}, {"id": "near",
                                     "position": [0.8, 0.2, 0.3]}]})",
                                 "h.json");
    for (const char* precision : {"double", "long-double"})
      CHECK(verify_results(sc, computed_results(sc, *parse_precision(precision), Method::direct), {}).failed == 0);
    // an R through the terminator (the polar plane's pair) whose second plane is h tilted by 1/1000: fails
    const ResultSet good = exact_results(sc);
    REQUIRE(failures(sc, good) == 0);
    ResultSet bad = good;
    for (std::size_t k = 0; k < bad.shadows.size(); ++k) {
      auto& s = bad.shadows[k];
      const Q lz = k == 0 ? Q(79, 10) : Q(3, 10);
      const Vec4<Q> tilted(Q(1, 1000), 0, 1, -lz);
      s.R = s.polar * tilted.transpose() + tilted * s.polar.transpose();
    }
    CHECK(failures(sc, bad) == 2);
    CHECK(failures(sc, rounded(bad)) == 2);
  }
}

TEST_CASE("verify: a far-away candidate computed naively in world coordinates fails", "[verdicts][verify]") {
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "far", "quadrics": [{"id": "ball", "sphere":
      {"center": [37000000.25, 1.5, -2], "radius": 0.001}}], "lights": [{"id": "lamp", "position": [37000000.5, 2, 3]}],
      "mirrors": [{"id": "m", "plane": [1, 0, 0, -37000010]}]})",
                               "far.json");
  const VerifyReport naive = verify_results(sc, computed_results(sc, *parse_precision("double"), Method::direct, Frame::world), {});
  CHECK(naive.failed == 2);
  const auto naive_doc = verify_document(sc, naive);
  for (const auto& c : naive_doc["checks"]) {
    CHECK(c["consistent_with_precision"].get<bool>());  // as good as world-frame doubles can be ...
    CHECK(c["geometric_error"].get<double>() > 1);      // ... and still wrong by more than the object's size
  }
  CHECK(verify_results(sc, computed_results(sc, *parse_precision("double"), Method::direct), {}).failed == 0);
}

namespace {
/// A scene of the quadric q (its JSON object) 3e7 from the world origin, a lamp beside it and a mirror
/// beyond it.
Scene far_scene(const std::string& q) {
  return parse_scene(R"({"format": "qverify-scene/1", "name": "far", "quadrics": [)" + q +
                         R"(], "lights": [{"id": "lamp", "position": [30000003, 2, 5]}],
                         "mirrors": [{"id": "m", "plane": [1, 0, 0, -30000010]}]})",
                     "far.json");
}
}  // namespace

TEST_CASE("a far object given as a matrix or as coefficients gets its local frame, and verify passes it",
          "[verdicts][frames]") {
  // the sphere |x - c|^2 = 1/4 with c = (3e7 + 1/2, -2, 1), written as a matrix and as coefficients
  const std::string matrix = R"({"id": "ball", "matrix": [[1, 0, 0, "-60000001/2"], [0, 1, 0, 2], [0, 0, 1, -1],
      ["-60000001/2", 2, -1, "3600000120000020/4"]]})";
  const std::string coefficients = R"({"id": "ball", "coefficients": {"xx": 1, "yy": 1, "zz": 1, "x": -60000001,
      "y": 4, "z": -2, "c": "900000030000005"}})";
  for (const std::string& q : {matrix, coefficients}) {
    INFO(q);
    const Scene sc = far_scene(q);
    const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
    REQUIRE(rs.shadows[0].origin);
    CHECK(*rs.shadows[0].origin == Vec3<Q>(Q(60000001, 2), -2, 1));  // the centre, not its mirror image
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    CHECK(v.failed == 0);
    const auto v_doc = verify_document(sc, v);
    for (const auto& c : v_doc["checks"]) CHECK(c["geometric_error"].get<double>() < 1e-12);
  }
}

TEST_CASE("R off where no sample is: certified where h is parallel to the polar plane, at any count", "[verdicts][verify]") {
  // A lamp straight above a level cylinder's axis: the polar plane is parallel to h, and R's floor
  // |h . x| (one number there) was not found, so R was judged on its samples alone, and an R 8.2e-6
  // off away from the one chord that 1 or 2 samples draw passed (audit 33a F1).
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "top", "quadrics": [{"id": "c", "cylinder":
      {"point": [0, 2, 3], "axis": [1, 0, 0], "radius": "3/2"}}], "lights": [{"id": "lamp", "position": [0, 2, 5]}]})",
                               "top.json");
  ResultSet rs = exact_results(sc);
  rs.precision = *parse_precision("double");  // (a floating candidate: judged by its geometric error)
  REQUIRE(rs.shadows.size() == 1);
  const Vec4<Q> h = reference_second_plane(Vec4<Q>(0, 2, 5, 1)), w(1, -16, 0, 32);
  Mat4<Q>& R = rs.shadows[0].R;
  R += max_abs(R) / 10000000 * Mat4<Q>(h * w.transpose() + w * h.transpose());
  for (int n : {1, 2, 64}) {
    INFO(n << " samples");
    VerifyOptions opt;
    opt.samples = n;
    CHECK(verify_results(sc, rs, opt).failed == 1);
    // the same R as an exact candidate: not proportional to the exact one, whatever the samples
    ResultSet exact = rs;
    exact.precision = *parse_precision("exact");
    CHECK(verify_results(sc, exact, opt).failed == 1);
    CHECK(verify_results(sc, exact_results(sc), opt).failed == 0);
  }
}

TEST_CASE("a parabolic cylinder lit from afar: its gradient floor grows with the distance", "[verdicts][verify]") {
  // (3 y - 4 z)^2 / 25 = (4 y + 3 z) / 5, lit from 1e8 straight down its axis: the terminator's points
  // lie 1e4 from the vertex line, where the gradient is about 2e4, but the floor of a parabolic
  // cylinder (a plane for a kernel) stayed |k_n| = 1/2, and eval's own results, 1.1e-10 off, were bounded
  // at 2.2e-6, flagged and failed (audit 33a F2)
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "pc", "quadrics": [{"id": "r", "coefficients":
      {"yy": "9/25", "zz": "16/25", "yz": "-24/25", "y": "-4/5", "z": "-3/5"}}],
      "lights": [{"id": "c", "position": ["3/10", "-80000000", "-60000000"]}]})", "pc.json");
  const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
  REQUIRE(rs.shadows.size() == 1);
  REQUIRE(rs.shadows[0].accuracy);
  REQUIRE(rs.shadows[0].accuracy->bound);
  CHECK(*rs.shadows[0].accuracy->bound < 1e-9);
  CHECK(!rs.shadows[0].accuracy->inaccurate);
  CHECK(verify_results(sc, rs, VerifyOptions{}).failed == 0);
}

TEST_CASE("a cone is computed at its apex (or above it at a lamp's height) in any units", "[verdicts][frames]") {
  // A cone's rounded matrix is a hyperboloid about sqrt(eps) |apex| off near its apex, where its
  // gradient vanishes: a cone at (0, 0, 5) kept the world frame (its "size" was 1, in the scene's units:
  // a frame only beyond 64 units) and its double P under a parallel light was flagged (audit 31a F6;
  // this one at 9e-9 and 1.3e-9, and at 3.2e-8 and 7.1e-9 scaled by 3, not scaled by 2^-6): no flag
  // in any units now.
  for (const Q& k : {Q(1), Q(1, 64), Q(3)}) {
    INFO("scale " << k);
    const auto num = [&](const Q& v) { return "\"" + Q(v * k).str() + "\""; };
    const std::string text = std::string(R"({"format": "qverify-scene/1", "name": "c", "quadrics": [{"id": "c", "cone": {"apex": [0, 0, )") +
                             num(5) + R"(], "axis": [1, 2, 3], "tan_half_angle": "2/7"}}], "lights": [
        {"id": "sun", "direction": ["-89/150", "11/15", "26/75"]}, {"id": "sun2", "direction": ["1/15", "4/3", "7/15"]},
        {"id": "lamp", "position": [)" + num(2) + ", " + num(-3) + ", " + num(Q(11, 2)) + R"(]}]})";
    const Scene sc = parse_scene(text, "cone.json");
    const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
    REQUIRE(rs.shadows.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
      INFO("shadow " << i);
      REQUIRE(rs.shadows[i].accuracy);
      CHECK(!rs.shadows[i].accuracy->inaccurate);
      REQUIRE(rs.shadows[i].origin);
      CHECK((*rs.shadows[i].origin)(0) == 0);
      CHECK((*rs.shadows[i].origin)(1) == 0);
      // the suns: at the apex; the lamp: above it, at the lamp's height
      CHECK((*rs.shadows[i].origin)(2) == (i < 2 ? Q(5) * k : Q(11, 2) * k));
    }
    CHECK(verify_results(sc, rs, VerifyOptions{}).failed == 0);
  }
}

TEST_CASE("a far quadric without a centre gets a frame on its axis, and verify passes it", "[verdicts][frames]") {
  // the cylinder (x - a)^2 + (y + 2)^2 = 1/4 and the paraboloid z - 1 = (x - a)^2 + (y + 2)^2,
  // a = 3e7 + 1/2, given as a matrix and as coefficients: no centre, and they were computed in
  // world coordinates (audit 28a F4)
  const std::string cylinder = R"({"id": "pipe", "matrix": [[1, 0, 0, "-60000001/2"], [0, 1, 0, 2], [0, 0, 0, 0],
      ["-60000001/2", 2, 0, "900000030000004"]]})";
  const std::string paraboloid = R"({"id": "bowl", "coefficients": {"xx": 1, "yy": 1, "x": -60000001, "y": 4,
      "z": -1, "c": "3600000120000021/4"}})";
  for (const std::string& q : {cylinder, paraboloid}) {
    INFO(q);
    const Scene sc = far_scene(q);
    const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
    REQUIRE(rs.shadows.size() == 1);
    REQUIRE(rs.shadows[0].origin);
    CHECK(abs(Q(rs.shadows[0].origin->x() - Q(60000001, 2))) < 1);  // on the axis
    CHECK(abs(Q(rs.shadows[0].origin->y() + 2)) < 1);
    REQUIRE(rs.reflections.size() == 1);
    CHECK(rs.reflections[0].origin);
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    CHECK(v.failed == 0);
    for (const VerifyCheck& c : v.checks) {
      REQUIRE(c.report);
      CHECK(c.report->geometric_error < 1e-12);
    }
  }
}

TEST_CASE("a terminator of one point: the results are judged as matrices, by verify and eval alike",
          "[verdicts][verify][accuracy]") {
  // A cone lit along its axis (the terminator is the apex) and a light on a sphere at a point no double
  // holds: P and R are singular at the one point, which says nothing of their shapes. A P that is not the
  // cone (P_zz = 1/2 for 0: a real cone where the line through the apex is right) passed; the correctly
  // rounded double plane pair of the light on the sphere failed with a "geometric error" of 0.65 (a second
  // order measure at a vanishing gradient), and passed once the scene was scaled by 5.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "one", "quadrics": [
      {"id": "funnel", "cone": {"apex": [2, 2, 0], "axis": [0, 0, 1], "tan_half_angle": "1/3"}},
      {"id": "ball", "sphere": {"center": [0, 0, 0], "radius": 1}},
      {"id": "ball5", "sphere": {"center": [0, 0, 0], "radius": 5}}],
      "lights": [{"id": "sun", "direction": [0, 0, -1]}, {"id": "on", "position": ["3/5", "4/5", 0]},
                 {"id": "on5", "position": [3, 4, 0]}],
      "requests": {"shadows": [{"quadric": "funnel", "light": "sun"}, {"quadric": "ball", "light": "on"},
                               {"quadric": "ball5", "light": "on5"}]}})",
                               "one.json");
  const ResultSet good = exact_results(sc);
  REQUIRE(failures(sc, good) == 0);
  CHECK(failures(sc, rounded(good)) == 0);
  for (const char* precision : {"double", "long-double", "float128"}) {
    INFO(precision);
    const ResultSet rs = computed_results(sc, *parse_precision(precision), Method::direct);
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    CHECK(v.failed == 0);
    for (const ShadowMatrices& s : rs.shadows) {
      REQUIRE(s.accuracy);
      CHECK_FALSE(s.accuracy->inaccurate);
    }
    for (const VerifyCheck& c : v.checks) {
      REQUIRE(c.report);
      CHECK(c.report->find("as_matrices"));
    }
  }
  // float: beyond 1e-9 as matrices, flagged by eval exactly where verify fails it
  const ResultSet f = computed_results(sc, *parse_precision("float"), Method::direct);
  const VerifyReport vf = verify_results(sc, f, VerifyOptions{});
  for (std::size_t k = 0; k < f.shadows.size(); ++k) {
    INFO("float, shadow " << k);
    REQUIRE(f.shadows[k].accuracy);
    CHECK(f.shadows[k].accuracy->inaccurate == !vf.checks[k].passed());
  }
  for (int bug = 0; bug < 3; ++bug) {
    ResultSet bad = good;
    if (bug == 0) bad.shadows[0].P(2, 2) += Q(1, 2);  // a real cone with the right apex
    if (bug == 1) bad.shadows[1].P = typed_scene<Q>(sc).A[1];  // the sphere itself: through L
    if (bug == 2) bad.shadows[1].R(0, 3) += Q(1, 1000), bad.shadows[1].R(3, 0) += Q(1, 1000);
    INFO("bug " << bug);
    CHECK(failures(sc, bad) == 1);
    CHECK(failures(sc, rounded(bad)) == 1);
    // eval's meter, given the same results, flags them
    const TypedScene<Q> t = typed_scene<Q>(sc);
    const std::size_t k = bug == 0 ? 0 : 1;
    ShadowMeter meter(t.A[sc.shadows[k].quadric], t.L[sc.shadows[k].other], AccuracyOptions{});
    CHECK(meter(std::nullopt, bad.shadows[k].P, bad.shadows[k].polar, bad.shadows[k].R).inaccurate);
  }
}

TEST_CASE("a wrong status, sign or M fails also where there is no point to sample", "[verdicts][verify]") {
  // A light inside a sphere (no real terminator) and an imaginary sphere reflected (no real point): the
  // checks were skipped whole, so a candidate's status "ok" for "no-real-silhouette" passed.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "none", "quadrics": [
      {"id": "ball", "sphere": {"center": [0, 0, 0], "radius": 1}},
      {"id": "ghost", "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}],
      "lights": [{"id": "inside", "position": ["1/10", "1/5", "3/10"]}],
      "mirrors": [{"id": "m", "plane": [0, 0, 1, -1]}],
      "requests": {"shadows": [{"quadric": "ball", "light": "inside"}],
                   "reflections": [{"quadric": "ghost", "mirror": "m"}]}})",
                               "none.json");
  const ResultSet good = exact_results(sc);
  const VerifyReport v = verify_results(sc, good, VerifyOptions{});
  CHECK(v.failed == 0);
  CHECK(v.skipped == 2);
  for (int bug = 0; bug < 4; ++bug) {
    ResultSet bad = good;
    if (bug == 0) bad.shadows[0].status = "ok";
    if (bug == 1) bad.shadows[0].P = -bad.shadows[0].P;
    if (bug == 2) bad.reflections[0].M(2, 3) += 1;
    if (bug == 3) bad.reflections[0].B = -bad.reflections[0].B;
    INFO("bug " << bug);
    const VerifyReport b = verify_results(sc, bad, VerifyOptions{});
    CHECK(b.failed == 1);
    CHECK(b.skipped == 1);
  }
}

TEST_CASE("an mpfr document read back is the values eval held: a far cone's mirror image passes", "[verdicts][verify]") {
  // mpfr entries are written with just enough digits to round-trip at the working precision; read as the
  // decimals they spell, B of a cone 2^100 from the origin (paper route, world frame) was 3e18 object sizes
  // off, where eval had certified 4e-27 for the value it held.
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "conefar", "quadrics": [{"id": "c", "cone":
      {"apex": ["2535301200456458802993406410752", "2535301200456458802993406410752", 0], "axis": [0, 0, 1],
       "tan_half_angle": "1/3"}}], "mirrors": [{"id": "floor", "plane": [0, 0, 1, "3802951800684688204490109616128"]}]})",
                               "conefar.json");
  for (const char* precision : {"mpfr:128", "mpfr:256"}) {
    INFO(precision);
    const auto doc = eval_json(eval_report(sc, *parse_precision(precision), Method::paper, std::nullopt, AccuracyOptions{}));
    const ResultSet rs = candidate_results_text(sc, doc.dump(), "eval.json", *parse_precision("double"));
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    INFO(verify_document(sc, v).dump(1));
    CHECK(v.failed == 0);
    // and the value read is the one computed, entry for entry
    const ResultSet computed = computed_results(sc, *parse_precision(precision), Method::paper);
    CHECK(rs.reflections[0].B == computed.reflections[0].B);
  }
}

TEST_CASE("certified bounds hold for objects 1e-200 and 1e200 across: no flag on accurate results",
          "[verdicts][accuracy]") {
  // The bounds' intervals are doubles: in world units an object 1e-200 across squared to 1e-400, the
  // gradients' floors underflowed to 0 and accurate long double, float128 and mpfr results had no bound.
  for (const char* scale : {"e-200", "e200"}) {
    INFO(scale);
    const std::string n = std::string("1") + scale, c2 = std::string("2") + scale, three = std::string("3") + scale,
                      four = std::string("4") + scale, eight = std::string("8") + scale;
    const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "tiny", "quadrics": [{"id": "ball", "sphere":
        {"center": [0, 0, ")" + c2 + R"("], "radius": ")" + n + R"("}}], "lights": [{"id": "lamp", "position": [")" +
                                     three + R"(", ")" + four + R"(", ")" + eight + R"("]}], "mirrors": [{"id": "m",
        "plane": [0, 0, 1, ")" + n + R"("]}]})",
                                 "tiny.json");
    for (const char* precision : {"long-double", "float128", "mpfr:128"}) {
      INFO(precision);
      const ResultSet rs = computed_results(sc, *parse_precision(precision), Method::direct);
      for (const ShadowMatrices& s : rs.shadows) {
        REQUIRE(s.accuracy);
        INFO(s.accuracy->reason);
        CHECK(s.accuracy->bound);
        CHECK_FALSE(s.accuracy->inaccurate);
      }
      for (const ReflectionMatrices& r : rs.reflections) {
        REQUIRE(r.accuracy);
        INFO(r.accuracy->reason);
        CHECK(r.accuracy->bound);
        CHECK_FALSE(r.accuracy->inaccurate);
      }
      CHECK(verify_results(sc, rs, VerifyOptions{}).failed == 0);
    }
  }
}

TEST_CASE("the paper route's P and R and every B are exactly symmetric in every precision", "[verdicts][verify]") {
  // The dense triple products N^T X N rounded (i, j) and (j, i) apart: float P and R of the paper route
  // came out 2e-8 and 6e-8 from symmetric, unflagged, and verify failed them (core/scalar.hpp, congruence).
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "sym", "quadrics": [
      {"id": "point", "sphere": {"center": [-1, 0, 0], "radius": 0}},
      {"id": "egg", "ellipsoid": {"center": [0.3, -0.2, 0.1], "radii": [1, 0.5, 0.25]}}],
      "lights": [{"id": "sun", "direction": [-1, 2, -3]}, {"id": "lamp", "position": [3, 4, 8]}],
      "mirrors": [{"id": "m", "plane": [1, 1, 1, 0]}, {"id": "far", "plane": [2, 3, 6, -7000]}]})",
                               "sym.json");
  for (const char* precision : {"float", "double", "long-double", "float128", "mpfr:128", "interval"})
    for (Method method : {Method::paper, Method::direct}) {
      INFO(precision << " " << method_name(method));
      const ResultSet rs = computed_results(sc, *parse_precision(precision), method);
      for (const ShadowMatrices& s : rs.shadows) {
        CHECK(s.P == Mat4<Q>(s.P.transpose()));
        CHECK(s.R == Mat4<Q>(s.R.transpose()));
      }
      for (const ReflectionMatrices& r : rs.reflections) CHECK(r.B == Mat4<Q>(r.B.transpose()));
      for (const VerifyCheck& c : verify_results(sc, rs, VerifyOptions{}).checks)
        if (c.report)
          for (const std::string& p : c.report->problems) CHECK(p.find("symmetric") == std::string::npos);
    }
}

TEST_CASE("eval counts M's error, which verify judges: a float M no float can hold is flagged", "[verdicts][accuracy]") {
  // eval's bound covered B alone: a float M of the plane x + y + z = 0 (entries 1/3, 2/3) is 2e-8 off,
  // unflagged, and verify failed it ("M is not the reflection in the mirror plane").
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "mirrors", "quadrics": [{"id": "s", "sphere":
      {"center": [0, 0, 0], "radius": 1}}], "mirrors": [{"id": "diag", "plane": [1, 1, 1, 0]},
      {"id": "far", "plane": [0, 0, 1, -1e20]}, {"id": "wall", "plane": [1, 0, 0, 0]}]})",
                               "mirrors.json");
  for (const char* precision : {"float", "double", "long-double"}) {
    INFO(precision);
    const ResultSet rs = computed_results(sc, *parse_precision(precision), Method::direct);
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    for (std::size_t k = 0; k < rs.reflections.size(); ++k) {
      INFO("mirror " << k);
      const ReflectionMatrices& r = rs.reflections[k];
      REQUIRE(r.accuracy);
      REQUIRE(v.checks[k].report);
      CHECK(r.accuracy->inaccurate == !v.checks[k].passed());
      CHECK(std::find(r.accuracy->certified.begin(), r.accuracy->certified.end(), "M") != r.accuracy->certified.end());
      if (r.accuracy->bound) CHECK(*r.accuracy->bound >= v.checks[k].report->M_error.value_or(0));
    }
    if (std::string(precision) == "float") {  // the diagonal mirror's M cannot be held: flagged
      CHECK(rs.reflections[0].accuracy->inaccurate);
      CHECK_FALSE(rs.reflections[2].accuracy->inaccurate);  // x = 0: M and B exact in float
    }
    if (std::string(precision) != "float") CHECK(v.failed == 0);
  }
}
TEST_CASE("R's second plane far away: accurate results pass, a tilted h fails (a check of R's shape)",
          "[verdicts][verify][accuracy]") {
  // a light 4e29 away, rotated off the vertical: the points of h were taken 5 units from R's crossing
  // line (1e-29 of their distance): the correctly rounded R measured 0.77, and a tilt of 1e-6 measured 1e-35
  const Scene far = parse_scene(R"({"format": "qverify-scene/1", "name": "farrot", "quadrics": [{"id": "s", "sphere":
      {"center": ["-2/3", "5", "1"], "radius": "5"}}], "lights": [{"id": "far", "position": ["-2/3",
      "-11999999999999999999999999999899/13", "4999999999999999999999999999998/13"]}]})", "farrot.json");
  const Scene funnel = parse_scene(R"({"format": "qverify-scene/1", "name": "funnel", "quadrics": [{"id": "c", "cone":
      {"apex": [2000000000000, 2000000000000, 0], "axis": [0, 0, 1], "tan_half_angle": "1/3"}}],
      "lights": [{"id": "lamp", "position": [100000000000, 200000000000, 9700000000000]}]})",
                                   "funnel.json");
  for (const Scene* sc : {&far, &funnel}) {
    INFO(sc->name);
    CHECK(failures(*sc, computed_results(*sc, *parse_precision("double"), Method::direct)) == 0);
    CHECK(failures(*sc, rounded(exact_results(*sc))) == 0);  // the best a double R can be
  }
  // h tilted by 1e-6 about the object (x / l_z, an angle): fails, in exact and rounded
  ResultSet bad = exact_results(far);
  auto& s = bad.shadows[0];
  const Q lz = Q("4999999999999999999999999999998") / 13;
  const Vec4<Q> tilted(Q(1, 1000000), 0, 1, -lz);
  s.R = s.polar * tilted.transpose() + tilted * s.polar.transpose();
  CHECK(failures(far, bad) == 1);
  CHECK(failures(far, rounded(bad)) == 1);
  // float: a cone lit along its axis from 1e12 (R's h 1.8e-8 of its distance off): verify fails it, on
  // R_on_second_plane, a check of R's shape, and eval flags it: the single-point terminator's matrices
  // are judged in the item's own frame (about the apex, in units of the light's distance), where R is
  // as far off. (Judged in the world frame, relative to its largest entries, it was not: a measure that
  // moved with the scene's placement, audit 32a F2.) From 1000 (exact in float) neither.
  for (const char* z : {"1000000000000", "1000"}) {
    const Scene sc = parse_scene(std::string(R"({"format": "qverify-scene/1", "name": "axis", "quadrics": [{"id": "c",
        "cone": {"apex": [0, 0, 0], "axis": [0, 0, 1], "tan_half_angle": 1}}], "lights": [{"id": "l", "position":
        [0, 0, )") + z + "]}]}", "axis.json");
    const ResultSet rs = computed_results(sc, *parse_precision("float"), Method::direct);
    const bool fails = failures(sc, rs) == 1;
    INFO(z);
    CHECK(fails == (std::string(z) != "1000"));
    CHECK(rs.shadows[0].accuracy->inaccurate == fails);
  }
}
// (check_flags/measured_errors compare eval's flags with verify's geometric_error, the geometric error
// of the contract; the checks of the results' shapes are verify's alone.)


TEST_CASE("eval flags a result that is wrongly zero or wrongly not, which verify fails, also without points",
          "[verdicts][accuracy]") {
  // Degenerate quadrics under an exact rotation: the exact P of a double plane lit by a lamp is the zero
  // matrix and the double one rounding noise; verify failed it ("P is zero where it should not be"), eval
  // gave no bound ("no real point") and no flag.
  const Scene sc = parse_scene(R"JSON({"format": "qverify-scene/1", "name": "degenerate", "quadrics": [{"id": "cone", "cone": {"apex": ["2/15", "86/13", "-21/65"], "axis": ["-1", "-14/13", "34/13"], "tan_half_angle": "3/4"}}, {"id": "planepair", "matrix": [["-7/25", "24/65", "288/325", "-701/975"], ["24/65", "7/169", "84/845", "-181/845"], ["288/325", "84/845", "1008/4225", "-2172/4225"], ["-701/975", "-181/845", "-2172/4225", "27032/38025"]]}, {"id": "doubleplane", "matrix": [["9/25", "12/65", "144/325", "-366/325"], ["12/65", "16/169", "192/845", "-488/845"], ["144/325", "192/845", "2304/4225", "-5856/4225"], ["-366/325", "-488/845", "-5856/4225", "14884/4225"]]}, {"id": "point", "sphere": {"center": ["14/15", "95/13", "-82/65"], "radius": "0"}}, {"id": "imag", "matrix": [["1", "0", "0", "-1/3"], ["0", "1", "0", "-7"], ["0", "0", "1", "2"], ["-1/3", "-7", "2", "487/9"]]}, {"id": "line", "cylinder": {"point": ["-7/15", "94/13", "-94/65"], "axis": ["0", "-12/13", "5/13"], "radius": "0"}}, {"id": "flat", "ellipsoid": {"center": ["1/3", "7", "-2"], "radii": ["1", "2", "0"], "axes": [["3/5", "-4/5", "0"], ["4/13", "3/13", "-12/13"], ["48/65", "36/65", "5/13"]]}}, {"id": "zero", "matrix": [["0", "0", "0", "0"], ["0", "0", "0", "0"], ["0", "0", "0", "0"], ["0", "0", "0", "0"]]}, {"id": "cyl", "cylinder": {"point": ["1/3", "7", "-2"], "axis": ["0", "-12/13", "5/13"], "radius": "1"}}, {"id": "para", "matrix": [["1", "0", "0", "-1/3"], ["0", "25/169", "60/169", "23/169"], ["0", "60/169", "144/169", "-329/338"], ["-1/3", "23/169", "-329/338", "-9740/1521"]]}], "lights": [{"id": "lamp", "position": ["-16/15", "-29/13", "458/65"]}, {"id": "sun", "direction": ["-1", "46/13", "9/13"]}, {"id": "apexlamp", "position": ["2/15", "86/13", "-21/65"]}], "mirrors": [{"id": "m", "plane": ["-1", "-14/13", "34/13", "394/39"]}]})JSON", "degenerate-rotated.json");
  for (const char* precision : {"double", "long-double"})
    for (Method method : {Method::direct, Method::paper}) {
      INFO(precision << " " << method_name(method));
      const ResultSet rs = computed_results(sc, *parse_precision(precision), method);
      const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
      for (std::size_t k = 0; k < v.checks.size(); ++k) {
        const VerifyCheck& c = v.checks[k];
        if (c.passed() || c.skipped()) continue;
        INFO(c.kind << " " << c.quadric << "/" << c.other);
        const bool shadow = k < rs.shadows.size();
        const auto& acc = shadow ? rs.shadows[k].accuracy : rs.reflections[k - rs.shadows.size()].accuracy;
        REQUIRE(acc);
        CHECK(acc->inaccurate);
      }
    }
}

TEST_CASE("a cone's polar plane moved by a small part of its size fails - at any scale", "[verdicts][accuracy]") {
  // A cone lit from 17 units away, 58 degrees off its axis (outside it: the terminator is two lines):
  // its terminator was sampled up to 1e7 units out (the sampler's steps from the apex were the
  // primitive integers of the plane's normal), so a polar plane moved by 0.01 units passed as 1e-10
  // object sizes (audit 28a F1). The steps now scale with the lamp's distance, and so do the points
  // (each scale draws its own: the seed is a function of the exact inputs); the points kept lie
  // within 16 steps of the moved base: the object size within 30 steps (Euclidean) of the apex.
  for (const Q k : {Q(1), Q(1, 100000)}) {
    INFO("scale " << k);
    const Mat4<Q> A = cone_quadric<Q>(Vec3<Q>(k * Q(1, 3), k * Q(2, 7), k * Q(-5, 11)), Vec3<Q>(Q(3, 13), Q(-2, 9), 1), Q(4, 7));
    const std::string m = matrix_text(A);
    auto num = [&](const Q& x) { return text(Q(k * x)); };
    const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "quadrics": [{"id": "cone", "matrix": )" + m +
                                     R"(}], "lights": [{"id": "lamp", "position": [)" + num(Q(31, 2)) + ", " +
                                     num(Q(-27, 7)) + ", " + num(Q(13, 3)) + "]}]}",
                                 "cone.json");
    ResultSet rs = computed_results(sc, *parse_precision("exact"), Method::direct);
    rs.precision = *parse_precision("double");  // judged against the accuracy target, not in proof mode
    REQUIRE(rs.shadows.size() == 1);
    CHECK(verify_results(sc, rs, VerifyOptions{}).checks[0].passed());
    Vec4<Q>& pi = rs.shadows[0].polar;
    const Q n = std::max({Q(abs(pi(0))), Q(abs(pi(1))), Q(abs(pi(2)))});
    pi(3) += k * n / 100;  // the plane moved by 0.6e-2 to 1e-2 of the scene's units, times the scale
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    CHECK_FALSE(v.checks[0].passed());
    REQUIRE(v.checks[0].report);
    INFO("object size " << v.checks[0].report->object_size);
    CHECK(v.checks[0].report->geometric_error > 1e-7);
    CHECK(v.checks[0].report->object_size < 500 * k.convert_to<double>());  // (a step: 15.2 k)
  }
}

TEST_CASE("under a parallel light R's second plane is judged as an angle - the same in any units",
          "[verdicts][accuracy]") {
  // h is the plane at infinity; R made with a second plane h' = (e, 1) instead lies 1 / |e| away, an
  // angle of about |e| times the object's size. The measure was a relative residual on directions,
  // which went as 1 / scale^2: the same candidate passed at one scale and failed at another (audit 37a F1).
  for (const Q& tilt : {Q(1, 1000), Q(1, 100000000000LL)}) {
    std::optional<double> first;
    std::optional<bool> passed;
    for (const Q& s : {Q(1, 10000), Q(1), Q(10000), Q(1, 1024)}) {
      INFO("tilt " << tilt << ", scale " << s);
      const Mat4<Q> A = ellipsoid_quadric<Q>(Vec3<Q>(Q(1, 3) * s, Q(-2, 7) * s, Q(5, 11) * s), Vec3<Q>(s, Q(3, 2) * s, Q(2, 3) * s),
                                               Mat3<Q>::Identity());
      const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "quadrics": [{"id": "egg", "matrix": )" + matrix_text(A) +
                                       R"(}], "lights": [{"id": "sun", "direction": [3, -2, 7]}]})",
                                   "egg.json");
      ResultSet rs = computed_results(sc, *parse_precision("exact"), Method::direct);
      rs.precision = *parse_precision("double");
      REQUIRE(rs.shadows.size() == 1);
      const Vec4<Q> pi = rs.shadows[0].polar;
      const Vec4<Q> h(tilt / s, Q(-2) * tilt / s, Q(2) * tilt / s, Q(1));  // 1 / (3 tilt) scene units away, times s
      rs.shadows[0].R = Mat4<Q>(pi * h.transpose() + h * pi.transpose());
      const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
      REQUIRE(v.checks.size() == 1);
      REQUIRE(v.checks[0].report);
      REQUIRE(v.checks[0].report->second_plane_error);
      const double m = *v.checks[0].report->second_plane_error;
      if (!first) first = m, passed = v.checks[0].passed();
      // (over the sampled points, whose seeded ones the scaled matrices draw anew: alike to 1e-4)
      CHECK(m == Approx(*first).epsilon(1e-3));
      CHECK(v.checks[0].passed() == *passed);
    }
    // about 3 tilt (|e|) times the size (1.5), over sqrt 2 or so: the far plane passes, the near fails
    CHECK(*first > tilt.convert_to<double>());
    CHECK(*first < 10 * tilt.convert_to<double>());
    CHECK(*passed == (tilt < Q(1, 1000000)));
  }
}

TEST_CASE("where h crosses the terminator, an R with the terminator on it exactly is bounded at 0", "[verdicts][accuracy]") {
  // A lamp beside an ellipsoid (h, z = l_z, crosses it): R's gradient vanishes where its planes cross on
  // the terminator, and R is bounded as a plane pair. An antisymmetric part of 1e-16 (no quadric's) was
  // taken into its first plane, and a second plane tilted by 1e-16 made it tilt the first to match:
  // bounded at 2e-8 and 1.4e-8, though the terminator lies on R exactly (audit 37a F2).
  const Mat4<Q> A = ellipsoid_quadric<Q>(Vec3<Q>(0, 0, 0), Vec3<Q>(1, Q(3, 2), Q(2, 3)), Mat3<Q>::Identity());
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "quadrics": [{"id": "egg", "matrix": )" + matrix_text(A) +
                                   R"(}], "lights": [{"id": "lamp", "position": [3, 1, "1/5"]}]})",
                               "egg.json");
  const ResultSet exact = computed_results(sc, *parse_precision("exact"), Method::direct);
  REQUIRE(exact.shadows.size() == 1);
  const Vec4<Q> pi = exact.shadows[0].polar, h(0, 0, 1, Q(-1, 5));
  const Mat4<Q> R = exact.shadows[0].R;
  const Q tiny = max_abs(R) / pow10(16);
  Mat4<Q> skew = Mat4<Q>::Zero();
  skew(0, 1) = tiny, skew(1, 0) = -tiny, skew(2, 3) = -tiny, skew(3, 2) = tiny;
  const Vec4<Q> tilted = h + Vec4<Q>(Q(1, 3), Q(-2, 7), 0, 0) / pow10(16);
  for (const Mat4<Q>& candidate : {Mat4<Q>(R + skew), Mat4<Q>(pi * tilted.transpose() + tilted * pi.transpose())}) {
    ResultSet rs = exact;
    rs.precision = *parse_precision("double");
    rs.shadows[0].R = candidate;
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    REQUIRE(v.checks.size() == 1);
    REQUIRE(v.checks[0].report);
    const CheckReport& r = *v.checks[0].report;
    INFO(r.summary());
    CHECK(v.checks[0].passed());
    REQUIRE(r.certified);
    CHECK(r.certified->upper < 1e-14);
  }
}

TEST_CASE("a cone with no length of its own is sampled by unit steps - its placement and the mirror's excuse no error",
          "[verdicts][accuracy]") {
  // Under a parallel light, or in a mirror, a cone has no length: its steps were its apex's distance
  // from the origin (a polar plane moved by 0.01 units passed with the apex at 1e6) or the mirror's
  // distance (B moved by 0.02 units passed with the mirror at 1e7), the object size 4e7 to 2e9.
  for (const Q& far : {Q(0), Q(1000000)}) {
    INFO("apex offset " << far);
    const Mat4<Q> A = cone_quadric<Q>(Vec3<Q>(Q(1, 3) + far, Q(2, 7), Q(-5, 11)), Vec3<Q>(Q(3, 13), Q(-2, 9), 1), Q(4, 7));
    for (const bool mirror : {false, true}) {
      INFO((mirror ? "mirror" : "parallel light"));
      const Vec4<Q> plane(1, 0, 0, -(Q(1, 3) + far + (mirror ? Q(10000000) : Q(5))));
      const Scene sc = parse_scene(
          R"({"format": "qverify-scene/1", "quadrics": [{"id": "cone", "matrix": )" + matrix_text(A) +
              R"(}], "lights": [{"id": "sun", "direction": [31, -8, 4]}], "mirrors": [{"id": "m", "plane": [)" +
              text(plane(0)) + ", " + text(plane(1)) + ", " + text(plane(2)) + ", " + text(plane(3)) + "]}]}",
          "cone.json");
      ResultSet rs = computed_results(sc, *parse_precision("exact"), Method::direct);
      rs.precision = *parse_precision("double");  // judged against the accuracy target, not in proof mode
      REQUIRE(rs.shadows.size() == 1);
      REQUIRE(rs.reflections.size() == 1);
      CHECK(verify_results(sc, rs, VerifyOptions{}).failed == 0);
      std::size_t k = 0;
      if (mirror) {  // B moved by 0.02 units along x
        Mat4<Q>& B = rs.reflections[0].B;
        const Mat4<Q> T = translation<Q>(Vec3<Q>(Q(-1, 50), 0, 0));
        B = T.transpose() * B * T;
        k = 1;
      } else {  // the polar plane moved by 0.01 of its normal's largest entry
        Vec4<Q>& pi = rs.shadows[0].polar;
        pi(3) += std::max({Q(abs(pi(0))), Q(abs(pi(1))), Q(abs(pi(2)))}) / 100;
      }
      const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
      REQUIRE(v.checks.size() == 2);
      const VerifyCheck& c = v.checks[k];
      CHECK(c.kind == (mirror ? "reflection" : "shadow"));
      CHECK_FALSE(c.passed());
      REQUIRE(c.report);
      INFO("object size " << c.report->object_size);
      CHECK(c.report->geometric_error > 1e-6);
      CHECK(c.report->object_size < 50);  // unit steps: within 16 of the moved base, 30 (Euclidean) of the apex
    }
  }
}

TEST_CASE("a reflection moved or turned a little is bounded by how far it moved the points", "[verdicts][accuracy]") {
  // The ball bound divided the value's bound by the gradient's floor shell by shell: a hyperbolic
  // paraboloid's B moved by 2e-9 (3.7e-10 of its size) was bounded at 2.1e-9 and failed (audit 35a
  // F2). Its error is now split into an infinitesimal motion of the exact B and a rest
  // (certified_bound.cpp, motion_part): the motion's part of the distance is how far it moves the
  // points. B moved by d passes where d is below T times the size and fails well above it. Where the
  // gradient vanishes (a plane pair, a cone) the second order is taken from the moved points z - V z.
  const Scene sc = parse_scene(
      R"({"format": "qverify-scene/1", "quadrics": [{"id": "saddle", "coefficients": {"xx": 1, "yy": -3, "z": -1}},
          {"id": "bowl", "coefficients": {"xx": 1, "yy": 2, "z": -1}}, {"id": "egg", "coefficients": {"xx": 1, "yy": "1/4", "zz": "1/9", "c": -1}},
          {"id": "planes", "coefficients": {"xx": 1, "yy": -4}}, {"id": "cone", "coefficients": {"xx": 1, "yy": 2, "zz": -1}}],
          "mirrors": [{"id": "m", "plane": ["0.12345678901234567", "-0.98765432109876543", "0.333333333333333333", "-2.7182818284590452"]}]})",
      "moved.json");
  const ResultSet exact = computed_results(sc, *parse_precision("exact"), Method::direct);
  REQUIRE(exact.reflections.size() == 5);
  const VerifyReport sizes = verify_results(sc, exact, VerifyOptions{});
  for (std::size_t k = 0; k < 5; ++k) {
    REQUIRE(sizes.checks[k].report);
    const double size = sizes.checks[k].report->object_size;
    // (the ellipsoid's bound is a branch and bound's, which stops within a factor 2 of a distance attained;
    // the plane pair's and the cone's, about the line and the point where their gradient vanishes, is
    // the second order's from the moved points, within 3 times: the cone moved by 0.4 targets is
    // bounded at 2.7 times that, and fails)
    const double slack = k == 2 ? 2.0 : k >= 3 ? 3.0 : 1.0;
    INFO(sc.quadrics[k].id << ", size " << size);
    // a translation by d along (1, 2, 2) / 3, and a turn by about d / 10 about a point 10 away (R = (I - S)^-1
    // (I + S), S skew with entries d / 20: exactly rational)
    for (const double rel : {0.4, 4.0}) {
      const Q d = Q(rel) * Q(size) / Q(1000000000);
      ResultSet rs = exact;
      rs.precision = *parse_precision("double");
      Mat4<Q>& B = rs.reflections[k].B;
      const Mat4<Q> T = translation<Q>(Vec3<Q>(d / 3, 2 * d / 3, 2 * d / 3));
      B = T.transpose() * B * T;
      const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
      const VerifyCheck& c = v.checks[k];
      REQUIRE(c.report);
      REQUIRE(c.report->certified);
      INFO("moved by " << rel << " T sizes: bound " << c.report->certified->upper);
      if (rel > 1 || k != 4) CHECK(c.passed() == (rel < 1));
      CHECK(c.report->certified->upper <= slack * 1.5 * rel * 1e-9);
      ResultSet turned = exact;
      turned.precision = *parse_precision("double");
      Mat3<Q> S = Mat3<Q>::Zero();
      S(0, 1) = d / 20, S(1, 0) = -d / 20, S(1, 2) = d / 40, S(2, 1) = -d / 40;
      const Mat3<Q> R3 = Mat3<Q>((Mat3<Q>::Identity() - S).inverse() * (Mat3<Q>::Identity() + S));
      Mat4<Q> R = Mat4<Q>::Identity();
      R.topLeftCorner<3, 3>() = R3;
      const Mat4<Q> about = translation<Q>(Vec3<Q>(10, 0, 0));
      const Mat4<Q> G = Mat4<Q>(about * R * Mat4<Q>(about.inverse()));
      turned.reflections[k].B = G.transpose() * turned.reflections[k].B * G;
      const VerifyReport vt = verify_results(sc, turned, VerifyOptions{});
      REQUIRE(vt.checks[k].report);
      REQUIRE(vt.checks[k].report->certified);
      INFO("turned: bound " << vt.checks[k].report->certified->upper << ", sampled " << vt.checks[k].report->geometric_error);
      // (the points move by at most the angle, 2 |s| = 0.112 d, times their distance from the turn's point,
      // at most 10 + 10 + the size: the ball's centre lies within 10 of the origin)
      CHECK(vt.checks[k].report->certified->upper <= slack * 0.15 * rel * 1e-9 * (20 + size));
    }
  }
}

TEST_CASE("a double plane or a line reflected is sampled on it - a B without real points fails", "[verdicts][accuracy]") {
  // Lines through a point beside them only touch such quadrics: no point was found, and B was judged as a
  // matrix, where 9e-10 added to its constant (no real point at all) passed (audit 36a F2). Their points
  // are now A's kernel's, rational (sampling.cpp, Prism::on_kernel).
  const Scene sc = parse_scene(
      R"({"format": "qverify-scene/1", "quadrics": [{"id": "dp", "coefficients": {"xx": 1}}, {"id": "line", "coefficients": {"xx": 1, "yy": 1}}],
          "mirrors": [{"id": "m", "plane": [0, 0, 1, -3]}]})",
      "degenerate.json");
  const ResultSet exact = computed_results(sc, *parse_precision("exact"), Method::direct);
  REQUIRE(exact.reflections.size() == 2);
  const VerifyReport ok = verify_results(sc, exact, VerifyOptions{});
  for (const VerifyCheck& c : ok.checks) {
    INFO(c.quadric);
    CHECK(c.passed());
    REQUIRE(c.report);
    CHECK(c.report->points == static_cast<std::size_t>(kDefaultSamples));
  }
  for (const Q eps : {Q(9, 10000000000), Q(-9, 10000000000)})
    for (const bool skew : {false, true}) {
      // (with an antisymmetric part, within the target, which verify accepts: it does not change the
      // surface, but it was taken into the gradient, and such a B with no real point passed at 9.8e-11:
      // audit 36b F1; the surface's gradient is its symmetric part's)
      ResultSet rs = exact;
      rs.precision = *parse_precision("double");
      for (auto& r : rs.reflections) {
        const Q big = max_abs(r.B);
        r.B(3, 3) += eps * big;
        if (skew)
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) r.B(i, j) += Q(3, 10000000000) * big, r.B(j, i) -= Q(3, 10000000000) * big;
      }
      const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
      for (const VerifyCheck& c : v.checks) {
        INFO(c.quadric << ", " << eps << (skew ? ", skew" : ""));
        CHECK_FALSE(c.passed());
      }
    }
}

TEST_CASE("correctly rounded results of degenerate references: not flagged, and they pass", "[verdicts][accuracy]") {
  // A cone's P under a sun is a plane pair: rounded, it is truly sqrt(eps) rho off along the line where
  // its planes cross (the apex's generator line), 5e-17 off on the terminator. Its certified bound over
  // the generator lines flagged it at 7.1e-9, and verify failed eval's own double results (audit 31a
  // F1). A hyperbolic paraboloid's R, 1.3e-16 off on the terminator, was flagged at 6.7e-9 near the line
  // where h crosses the polar plane, a line the terminator does not meet (F2). The geometric error is
  // of the terminator's points; P's generators and R's polar plane are checks of their shapes, sampled.
  const char* scenes[] = {
      R"({"format": "qverify-scene/1", "name": "cone", "quadrics": [{"id": "cone", "cone": {"apex": [0, 0, 0],
          "axis": [1, 2, 3], "tan_half_angle": "1/3"}}], "lights": [{"id": "sun", "direction": [1, -1, 2]}]})",
      R"({"format": "qverify-scene/1", "name": "hpar", "quadrics": [{"id": "hpar", "coefficients": {"xx": "32/75",
          "yy": "1/3", "zz": "-19/25", "xy": "-4/5", "xz": "-52/75", "yz": "16/15", "x": "41/15", "y": "-6",
          "z": "112/15", "c": "-55/3"}}], "lights": [{"id": "p0", "position": ["88/75", "47/30", "857/150"]}]})"};
  for (const char* text : scenes) {
    const Scene sc = parse_scene(text, "degenerate.json");
    INFO(sc.name);
    const ResultSet rs = computed_results(sc, *parse_precision("double"), Method::direct);
    REQUIRE(rs.shadows.size() == 1);
    const auto& acc = rs.shadows[0].accuracy;
    REQUIRE(acc);
    REQUIRE(acc->bound);
    INFO("error_bound " << *acc->bound);
    CHECK_FALSE(acc->inaccurate);
    CHECK(*acc->bound < 1e-12);
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{});
    REQUIRE(v.checks.size() == 1);
    CHECK(v.passed == 1);
  }
}

TEST_CASE("verify: a flat cone's P changed near its apex fails, its first-order distance there meaning nothing",
          "[verdicts][accuracy]") {
  // Audit 39a's flat cone (eigenvalues -1, 1e-6, 1) under a sun, eval's P changed by 1e-19 e4 e4^T -
  // 4e-16 (l e4^T + e4 l^T), l . z = d0 . (x - apex), d0 one terminator line's direction (review of
  // session 40): the exact terminator point apex + 0.0014 d0 is 3.6e-5 of the size from P (80 digits,
  // the Lagrange condition), its first-order distance 6e-11. The terminator's gradient floor raised
  // 500 times let the ball bound's first order win there (1.7e-10: a pass); the first order now counts
  // only where the curvature cannot undo it, and the bound is 2e-4.
  const Scene sc = parse_scene(test::kFlatConeSun, "flat-cone.json");
  const char* candidate = R"({"format":"qverify-eval/1","precision":"double","shadows":[{"quadric":"q","light":"d6","status":"ok","origin":[-1.3333333333333333,2.5,14.0],"P":[[-1.95999972,-1.4e-06,-0.28000096,-1.99502455174406e-16],[-1.4e-06,-1.1339537073845723e-41,-2e-07,-1.0886631441116096e-16],[-0.28000096,-2e-07,-0.04000028,3.6030747092573556e-16],[-1.99502455174406e-16,-1.0886631441116096e-16,3.6030747092573556e-16,9.999999999998121e-20]],"polar_plane":[1.3999998666666666,3.3333333333333335e-07,0.20000093333333333,1.0362080576303217e-16],"R":[[0.0,0.0,0.0,1.3999998666666666],[0.0,0.0,0.0,3.3333333333333335e-07],[0.0,0.0,0.0,0.20000093333333333],[1.3999998666666666,3.3333333333333335e-07,0.20000093333333333,2.0724161152606434e-16]]}],"reflections":[]})";
  const ResultSet rs = candidate_results_text(sc, candidate, "changed.json", *parse_precision("double"));
  const auto checks = verify_document(sc, verify_results(sc, rs, VerifyOptions{}))["checks"];
  REQUIRE(checks.size() == 1);
  INFO(checks[0].dump());
  CHECK(checks[0]["status"] == "fail");
  CHECK(checks[0]["certified"]["geometric_error_bound"].get<double>() >= 3.6e-5);
}
