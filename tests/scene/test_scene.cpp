// Scene format: exact numbers, every shape, every error (with its JSON path).
#include <qverify/exact/number_text.hpp>
#include <qverify/scene/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace qverify;
using Q = Rational;

namespace {

Q num(const std::string& text) {
  std::string err;
  auto v = parse_rational(text, err);
  INFO(text << ": " << err);
  REQUIRE(v);
  return *v;
}

std::string wrap(const std::string& quadrics, const std::string& rest = "") {
  return R"({"format": "qverify-scene/1", "name": "t", "quadrics": [)" + quadrics + "]" + rest + "}";
}

/// The InputError path for a scene that must be rejected.
std::string rejected_path(const std::string& text) {
  try {
    parse_scene(text, "t.json");
  } catch (const InputError& e) {
    CHECK(e.file == "t.json");
    CHECK(!e.problem.empty());
    return e.path;
  }
  FAIL("scene was accepted: " << text);
  return "";
}

}  // namespace

TEST_CASE("numbers are read exactly from their text", "[numbers]") {
  CHECK(num("0.1") == Q(1, 10));
  CHECK(num("-7/3") == Q(-7, 3));
  CHECK(num("2.5e-7") == Q(25, 100000000));
  CHECK(num("1E2") == Q(100));
  CHECK(num("1e-300") * Q(boost::multiprecision::pow(boost::multiprecision::mpz_int(10), 300)) == 1);
  CHECK(num("123456789012345678901234567890") == Q(boost::multiprecision::mpz_int("123456789012345678901234567890")));
  CHECK(num("-0.000") == 0);
  // leading zeros are decimal, never octal (found by fuzzing: GMP reads "010" as 8)
  CHECK(num("010/3") == Q(10, 3));
  CHECK(num("-007/0020") == Q(-7, 20));
  CHECK(num("0000000000000000000000000000000000000000000000002049638230412172402/1") ==
        Q(boost::multiprecision::mpz_int("2049638230412172402")));
  CHECK(num("0/5") == 0);
  CHECK(num("09.5") == Q(19, 2));
  std::string err;
  // the range is the leading digit's decimal exponent, -10000 to 10000 (1e-10001 was in, 1e10000 out)
  CHECK(parse_rational("1e10000", err));
  CHECK(parse_rational("9.99e10000", err));
  CHECK(parse_rational("1e-10000", err));
  CHECK(parse_rational("0.001e-9997", err));
  for (const char* bad : {"1e10001", "1e-10001", "0.01e-9999", "10e10000"}) {
    INFO(bad);
    CHECK_FALSE(parse_rational(bad, err));
  }
  for (const char* bad : {"abc", "1/0", "1/-2", "1e", "--1", "1.2.3", "", "1e1000000000", "0x10", "1/2/3", "nan", "inf"}) {
    INFO(bad);
    CHECK_FALSE(parse_rational(bad, err));
  }
}

TEST_CASE("inputs round once to nearest in each precision", "[numbers][rounding]") {
  RoundingReport rep;
  CHECK(round_rational<double>(Q(1, 10), rep) == 0.1);
  CHECK(rep.inexact);
  CHECK(round_rational<double>(Q(1, 3), rep) == 1.0 / 3.0);
  CHECK(round_rational<float>(Q(1, 10), rep) == 0.1f);
  CHECK(round_rational<long double>(Q(1, 10), rep) == 0.1L);
  CHECK(round_rational<Float128>(Q(1, 3), rep) == Float128(1) / Float128(3));
  CHECK(round_rational<double>(num("1e-320"), rep) == 1e-320);  // subnormal, correctly rounded
  RoundingReport big;
  round_rational<double>(num("1e400"), big);
  CHECK(big.overflow);
  RoundingReport fine;
  CHECK(round_rational<double>(Q(3, 4), fine) == 0.75);
  CHECK_FALSE(fine.inexact);
  CHECK(to_rational(0.1) != Q(1, 10));
  CHECK(to_rational(0.75) == Q(3, 4));
}

