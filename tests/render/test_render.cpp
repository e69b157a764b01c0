// qverify render: the two methods, the shadow-volume theorem behind them,
// the certified check of disagreeing pixels, and the CLI.
#include "cli_run.hpp"

#include <qverify/render/render.hpp>

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace qverify;
using namespace qverify::render;

namespace {

std::string scene_path(const char* name) { return std::string(QVERIFY_SCENES) + "/" + name; }

/// The example scene with a smaller camera (the tests stay fast).
Scene small_scene(const char* name, int width = 160, int height = 120) {
  std::ifstream in(scene_path(name));
  nlohmann::json j;
  in >> j;
  j["camera"]["width"] = width;
  j["camera"]["height"] = height;
  return parse_scene(j.dump(), name);
}

/// A point in a cube of half side 3, with a random denominator.
Rational random_rational(std::mt19937_64& g, int range = 3) {
  std::uniform_int_distribution<long> num(-range * 64, range * 64), den(1, 64);
  return Rational(num(g)) / Rational(den(g));
}

}  // namespace

TEST_CASE("shadow volume test equals the shadow ray, certified, on random configurations", "[render][theorem]") {
  // The point-in-quadric rule of trace.hpp against the shadow ray it replaces,
  // both run in certified 256-bit intervals from exact random inputs: quadrics
  // of every signature, point and parallel lights inside and outside them,
  // points inside and outside, on the surface (self) or not.
  set_mpfi_bits(256);
  std::mt19937_64 g(20261122);
  int decided = 0, shadowed = 0, inside_light = 0, total = 0, self_cases = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Mat4<Rational> A;
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) A(i, j) = A(j, i) = random_rational(g, 2);
    Vec4<Rational> L(random_rational(g), random_rational(g), random_rational(g), Rational(trial % 4 == 0 ? 0 : 1));
    Vec3<Rational> x(random_rational(g), random_rational(g), random_rational(g));
    const bool self = trial % 3 == 0;
    if (self) {  // put x on A exactly: shift the constant term by -x^T A x
      const Vec4<Rational> X(x(0), x(1), x(2), Rational(1));
      A(3, 3) -= X.dot(A * X);
    }
    const Rational s = L.dot(A * L);
    if (s == 0) continue;
    auto enc = [](const Rational& q) { return enclose_mpfi(q); };
    Mat4<Mpfi> Ai = A.unaryExpr(enc);
    Vec4<Mpfi> Li = L.unaryExpr(enc);
    Vec3<Mpfi> xi = x.unaryExpr(enc);
    Occluder<Mpfi> oc{0, tangent_cone<Mpfi>(Ai, Li), polar_plane<Mpfi>(Ai, Li), s > 0 ? 1 : -1};
    ++total;
    try {
      const bool by_volume = in_shadow_volume<Mpfi>(oc, Ai, xi, self);
      const bool by_ray = shadow_ray_blocked<Mpfi>(Ai, Li, xi, self);
      INFO("trial " << trial);
      CHECK(by_volume == by_ray);
      ++decided;
      shadowed += by_ray;
      inside_light += s < 0;
      self_cases += self;
    } catch (const Undecided&) {
    }
  }
  CHECK(decided >= total * 99 / 100);
  CHECK(shadowed > decided / 10);      // both outcomes are exercised
  CHECK(shadowed < decided * 9 / 10);
  CHECK(inside_light > decided / 10);  // and lights on both sides of A
  CHECK(self_cases > decided / 5);     // and points on A itself
}

TEST_CASE("both methods agree on the example scenes and the certified check confirms sampled pixels", "[render]") {
  for (const char* name : {"ball-lamp-floor.json", "egg-sun-wall.json", "mixed-requests.json"}) {
    INFO(name);
    const Scene sc = small_scene(name);
    const Renderer r(sc, RenderOptions{});
    const Image t = r.render(RenderMethod::transforms), w = r.render(RenderMethod::raytrace);
    REQUIRE(t.ids.size() == 160u * 120u);
    long differ = 0, shown = 0, in_mirror = 0, shadowed = 0;
    for (std::size_t i = 0; i < t.ids.size(); ++i) {
      differ += t.ids[i] != w.ids[i];
      shown += t.ids[i].surface >= 0;
      in_mirror += t.ids[i].mirror >= 0 && t.ids[i].surface >= 0;
      shadowed += t.ids[i].shadowed != 0 || t.ids[i].mirror_shadowed != 0;
    }
    CHECK(differ * 1000 <= static_cast<long>(t.ids.size()));
    CHECK(shown > 100);
    CHECK(in_mirror >= 5);  // every example shows a reflection
    CHECK(shadowed > 10);
    // every 97th pixel re-traced in certified arithmetic: the truth is what both methods drew
    for (std::size_t i = 0; i < t.ids.size(); i += 97) {
      const int x = static_cast<int>(i % 160), y = static_cast<int>(i / 160);
      const Certified c = r.certify(x, y);
      INFO("pixel " << x << ", " << y << ": " << r.describe(t.ids[i]));
      REQUIRE(c.decided);
      CHECK(c.methods_agree);
      CHECK(c.truth == t.ids[i]);
      CHECK(c.truth == w.ids[i]);
    }
  }
}

