// item_candidate (verify/item_candidate.hpp): plain functions as the candidate of a stress sweep (issue 19).
#include <qverify/core/core.hpp>
#include <qverify/report/report.hpp>
#include <qverify/studies/stress.hpp>
#include <qverify/verify/item_candidate.hpp>
#include <qverify/report/verify_document.hpp>
#include <qverify/verify/verifier.hpp>

#include "cli_run.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <stdexcept>
#include <unistd.h>

using namespace qverify;
using qverify_test::fresh_dir;

namespace {

/// qverify's own core in double, in the world frame: a correct implementation.
ShadowCandidate<double> core_shadow(const Mat4<double>& A, const Vec4<double>& L) {
  const ShadowResult<double> s = shadow<double>(A, L, Method::direct);
  ShadowCandidate<double> c;
  c.P = s.P;
  c.polar_plane = s.polar_plane;
  c.R = s.R;
  return c;
}

ReflectionCandidate<double> core_reflection(const Mat4<double>& A, const Vec4<double>& plane) {
  const Mat4<double> M = mirror_matrix<double>(plane);
  ReflectionCandidate<double> c;
  c.M = M;
  c.B = reflection<double>(A, M, Method::direct).B;
  return c;
}

const StressRun& run_named(const StressPoint& point, const std::string& run) {
  for (const StressRun& r : point.runs)
    if (r.run == run) return r;
  FAIL("no run " << run);
  throw std::logic_error("unreachable");
}

}  // namespace

