// The stability families at their worst case, and the local frames of the robust path.
#include <qverify/verify/stress.hpp>
#include <qverify/verify/verifier.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <unistd.h>

using namespace qverify;

TEST_CASE("every stress family at its worst case: the default double path meets the geometric target",
          "[stress]") {
  for (const StressFamily& fam : stress_families()) {
    INFO(fam.name);
    StressOptions opt;
    opt.out_dir = (std::filesystem::temp_directory_path() / ("qverify-stress-" + std::to_string(::getpid()))).string();
    opt.families = {fam.name};
    opt.worst_only = true;
    const auto doc = run_stress(opt);
    REQUIRE(doc["families"].size() == 1);
    const auto& f = doc["families"][0];
    const auto& p = f["points"][0];
    INFO("param " << p["param"].get<double>() << " target " << p["target"].get<double>());
    CHECK(f["default_meets_target"].get<bool>());
    INFO(f["flag_check"].dump());
    CHECK(f["flag_check"]["ok"].get<bool>());  // every run beyond the target was flagged
    // every point is run in at least 4 precisions and both methods
    std::set<std::string> precisions, methods;
    for (const auto& r : p["runs"]) {
      precisions.insert(r["precision"].get<std::string>());
      methods.insert(r["method"].get<std::string>());
    }
    CHECK(precisions.size() >= 4);
    CHECK(methods.size() == 2);
  }
}

TEST_CASE("the sweeps separate the naive and the robust double paths where they should", "[stress]") {
  StressOptions opt;
  opt.out_dir = (std::filesystem::temp_directory_path() / ("qverify-stress2-" + std::to_string(::getpid()))).string();
  opt.families = {"far-from-origin", "mirror-far", "decimal-inputs"};
  opt.worst_only = true;
  const auto doc = run_stress(opt);
  for (const auto& f : doc["families"]) {
    INFO(f["name"].get<std::string>());
    double naive = 0, robust = 1;
    for (const auto& r : f["points"][0]["runs"]) {
      if (r["run"] == "double/direct/world (naive)") naive = r["geometric_error"].is_null() ? 1e300 : r["geometric_error"].get<double>();
      if (r["run"] == "double/direct (default, robust)") robust = r["geometric_error"].get<double>();
    }
    CHECK(naive > 1e-3);   // the naive world-frame double result is geometrically wrong here
    CHECK(robust < 1e-9);  // the default one is not
  }
}

TEST_CASE("far objects get a local origin that the verifier and candidates understand", "[stress][frames]") {
  const Scene sc = parse_scene(R"({"format": "qverify-scene/1", "name": "far",
      "quadrics": [{"id": "ball", "sphere": {"center": [1000000000000.5, -3, 2], "radius": 1}}],
      "lights": [{"id": "lamp", "position": [1000000000003.5, 1, 10]}],
      "mirrors": [{"id": "far", "plane": [1, 0, 0, -2e12]}]})",
                               "far.json");
  const auto dbl = *parse_precision("double");
  const ResultSet rs = computed_results(sc, dbl, Method::direct);
  REQUIRE(rs.shadows[0].origin);
  CHECK(*rs.shadows[0].origin == Vec3<Rational>(Rational(2000000000001, 2), -3, 2));
  REQUIRE(rs.reflections[0].origin);  // the image, 3e12 further
  const VerifyOutcome v = verify_results(sc, rs, VerifyOptions{8, 1});
  CHECK(v.failed == 0);
  for (const auto& c : v.document["checks"]) {
    CHECK(c["status"] == "pass");
    for (const char* k : {"on_P", "on_R", "on_B"})
      if (c.contains(k)) CHECK(c[k]["max_distance"].get<double>() < 1e-9);
  }
  // the world-frame result of the same scene is geometrically useless
  const ResultSet world = computed_results(sc, dbl, Method::direct, Frame::world);
  const VerifyOutcome w = verify_results(sc, world, VerifyOptions{8, 1});
  CHECK(w.document["checks"][0]["on_P"]["max_distance"].get<double>() > 1e3);
  CHECK(w.document["checks"][0]["status"] == "fail");  // and a verdict says so
}