TEST_CASE("far from the world origin the world frame loses shadow pixels and the certified check names the culprit",
          "[render][frame]") {
  const Scene sc = small_scene("far-ball-lamp-floor.json", 200, 150);  // the ball scene moved 1e7 along x
  RenderOptions world;
  world.camera_frame = false;
  const Comparison bad = compare_methods(Renderer(sc, world), 1, 200);
  const Comparison good = compare_methods(Renderer(sc, RenderOptions{}), 1, 200);
  CHECK(bad.disagreeing > 0);
  CHECK(bad.undecided == 0);
  CHECK(bad.methods_differ_exactly == 0);
  CHECK(bad.transforms_right + bad.raytrace_right + bad.neither == static_cast<long>(bad.checked.size()));
  // P in the world frame cancels ~14 digits at the terminator: the raytrace's shadow ray is right more often
  CHECK(bad.raytrace_right > bad.transforms_right);
  CHECK(good.agreement >= 0.999);
  CHECK(good.agreement > bad.agreement);
}

TEST_CASE("render pixel ids read as words and colour apart from the background", "[render]") {
  const Scene sc = small_scene("ball-lamp-floor.json");
  const Renderer r(sc, RenderOptions{});
  PixelId bg;
  CHECK(r.describe(bg) == "background");
  PixelId p{0, 0, 1, 0};
  CHECK(r.describe(p) == "ball (shadowed from lamp) in floor");
  const auto c0 = Renderer::id_colour(bg), c1 = Renderer::id_colour(p);
  CHECK((c0 == std::array<std::uint8_t, 3>{0, 0, 0}));
  CHECK(c1 != c0);
  CHECK(Renderer::id_colour(PixelId{0, 0, 0, 0}) != c1);
  REQUIRE(r.left_out().empty());
}

TEST_CASE("render --compare --json has the issue's shape and writes PNGs", "[render][cli]") {
  using qverify_test::run;
  const auto dir = std::filesystem::temp_directory_path() / ("qverify-render-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "t.png").string(), ids = (dir / "ids.png").string(), diff = (dir / "diff.png").string();
  const auto res = run("render " + scene_path("mixed-requests.json") + " --compare --json --repeat 1 --out " + out +
                       " --ids " + ids + " --diff " + diff);
  REQUIRE(res.code == 0);
  const auto doc = nlohmann::json::parse(res.out);
  CHECK(doc["format"] == "qverify-render/1");
  CHECK(doc["pixels"] == 640 * 480);
  CHECK(doc["agreement"].get<double>() >= 0.999);
  CHECK(doc["disagreeing"].is_number_integer());
  CHECK(doc["seconds"]["transforms"].get<double>() > 0);
  CHECK(doc["seconds"]["raytrace"].get<double>() > 0);
  CHECK(doc["left_out"].size() == 14);  // the pairs mixed-requests does not request
  for (const auto& f : {out, ids, diff}) {
    std::ifstream png(f, std::ios::binary);
    char sig[8] = {};
    png.read(sig, 8);
    CHECK(std::string(sig + 1, 3) == "PNG");
  }
  const auto single = run("render " + scene_path("ball-lamp-floor.json") + " --method raytrace --json --out " + out);
  REQUIRE(single.code == 0);
  CHECK(nlohmann::json::parse(single.out)["method"] == "raytrace");
}

TEST_CASE("render rejects what it cannot draw with exit 2", "[render][cli]") {
  using qverify_test::run;
  const std::string nocam = qverify_test::temp_file(
      "nocam.json", R"({"format": "qverify-scene/1", "quadrics": [{"id": "s", "sphere": {"center": [0,0,0], "radius": 1}}]})");
  for (const std::string& args :
       {"render " + nocam + " --out /tmp/x.png", "render " + scene_path("ball-lamp-floor.json"),
        "render " + scene_path("ball-lamp-floor.json") + " --compare --box -1",
        "render " + scene_path("ball-lamp-floor.json") + " --compare --method magic",
        "render " + scene_path("ball-lamp-floor.json") + " --out /nonexistent-dir/x.png"}) {
    INFO(args);
    const auto r = run(args);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
  }
}