TEST_CASE("every shape becomes its matrix", "[scene][shapes]") {
  const Scene sc = parse_scene(wrap(R"(
    {"id": "m", "matrix": [[2, 0.5, 0, 0], [0.5, 3, 0, -1], [0, 0, 1, 0], [0, -1, 0, -4]]},
    {"id": "k", "coefficients": {"xx": 1, "yy": -1, "z": -2, "c": 0.1}},
    {"id": "s", "sphere": {"center": [0, 0, 2], "radius": 1}},
    {"id": "e", "ellipsoid": {"center": [1.5, -0.5, 3], "radii": [1, 2, 0.75], "axes": [["3/5", "-4/5", 0], ["4/5", "3/5", 0], [0, 0, 1]]}},
    {"id": "y", "cylinder": {"point": [0, 0, 0], "axis": [0, 1, 1], "radius": 0.5}},
    {"id": "c", "cone": {"apex": [2, 2, 0], "axis": [0, 0, 1], "tan_half_angle": "1/3", "x-note": "kept"}})",
                                   R"(, "lights": [{"id": "lamp", "position": [0.1, 0.2, 9.7]}, {"id": "sun", "direction": [0, 0, -1]}],
       "mirrors": [{"id": "floor", "plane": [0, 0, 1, 3]}])"),
                                   "t.json");
  REQUIRE(sc.quadrics.size() == 6);
  const TypedScene<Q> ts = typed_scene<Q>(sc);
  CHECK(ts.A[0](0, 1) == Q(1, 2));
  CHECK(ts.A[1](3, 3) == Q(1, 10));
  CHECK(ts.A[1](2, 3) == -1);
  CHECK(ts.A[2] == sphere_quadric<Q>(Vec3<Q>(0, 0, 2), Q(1)));
  CHECK(ts.A[4] == cylinder_quadric<Q>(Vec3<Q>::Zero(), Vec3<Q>(0, 1, 1), Q(1, 2)));
  CHECK(ts.L[0] == Vec4<Q>(Q(1, 10), Q(1, 5), Q(97, 10), 1));
  CHECK(ts.L[1] == Vec4<Q>(0, 0, 1, 0));  // parallel light travelling along d sits at -d
  CHECK(ts.rounded_inputs.empty());
  // every pair is requested by default
  CHECK(sc.shadows.size() == 12);
  CHECK(sc.reflections.size() == 6);
  CHECK(sc.skipped_shadows().empty());
  // double rounds 0.1 once; the ellipsoid's 3/5 and 4/5 too
  const TypedScene<double> td = typed_scene<double>(sc);
  CHECK(td.L[0](0) == 0.1);
  CHECK(!td.rounded_inputs.empty());
}

TEST_CASE("requests select pairs - the rest is reported as skipped", "[scene][requests]") {
  const Scene sc = parse_scene(wrap(R"({"id": "a", "sphere": {"center": [0,0,0], "radius": 1}},
                                       {"id": "b", "sphere": {"center": [5,0,0], "radius": 1}})",
                                    R"(, "lights": [{"id": "l", "position": [0,0,9]}], "mirrors": [{"id": "m", "plane": [0,0,1,0]}],
                                       "requests": {"shadows": [{"quadric": "b", "light": "l"}], "reflections": []})"),
                               "t.json");
  REQUIRE(sc.shadows.size() == 1);
  CHECK(sc.shadows[0].quadric == 1);
  CHECK(sc.reflections.empty());
  CHECK(sc.skipped_shadows().size() == 1);
  CHECK(sc.skipped_reflections().size() == 2);
}