TEST_CASE("a correct function passes far from the origin except where the world frame itself breaks",
          "[item-candidate][stress]") {
  const auto dir = fresh_dir("item-cand");
  StressOptions opt;
  opt.out_dir = dir.string();
  opt.families = {"far-from-origin"};
  opt.samples = 4;
  opt.candidate = item_candidate("core", core_shadow, nullptr);
  const StressReport report = run_stress(opt);
  const StressFamilyResult& f = report.families[0];
  const std::vector<StressPoint>& pts = f.points;
  REQUIRE(pts.size() == 13);
  int passed = 0;
  for (const StressPoint& p : pts) {
    const double d = p.param;
    INFO("d = " << d);
    const StressRun& c = p.runs.back();
    REQUIRE(c.candidate);
    CHECK(c.status == "unstated");
    CHECK(c.precision->name() == "double");
    CHECK(c.frame == Frame::world);
    // item geometric errors, infinite where a run gave no finite item
    const double naive = run_named(p, "double/direct/world (naive)").item_geometric_error;
    const double mine = c.item_geometric_error;
    INFO("candidate " << mine << ", qverify's naive world-frame double " << naive);
    // within the accuracy target wherever a world-frame double computation can be (the naive run meets it)
    if (naive <= 1e-9) CHECK(mine <= 1e-9);
    if (mine <= 1e-9) ++passed;
    CHECK(c.beyond_accuracy == !(mine <= 1e-9));
  }
  CHECK(passed >= 8);  // d = 1 .. 1e7 at least: the world frame holds up to there
  // where it fails, it is the world frame's breakdown (1e8, README), not a failed call
  CHECK(f.candidate->failed_calls == 0);
  REQUIRE(f.candidate->breakdown);
  CHECK(*f.candidate->breakdown >= 1e8);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a function that throws gives candidate-failed points and the sweep goes on", "[item-candidate][stress]") {
  const auto dir = fresh_dir("item-cand-throw");
  StressOptions opt;
  opt.out_dir = dir.string();
  opt.families = {"far-from-origin"};
  opt.samples = 4;
  int calls = 0;
  opt.candidate = item_candidate(
      "thrower",
      [&calls](const Mat4<double>& A, const Vec4<double>& L) {
        if (++calls % 2 == 1) throw std::runtime_error("no shadow today");
        return core_shadow(A, L);
      },
      nullptr);
  const StressReport report = run_stress(opt);
  write_stress_report(dir, report);
  const StressFamilyResult& f = report.families[0];
  const std::vector<StressPoint>& pts = f.points;
  REQUIRE(pts.size() == 13);
  CHECK(calls == 13);
  for (std::size_t k = 0; k < pts.size(); ++k) {
    INFO("point " << k);
    const StressRun& c = pts[k].runs.back();
    if (k % 2 == 0) {
      CHECK(c.status == "candidate-failed");
      CHECK(c.error == "shadow (obj, light): no shadow today");
      CHECK(c.reproducer == "failures/thrower-far-from-origin-" + std::to_string(k) + ".json");
      CHECK(std::filesystem::exists(dir / ("failures/thrower-far-from-origin-" + std::to_string(k) + ".log")));
    } else {
      CHECK(c.status == "unstated");
    }
    CHECK(pts[k].runs.size() == 10);  // qverify's nine runs are all there, and the candidate's
  }
  CHECK(f.candidate->failed_calls == 7);
  CHECK(f.candidate->breakdown == 1.0);
  CHECK(std::filesystem::exists(dir / "report.html"));
  CHECK(std::filesystem::exists(dir / "far-from-origin.svg"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("item_results: inputs, optional parts and every way a call fails", "[item-candidate]") {
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "two",
      "quadrics": [{"id": "ball", "sphere": {"center": ["1/10", 2, 3], "radius": 1}}],
      "lights": [{"id": "lamp", "position": [3, 4, 8]}],
      "mirrors": [{"id": "floor", "plane": [0, 0, 1, "1/3"]}]})",
                               "two.json");
  Mat4<double> seenA;
  Vec4<double> seenL, seenPlane;
  auto shadow_fn = [&](const Mat4<double>& A, const Vec4<double>& L) {
    seenA = A, seenL = L;
    ShadowCandidate<double> c;
    c.P = core_shadow(A, L).P;  // P only
    return c;
  };
  auto reflection_fn = [&](const Mat4<double>& A, const Vec4<double>& plane) {
    seenPlane = plane;
    return core_reflection(A, plane);
  };
  SECTION("the exact inputs rounded once; left-out parts are zero and noted") {
    const ResultSet rs = item_results(sc, "mine", shadow_fn, reflection_fn);
    // A: the exact matrix of the sphere, each entry rounded to nearest (-1/10 and 1/100 + 4 + 9 - 1)
    CHECK(seenA(0, 3) == -0.1);
    CHECK(seenA(3, 3) == 12.01);
    CHECK(seenL == Vec4<double>(3, 4, 8, 1));
    CHECK(seenPlane == Vec4<double>(0, 0, 1, 1.0 / 3));
    REQUIRE(rs.shadows.size() == 1);
    REQUIRE(rs.reflections.size() == 1);
    CHECK(rs.shadows[0].present);
    CHECK_FALSE(rs.shadows[0].origin);
    CHECK(rs.shadows[0].R.isZero());
    CHECK(rs.shadows[0].polar.isZero());
    CHECK(rs.reflections[0].present);
    CHECK_FALSE(rs.reflections[0].M.isZero());
    CHECK(rs.precision.name() == "double");
    CHECK(rs.notes.size() == 1);
  }
  SECTION("a throwing function, a missing function, no P, a NaN: failed calls with the reason") {
    auto thrower = [](const Mat4<double>&, const Vec4<double>&) -> ReflectionCandidate<double> {
      throw std::domain_error("mirror broke");
    };
    Candidate c = item_candidate("mine", shadow_fn, thrower);
    CandidateCall call = call_candidate(c, sc, "{}", "two");
    CHECK_FALSE(call.ok);
    CHECK(call.error == "reflection (ball, floor): mirror broke");

    call = call_candidate(item_candidate("mine", shadow_fn, nullptr), sc, "{}", "two");
    CHECK(call.error == "reflection (ball, floor): no reflection function was given");

    auto no_P = [](const Mat4<double>& A, const Vec4<double>& L) {
      ShadowCandidate<double> r = core_shadow(A, L);
      r.P.reset();
      return r;
    };
    call = call_candidate(item_candidate("mine", no_P, reflection_fn), sc, "{}", "two");
    CHECK(call.error == "shadow (ball, lamp): the function returned no P (the shadow cone is required)");

    auto nan_B = [](const Mat4<double>& A, const Vec4<double>& plane) {
      ReflectionCandidate<double> r = core_reflection(A, plane);
      (*r.B)(1, 2) = NAN;
      return r;
    };
    call = call_candidate(item_candidate("mine", shadow_fn, nan_B), sc, "{}", "two");
    CHECK(call.error == "reflection (ball, floor): the function returned a non-finite entry: B[1][2] = nan");

    call = call_candidate(item_candidate("mine", core_shadow, core_reflection), sc, "{}", "two");
    CHECK(call.ok);
  }
  SECTION("a function working in a local frame gives its origin; with every part given the verifier passes it") {
    auto local_shadow = [](const Mat4<double>& A, const Vec4<double>& L) {
      const Vec3<double> o(0.1, 2, 3);  // x_world = x_local + o
      Mat4<double> T = Mat4<double>::Identity();
      T.block<3, 1>(0, 3) = o;
      const Vec4<double> Ll(L(0) - o(0) * L(3), L(1) - o(1) * L(3), L(2) - o(2) * L(3), L(3));
      ShadowCandidate<double> c = core_shadow(Mat4<double>(T.transpose() * A * T), Ll);
      c.origin = o;
      c.status = "ok";
      return c;
    };
    const ResultSet rs = item_results(sc, "local", local_shadow, core_reflection);
    REQUIRE(rs.shadows[0].origin);
    CHECK(*rs.shadows[0].origin == exact_matrix(Vec3<double>(0.1, 2, 3)));
    CHECK(rs.shadows[0].status == "ok");
    CHECK(rs.notes.empty());
    const VerifyReport v = verify_results(sc, rs, VerifyOptions{8, 1});
    INFO(verify_document(sc, v).dump());
    CHECK(v.failed == 0);
    CHECK(v.passed == 2);
  }
  SECTION("a bad name is refused at once") {
    CHECK_THROWS_AS(item_candidate("no spaces", shadow_fn, nullptr), InputError);
  }
}