TEST_CASE("every rule of the scene format is enforced - with the JSON path", "[scene][errors]") {
  const std::string sphere = R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": 1}})";
  struct Case {
    std::string text, path;
  };
  const std::vector<Case> cases = {
      {"[1, 2]", ""},
      {"{", ""},
      {R"({"quadrics": []})", "format"},
      {R"({"format": "qverify-scene/2", "quadrics": []})", "format"},
      {R"({"format": "qverify-scene/1"})", "quadrics"},
      {R"({"format": "qverify-scene/1", "quadrics": [], "lihgts": []})", "lihgts"},
      {R"({"format": "qverify-scene/1", "quadrics": {}})", "quadrics"},
      {R"({"format": "qverify-scene/1", "name": 3, "quadrics": []})", "name"},
      {wrap(R"({"sphere": {"center": [0, 0, 0], "radius": 1}})"), "quadrics[0].id"},
      {wrap(R"({"id": "", "sphere": {"center": [0, 0, 0], "radius": 1}})"), "quadrics[0].id"},
      {wrap(sphere + "," + sphere), "quadrics[1].id"},
      {wrap(R"({"id": "s"})"), "quadrics[0]"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": 1}, "cone": {}})"), "quadrics[0].cone"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0], "radius": 1}})"), "quadrics[0].sphere.center"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, "x"], "radius": 1}})"), "quadrics[0].sphere.center[2]"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": -1}})"), "quadrics[0].sphere.radius"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": true}})"), "quadrics[0].sphere.radius"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": 1, "radus": 2}})"), "quadrics[0].sphere.radus"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0]}})"), "quadrics[0].sphere.radius"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": "1/0"}})"), "quadrics[0].sphere.radius"},
      {wrap(R"({"id": "s", "sphere": {"center": [0, 0, 0], "radius": 1e1000000000}})"), "quadrics[0].sphere.radius"},
      {wrap(R"({"id": "m", "matrix": [[1, 2, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]})"), "quadrics[0].matrix[1][0]"},
      {wrap(R"({"id": "m", "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]})"), "quadrics[0].matrix"},
      {wrap(R"({"id": "m", "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, -1]]})"), "quadrics[0].matrix[3]"},
      {wrap(R"({"id": "k", "coefficients": {"xx": 1, "w": 2}})"), "quadrics[0].coefficients.w"},
      {wrap(R"({"id": "k", "coefficients": [1, 2]})"), "quadrics[0].coefficients"},
      {wrap(R"({"id": "e", "ellipsoid": {"center": [0, 0, 0], "radii": [1, -1, 1]}})"), "quadrics[0].ellipsoid.radii[1]"},
      {wrap(R"({"id": "e", "ellipsoid": {"center": [0, 0, 0], "radii": [1, 1, 1], "axes": [[1, 0, 0], [2, 0], [0, 0, 1]]}})"),
       "quadrics[0].ellipsoid.axes[1]"},
      {wrap(R"({"id": "y", "cylinder": {"point": [0, 0, 0], "axis": [0, 0, 0], "radius": 1}})"), "quadrics[0].cylinder.axis"},
      {wrap(R"({"id": "c", "cone": {"apex": [0, 0, 0], "axis": [0, 0, 1], "tan_half_angle": -1}})"),
       "quadrics[0].cone.tan_half_angle"},
      {wrap(sphere, R"(, "lights": [{"id": "l"}])"), "lights[0]"},
      {wrap(sphere, R"(, "lights": [{"id": "l", "position": [0, 0, 1], "direction": [0, 0, 1]}])"), "lights[0].direction"},
      {wrap(sphere, R"(, "lights": [{"id": "l", "direction": [0, 0, 0]}])"), "lights[0].direction"},
      {wrap(sphere, R"(, "lights": [{"id": "s", "position": [0, 0, 5]}])"), "lights[0].id"},
      {wrap(sphere, R"(, "mirrors": [{"id": "m", "plane": [0, 0, 0, 1]}])"), "mirrors[0].plane"},
      {wrap(sphere, R"(, "mirrors": [{"id": "m", "plane": [0, 0, 1]}])"), "mirrors[0].plane"},
      {wrap(sphere, R"(, "requests": {"shadows": "some"})"), "requests.shadows"},
      {wrap(sphere, R"(, "requests": {"shadow": "all"})"), "requests.shadow"},
      {wrap(sphere, R"(, "lights": [{"id": "l", "position": [0, 0, 5]}], "requests": {"shadows": [{"quadric": "s", "light": "x"}]})"),
       "requests.shadows[0].light"},
      {wrap(sphere, R"(, "lights": [{"id": "l", "position": [0, 0, 5]}], "requests": {"shadows": [{"quadric": "l", "light": "l"}]})"),
       "requests.shadows[0].quadric"},
      {wrap(sphere, R"(, "lights": [{"id": "l", "position": [0, 0, 5]}], "requests": {"shadows": [{"quadric": "s", "light": "l"}, {"quadric": "s", "light": "l"}]})"),
       "requests.shadows[1]"},
      {wrap(sphere, R"(, "camera": {"eye": [0, 0, 0], "look_at": [0, 0, 0]})"), "camera.look_at"},
      {wrap(sphere, R"(, "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "fov_y_deg": 200})"), "camera.fov_y_deg"},
      {wrap(sphere, R"(, "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "width": 1.5})"), "camera.width"},
      {R"({"format": "qverify-scene/1", "quadrics": [], "quadrics": []})", "quadrics"},
      // a NUL byte ended nlohmann's input: what followed it was never read (audit 37b F5)
      {std::string(R"({"format": "qverify-scene/1", "quadrics": []})") + std::string(1, '\0') + "garbage{{{", ""},
      {std::string(R"({"format": "qverify-scene/1", "quadrics": [])") + std::string(1, '\0') + "]}", ""},
  };
  for (const Case& c : cases) {
    INFO(c.text);
    CHECK(rejected_path(c.text) == c.path);
  }
}

TEST_CASE("x- keys are kept for the user - nesting depth is limited", "[scene][errors]") {
  CHECK_NOTHROW(parse_scene(wrap(R"({"id": "s", "x-colour": [1, 2], "sphere": {"center": [0, 0, 0], "radius": 1}})",
                                 R"(, "x-anything": {"deep": [1]})"),
                            "t.json"));
  std::string deep = R"({"format": "qverify-scene/1", "quadrics": [], "x-deep": )" + std::string(200, '[') +
                     std::string(200, ']') + "}";
  CHECK_THROWS_AS(parse_scene(deep, "t.json"), InputError);
}

TEST_CASE("values beyond a precision's range round to infinity and are listed: the scene is legal", "[scene][range]") {
  const Scene sc = parse_scene(wrap(R"({"id": "s", "sphere": {"center": [0, 0, 1e400], "radius": 1}})"), "t.json");
  CHECK(typed_scene<Q>(sc).rounded_inputs.empty());
  const TypedScene<double> d = typed_scene<double>(sc);
  CHECK(d.rounded_inputs == std::vector<std::string>{"quadrics[0].sphere.center[2]"});
  CHECK(std::isinf(d.A[0](2, 3)));
  const TypedScene<long double> ld = typed_scene<long double>(sc);  // (long double reaches 1e4932)
  CHECK(std::isfinite(ld.A[0](2, 3)));
}

TEST_CASE("the fuzz corpora replay: every input loads or is refused as an InputError", "[scene][fuzz]") {
  namespace fs = std::filesystem;
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(QVERIFY_FUZZ_CORPUS) / "scene")) {
    std::ifstream in(e.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    INFO(e.path());
    try {
      const Scene sc = parse_scene(text, e.path().string());
      if (sc.shadows.size() + sc.reflections.size() <= 16) {
        (void)typed_scene<Q>(sc);
        (void)typed_scene<double>(sc);
      }
    } catch (const InputError& err) {
      CHECK(!err.problem.empty());
    }
    ++files;
  }
  CHECK(files >= 10);
}
