// The check API (verify/check.hpp): a user's matrices checked directly, with
// the semantics of `qverify verify`, in every scalar type.
#include <qverify/batch/batch.hpp>
#include <qverify/verify/check.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace qverify;
using Q = Rational;

namespace {

template <class S> Mat4<S> unit_sphere() { return sphere_quadric<S>(Vec3<S>(S(0), S(0), S(0)), S(1)); }
/// A light whose x (10/3) no binary format holds: every floating result rounds.
template <class S> Vec4<S> lamp() { return Vec4<S>(S(10) / S(3), S(4), S(8), S(1)); }

template <class S> ShadowCandidate<S> candidate_of(const ShadowResult<S>& r) {
  ShadowCandidate<S> c;
  c.P = r.P;
  c.polar_plane = r.polar_plane;
  c.R = r.R;
  return c;
}

template <class S> ReflectionCandidate<S> candidate_of(const ReflectionResult<S>& r) {
  ReflectionCandidate<S> c;
  c.B = r.B;
  return c;
}

template <class S> CheckReport own_shadow(Method m = Method::direct) {
  const Mat4<S> A = unit_sphere<S>();
  const Vec4<S> L = lamp<S>();
  return check_shadow<S>(A, L, candidate_of(shadow<S>(A, L, m)));
}

}  // namespace

TEST_CASE("check_shadow passes qverify's own results in every scalar type", "[check]") {
  for (const CheckReport& r : {own_shadow<float>(), own_shadow<double>(), own_shadow<long double>(),
                               own_shadow<Float128>(), own_shadow<Interval>(), own_shadow<double>(Method::paper)}) {
    INFO(r.summary());
    CHECK(r.kind == "shadow");
    CHECK(r.points == static_cast<std::size_t>(kDefaultSamples));
    CHECK(r.object_size == Approx(1.0));
    CHECK(r.exact_status == "ok");
    CHECK(r.find("on_P"));
    CHECK(r.find("on_generators"));
    CHECK(r.find("on_polar_plane"));
    CHECK(r.find("R_on_polar_plane"));
  }
  // float rounds at 2^-24: its geometric error is above 1e-9, below 1e-5
  CHECK_FALSE(own_shadow<float>().passed);
  CHECK(own_shadow<float>().geometric_error > 1e-9);
  CHECK(own_shadow<float>().geometric_error < 1e-5);
  CHECK(own_shadow<double>().passed);
  CHECK(own_shadow<double>().geometric_error < 1e-14);
  CHECK(own_shadow<long double>().passed);
  CHECK(own_shadow<Float128>().passed);
  INFO(own_shadow<Interval>().summary());
  CHECK(own_shadow<Interval>().passed);
  CHECK(own_shadow<double>(Method::paper).passed);
}

TEST_CASE("a cone lit from outside: an accurate P passes at its apex, where P's gradient vanishes", "[check]") {
  // The terminator is two of the cone's lines, crossing at its apex, which the sampler takes (the
  // line pair's singular point). There P_ref = (L^T A L) A - (A L)(A L)^T vanishes with its gradient,
  // and a rounded P's first-order distance was about half the apex's distance from the frame's
  // origin: every floating P failed, here by 5.7e-5 of the object's size. (The cone is exact in
  // double: t^2 = 1/4, integer apex and axis.)
  const Mat4<double> A = cone_quadric<double>(Vec3<double>(1, 2, 3), Vec3<double>(0, 1, 1), 0.5);
  // outside (0.86 from the axis for each unit along it, against 0.5); 10/3 rounded, so that P rounds
  // (integer inputs give an exact P, which vanishes at the apex)
  const Vec4<double> L(10.0 / 3, -3, 2, 1);
  const auto exact = [](const auto& m) { return m.unaryExpr([](double x) { return Q(x); }).eval(); };
  const ItemPoints pts = terminator_points(exact(A), exact(L), kDefaultSamples, item_seed(1, 1, exact(A), exact(L)));
  REQUIRE(pts.singular.size() == 1);  // the apex is sampled: the case at hand
  CHECK(pts.points[pts.singular[0]].p() == Vec4<Q>(1, 2, 3, 1));
  const ShadowResult<double> s = shadow<double>(A, L, Method::direct);
  const CheckReport good = check_shadow<double>(A, L, candidate_of(s));
  INFO(good.summary());
  CHECK(good.passed);
  CHECK(good.geometric_error < 1e-14);
  // P is exactly zero at the apex in exact arithmetic too, and a P off elsewhere still fails
  CHECK(check_shadow<Q>(exact(A), exact(L), candidate_of(shadow<Q>(exact(A), exact(L), Method::direct))).passed);
  ShadowCandidate<double> bad = candidate_of(s);
  (*bad.P)(0, 0) *= 1 + 1e-6;
  CHECK_FALSE(check_shadow<double>(A, L, bad).passed);
}

TEST_CASE("a sphere lit level with its centre: R measured by the Euclidean distance where its planes cross", "[check]") {
  // R = pi h^T + h pi^T, h the plane z = l_z. Lit level with the centre, h halves the terminator, and
  // the chords' midpoints (points of the polar plane R is measured on) lie on or within 1e-17 of the
  // line where R's planes cross, where R's gradient vanishes with R: a rounded R's first-order distance
  // there is a quotient of roundings. Measured so, this R was 0.29 of the object off, and every floating
  // R of the scene at a height of 0.1 failed (0.67 in double, 0.19 at mpfr:128). There a point's
  // distance is the second-order one, sqrt(|f| / curvature), a point of R being that close: about
  // sqrt(eps) times the line's distance from the origin, as the rounded plane pair's neck truly is.
  const double z = 0.1;
  const Mat4<double> A = sphere_quadric<double>(Vec3<double>(0, 0, z), 1);
  const Vec4<double> L(3, 1, z, 1);
  const auto exact = [](const auto& m) { return m.unaryExpr([](double x) { return Q(x); }).eval(); };
  const ItemPoints pts = terminator_points(exact(A), exact(L), kDefaultSamples, item_seed(1, 1, exact(A), exact(L)));
  const Vec4<Q> h(0, 0, 1, -Q(z));
  for (const RootPoint& y : pts.plane) CHECK(h.dot(y.p()) != 0);  // no point of the polar plane on h
  const ShadowResult<double> s = shadow<double>(A, L, Method::direct);
  const CheckReport at_default = check_shadow<double>(A, L, candidate_of(s));
  INFO(at_default.summary());
  // the neck: above the default target on the polar plane's points (a check of R's shape) and in R's
  // certified bound over the terminator (whose two points on h the samples miss), below 1e-8
  REQUIRE(at_default.find("R_on_polar_plane"));
  CHECK(at_default.find("R_on_polar_plane")->geometric_error > 1e-10);
  CHECK(at_default.find("R_on_polar_plane")->geometric_error < 1e-8);
  REQUIRE(at_default.certified);
  CHECK(at_default.certified->upper > 1e-9);
  CHECK(at_default.certified->upper < 1e-8);
  CHECK_FALSE(at_default.passed);
  CheckOptions loose;
  loose.accuracy = 1e-8;
  const CheckReport good = check_shadow<double>(A, L, candidate_of(s), loose);
  INFO(good.summary());
  CHECK(good.passed);
  // an R off elsewhere still fails
  ShadowCandidate<double> bad = candidate_of(s);
  (*bad.R)(0, 3) *= 1 + 1e-6;
  (*bad.R)(3, 0) = (*bad.R)(0, 3);
  CHECK_FALSE(check_shadow<double>(A, L, bad, loose).passed);
}

TEST_CASE("real points at infinity only: judged as matrices, a right result passes and a wrong one fails", "[check]") {
  // A cylinder lit from inside: the polar plane x = 2 is parallel to the axis, the section's one real point
  // is the axis's point at infinity (status ok, not no-real-silhouette), and there is no finite point to
  // sample. Such items were skipped: a candidate with P, the polar plane and R all wrong was skipped, exit
  // 0, and audit called it a pass, and a right one was not passed either (audit 31b F1). They are judged
  // as matrices against the exact ones, up to a factor, as eval measures them.
  const Mat4<double> A = cylinder_quadric<double>(Vec3<double>(0, 0, 0), Vec3<double>(0, 0, 1), 1);
  const Vec4<double> L(0.5, 0, 0, 1);
  const ShadowCandidate<double> good = candidate_of(shadow<double>(A, L, Method::direct));
  const CheckReport r = check_shadow<double>(A, L, good);
  INFO(r.summary());
  CHECK(r.exact_status == "ok");
  CHECK_FALSE(r.skipped);
  CHECK(r.passed);
  REQUIRE(r.find("as_matrices"));
  CHECK(r.find("as_matrices")->passed);
  ShadowCandidate<double> bad = good;
  (*bad.polar_plane)(3) *= 500;  // the plane x = 1000, not x = 2
  const CheckReport rb = check_shadow<double>(A, L, bad);
  INFO(rb.summary());
  CHECK_FALSE(rb.passed);
  CHECK_FALSE(rb.skipped);
  CHECK(rb.geometric_error > 0.1);
  // an imaginary cylinder reflected: B against M^T A M as a matrix
  Mat4<double> imaginary = Mat4<double>::Zero();  // x^2 + y^2 + 1 = 0: real only at z's point at infinity
  imaginary(0, 0) = imaginary(1, 1) = imaginary(3, 3) = 1;
  const Vec4<double> mirror(1, 2, 2, 3);
  ReflectionCandidate<double> rc = candidate_of(reflection_in_plane<double>(imaginary, mirror, Method::direct));
  const CheckReport rr = check_reflection<double>(imaginary, mirror, rc);
  INFO(rr.summary());
  CHECK_FALSE(rr.skipped);
  CHECK(rr.passed);
  (*rc.B)(3, 3) *= 7;
  CHECK_FALSE(check_reflection<double>(imaginary, mirror, rc).passed);
  // a quadric without any real point, not even at infinity, still has nothing to judge
  Mat4<double> none = Mat4<double>::Identity();
  const CheckReport rn = check_reflection<double>(none, mirror, candidate_of(reflection_in_plane<double>(none, mirror, Method::direct)));
  CHECK(rn.skipped);
}

TEST_CASE("a polar plane where A L = 0 must be zero: a cylinder lit along its axis", "[check]") {
  // A sun along the cylinder's axis: A L = 0, so P, the polar plane and R are all zero (status
  // light-on-surface). A non-zero polar plane was judged nowhere and passed audit (audit 31b F2).
  const Mat4<double> A = cylinder_quadric<double>(Vec3<double>(0, 0, 0), Vec3<double>(0, 0, 1), 1);
  const Vec4<double> L(0, 0, -1, 0);
  const ShadowCandidate<double> good = candidate_of(shadow<double>(A, L, Method::direct));
  REQUIRE(good.polar_plane);
  CHECK(good.polar_plane->isZero());
  const CheckReport rg = check_shadow<double>(A, L, good);
  INFO(rg.summary());
  CHECK(rg.passed);  // (judged as matrices: all zero, as the exact ones)
  CHECK_FALSE(rg.skipped);
  ShadowCandidate<double> bad = good;
  *bad.polar_plane = Vec4<double>(0, 0, 1, -5);
  const CheckReport r = check_shadow<double>(A, L, bad);
  INFO(r.summary());
  CHECK_FALSE(r.passed);
  CHECK_FALSE(r.skipped);
  CHECK_THAT(r.summary(), Catch::Contains("the polar plane is zero where it should not be"));
}

TEST_CASE("check_shadow with rationals is a proof: every residual exactly zero", "[check]") {
  const CheckReport r = own_shadow<Q>();
  INFO(r.summary());
  CHECK(r.exact);
  CHECK(r.passed);
  CHECK(r.accuracy == 0);
  CHECK(r.geometric_error == 0);
  CHECK(r.proved_exactly == static_cast<int>(r.points));
  // a rational result off by 1/10^30 in one entry is no longer a proof
  const Mat4<Q> A = unit_sphere<Q>();
  const Vec4<Q> L = lamp<Q>();
  ShadowCandidate<Q> c = candidate_of(shadow<Q>(A, L, Method::direct));
  (*c.P)(0, 0) += Q(1, 1) / Q("1000000000000000000000000000000");
  const CheckReport bad = check_shadow<Q>(A, L, c);
  CHECK_FALSE(bad.passed);
  CHECK(bad.proved_exactly == 0);
}

TEST_CASE("check_shadow: a wrong P fails, and the report says where and by how much", "[check]") {
  const Mat4<double> A = unit_sphere<double>();
  const Vec4<double> L = lamp<double>();
  const ShadowResult<double> good = shadow<double>(A, L, Method::direct);

  SECTION("one entry off by 1e-6 of the largest") {
    ShadowCandidate<double> c = candidate_of(good);
    (*c.P)(1, 1) += 1e-6 * good.P.cwiseAbs().maxCoeff();
    const CheckReport r = check_shadow<double>(A, L, c);
    CHECK_FALSE(r.passed);
    CHECK(r.geometric_error > 1e-9);
    CHECK(r.geometric_error < 1e-4);
    const QuadricCheck* w = r.worst_check();
    REQUIRE(w);
    REQUIRE(w->worst_approx);
    // the worst point is a point of the terminator or of its generators, at about the object's size
    CHECK(w->worst_approx->norm() < 20);
    const std::string s = r.summary();
    CHECK_THAT(s, Catch::Contains("FAILED"));
    CHECK_THAT(s, Catch::Contains("worst point"));
    CHECK_THAT(s, Catch::Contains("object size"));
    CHECK_THAT(s, Catch::Contains("expected P"));
  }
  SECTION("the pencil's other member sA + (AL)(AL)^T vanishes on the terminator too, but is no cone from L") {
    const Vec4<double> AL = A * L;
    ShadowCandidate<double> c = candidate_of(good);
    c.P = Mat4<double>(L.dot(AL) * A + AL * AL.transpose());
    const CheckReport r = check_shadow<double>(A, L, c);
    CHECK_FALSE(r.passed);
    CHECK(r.find("on_P")->passed);  // the terminator alone cannot tell
    CHECK_FALSE(r.find("on_generators")->passed);
    CHECK(r.find("on_generators")->geometric_error > 1e-3);
    // (the certified bound is of the geometric error, on the terminator, where this P is right)
    REQUIRE(r.certified);
    CHECK(r.certified_for == std::vector<std::string>{"P", "polar_plane", "R"});
  }
  SECTION("the same on a hyperboloid (a hyperbola: bounded over the ball of the object size), the samples see it") {
    Mat4<double> H = Mat4<double>::Zero();  // x^2 + y^2 - z^2 - 1 = 0, one sheet
    H(0, 0) = 1, H(1, 1) = 1, H(2, 2) = -1, H(3, 3) = -1;
    const Vec4<double> Lh(5, 1, 2, 1);
    const ShadowResult<double> gh = shadow<double>(H, Lh, Method::direct);
    ShadowCandidate<double> c = candidate_of(gh);
    const Vec4<double> AL = H * Lh;
    c.P = Mat4<double>(Lh.dot(AL) * H + AL * AL.transpose());
    const CheckReport r = check_shadow<double>(H, Lh, c);
    INFO(r.summary());
    REQUIRE(r.certified);  // the ball bound: the wrong P's error term swamps its gradient, no finite bound
    // (R too: h, z = 2, crosses the ball, and R's planes cross there: the second order bounds it)
    CHECK(r.certified_for == std::vector<std::string>{"P", "polar_plane", "R"});
    CHECK_FALSE(r.passed);
    CHECK(r.find("on_P")->passed);
    CHECK_FALSE(r.find("on_generators")->passed);
    CHECK_THAT(r.summary(), Catch::Contains("on_generators (P is not the cone"));
  }
  SECTION("an all-zero R vanishes at every point, but is no plane pair: it fails and is not certified") {
    ShadowCandidate<double> c = candidate_of(good);
    c.R = Mat4<double>::Zero();
    const CheckReport r = check_shadow<double>(A, L, c);
    CHECK_FALSE(r.passed);
    CHECK_THAT(r.summary(), Catch::Contains("R is zero"));
    REQUIRE(r.certified);
    CHECK(r.certified->upper == std::numeric_limits<double>::infinity());
  }
  SECTION("P with the opposite sign") {
    ShadowCandidate<double> c = candidate_of(good);
    c.P = Mat4<double>(-good.P);
    const CheckReport r = check_shadow<double>(A, L, c);
    CHECK_FALSE(r.passed);
    CHECK_THAT(r.summary(), Catch::Contains("wrong sign"));
  }
  SECTION("a polar plane of the wrong orientation") {
    ShadowCandidate<double> c = candidate_of(good);
    c.polar_plane = Vec4<double>(-good.polar_plane);
    CHECK_FALSE(check_shadow<double>(A, L, c).passed);
  }
  SECTION("a status word the exact inputs contradict") {
    ShadowCandidate<double> c = candidate_of(good);
    c.status = "degenerate-quadric";
    CHECK_FALSE(check_shadow<double>(A, L, c).passed);
  }
}

TEST_CASE("check_shadow checks only what a renderer gives", "[check]") {
  const Mat4<double> A = unit_sphere<double>();
  const Vec4<double> L = lamp<double>();
  ShadowCandidate<double> c;
  c.P = tangent_cone<double>(A, L);
  const CheckReport r = check_shadow<double>(A, L, c);
  INFO(r.summary());
  CHECK(r.passed);
  CHECK(r.find("on_P"));
  CHECK_FALSE(r.find("on_R"));
  CHECK_FALSE(r.find("on_polar_plane"));
}

TEST_CASE("check_shadow judges in the frame the result is given in", "[check]") {
  // a unit sphere at 10^6: its matrix computed in the frame of its centre is right there, and wrong as a world matrix
  const Vec3<double> c(1e6, 0, 0);
  const Mat4<double> Aworld = sphere_quadric<double>(c, 1.0);
  const Vec4<double> Lworld(1e6 + 3, 4, 8, 1);
  const Mat4<double> Alocal = unit_sphere<double>();
  const Vec4<double> Llocal(3, 4, 8, 1);
  ShadowCandidate<double> cand = candidate_of(shadow<double>(Alocal, Llocal, Method::direct));
  cand.origin = c;
  const CheckReport local = check_shadow<double>(Aworld, Lworld, cand);
  INFO(local.summary());
  CHECK(local.passed);
  cand.origin.reset();
  const CheckReport world = check_shadow<double>(Aworld, Lworld, cand);
  CHECK_FALSE(world.passed);
  CHECK(world.geometric_error > 1e3);
}

TEST_CASE("check_reflection: qverify's reflection passes, wrong ones fail", "[check]") {
  const Mat4<double> A = ellipsoid_quadric<double>(Vec3<double>(1, 2, 3), Vec3<double>(1, 2, 3), Mat3<double>::Identity());
  const Vec4<double> plane(0, 0, 1, 0);
  const Mat4<double> M = mirror_matrix<double>(plane);
  ReflectionCandidate<double> c;
  c.M = M;
  c.B = reflection<double>(A, M, Method::direct).B;
  const CheckReport r = check_reflection<double>(A, plane, c);
  INFO(r.summary());
  CHECK(r.passed);
  CHECK(r.kind == "reflection");
  CHECK(r.M_error == 0.0);

  ReflectionCandidate<double> wrongB = c;
  wrongB.B = A;  // the unreflected quadric
  const CheckReport rb = check_reflection<double>(A, plane, wrongB);
  CHECK_FALSE(rb.passed);
  CHECK_THAT(rb.summary(), Catch::Contains("expected B"));

  ReflectionCandidate<double> wrongM = c;
  wrongM.M = Mat4<double>::Identity();
  CHECK_FALSE(check_reflection<double>(A, plane, wrongM).passed);

  ReflectionCandidate<double> zeroB;  // vanishes at every point, but is no quadric
  zeroB.B = Mat4<double>::Zero();
  const CheckReport rz = check_reflection<double>(A, plane, zeroB);
  CHECK_FALSE(rz.passed);
  CHECK_THAT(rz.summary(), Catch::Contains("B is zero"));
  REQUIRE(rz.certified);
  CHECK(rz.certified->upper == std::numeric_limits<double>::infinity());

  ReflectionCandidate<double> onlyB;
  onlyB.B = c.B;
  CHECK(check_reflection<double>(A, plane, onlyB).passed);

  ReflectionCandidate<Q> exact;
  const Mat4<Q> Aq = exact_matrix(A);
  const Vec4<Q> pq = exact_matrix(plane);
  exact.M = mirror_matrix<Q>(pq);
  exact.B = reflection<Q>(Aq, *exact.M, Method::direct).B;
  const CheckReport re = check_reflection<Q>(Aq, pq, exact);
  CHECK(re.passed);
  CHECK(re.proved_exactly == static_cast<int>(re.points));
}

TEST_CASE("check_reflection: a quadric without real points must stay without them", "[check]") {
  // (x - c)^2 + y^2 + z^2 + 1/100 = 0: no real point, so M^T A M has none either. A rounded B that became a
  // real sphere was skipped ("no real point to sample") and eval left it unflagged (audit 38a F1).
  const Vec4<double> plane(0, 0, 1, -1);
  // (here (x - c)^2 + y^2 + z^2 + 1/64 = 0, c = 1000.5: its doubles exact)
  const double c = 1000.5;
  Mat4<double> A = Mat4<double>::Identity();
  A(0, 3) = A(3, 0) = -c;
  A(3, 3) = c * c + 1.0 / 64;
  const Mat4<double> M = mirror_matrix<double>(plane);
  ReflectionCandidate<double> right;
  right.B = Mat4<double>(M.transpose() * A * M);
  const CheckReport r = check_reflection<double>(A, plane, right);
  INFO(r.summary());
  CHECK(r.skipped);  // definite: nothing to sample, nothing wrong
  CHECK(r.problems.size() == 1);
  ReflectionCandidate<double> real = right;
  (*real.B)(3, 3) -= 1;  // now |x - c'|^2 = 63/64: a real sphere
  const CheckReport rr = check_reflection<double>(A, plane, real);
  CHECK_FALSE(rr.passed);
  CHECK_FALSE(rr.skipped);
  CHECK_THAT(rr.summary(), Catch::Contains("B has real points, where M^T A M has none"));
  ReflectionCandidate<double> point = right;
  (*point.B)(3, 3) -= 1.0 / 64;  // a single real point (semidefinite): also wrong
  CHECK_FALSE(check_reflection<double>(A, plane, point).passed);
}

TEST_CASE("bad input at the check door: an InputError naming the argument, nothing computed", "[check]") {
  const Mat4<double> A = unit_sphere<double>();
  const Vec4<double> L = lamp<double>();
  ShadowCandidate<double> c = candidate_of(shadow<double>(A, L, Method::direct));
  auto path_of = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.path;
    }
    return "(no error)";
  };
  Mat4<double> nanA = A;
  nanA(1, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK(path_of([&] { check_shadow<double>(nanA, L, c); }) == "A[1][2]");
  Mat4<double> asym = A;
  asym(0, 3) = 0.5;
  CHECK(path_of([&] { check_shadow<double>(asym, L, c); }) == "A[3][0]");  // a pair is named below the diagonal
  // the zero matrix is a degenerate quadric, not an input error (as in a scene)
  CHECK(path_of([&] { check_shadow<double>(Mat4<double>::Zero(), L, c); }) == "(no error)");
  CHECK(path_of([&] { check_shadow<double>(A, Vec4<double>::Zero(), c); }) == "L");
  Vec4<double> infL = L;
  infL(2) = std::numeric_limits<double>::infinity();
  CHECK(path_of([&] { check_shadow<double>(A, infL, c); }) == "L[2]");
  ShadowCandidate<double> nanP = c;
  (*nanP.P)(3, 3) = std::numeric_limits<double>::quiet_NaN();
  CHECK(path_of([&] { check_shadow<double>(A, L, nanP); }) == "P[3][3]");
  CHECK(path_of([&] { check_shadow<double>(A, L, ShadowCandidate<double>{}); }) == "candidate");
  CheckOptions bad;
  bad.accuracy = 0;
  CHECK(path_of([&] { check_shadow<double>(A, L, c, bad); }) == "accuracy");
  bad.accuracy = std::numeric_limits<double>::quiet_NaN();
  CHECK(path_of([&] { check_shadow<double>(A, L, c, bad); }) == "accuracy");
  // samples: 1 to kMaxSamples at every door (INT_MAX overflowed the sampler's attempt count and came
  // back "skipped", audit 31b F3); threads of a batch: 0 or more
  CheckOptions many;
  many.samples = std::numeric_limits<int>::max();
  CHECK(path_of([&] { check_shadow<double>(A, L, c, many); }) == "samples");
  many.samples = kMaxSamples + 1;
  CHECK(path_of([&] { check_shadow<double>(A, L, c, many); }) == "samples");
  BatchCheckOptions negative;
  negative.threads = -3;
  CHECK(path_of([&] { check_shadows<double>({A}, {L}, {c}, negative); }) == "threads");
  ReflectionCandidate<double> r;
  r.B = A;
  CHECK(path_of([&] { check_reflection<double>(A, Vec4<double>(0, 0, 0, 1), r); }) == "plane");
}

TEST_CASE("an error between the samples fails the check: certified over the whole terminator", "[check][certified]") {
  // An ellipsoid 10^4 long, 1 wide and 10^-4 thin (x^2 10^8 + y^2 + z^2 10^-8 = 1, centred at
  // (1/2, 1/4, 1/8)) lit from close by: the paper route in double is far off near the terminator's tips,
  // which the certified bound covers whatever the samples reach (random chords rarely reached them; the
  // chords are shaped by the terminator's axes since session 30: test_stress.cpp, mixed magnitudes).
  Mat4<double> A = Mat4<double>::Zero();
  const double c[3] = {0.5, 0.25, 0.125}, k[3] = {1e8, 1, 1e-8};
  A(3, 3) = -1;
  for (int i = 0; i < 3; ++i) {
    A(i, i) = k[i];
    A(i, 3) = A(3, i) = -k[i] * c[i];
    A(3, 3) += k[i] * c[i] * c[i];
  }
  const Vec4<double> L(2.5, 3.25, 6.125, 1);
  CheckOptions opt;
  opt.method = Method::paper;
  const CheckReport rep = check_shadow<double>(A, L, candidate_of(shadow<double>(A, L, Method::paper)), opt);
  INFO(rep.summary());
  CHECK_FALSE(rep.passed);
  REQUIRE(rep.certified);
  CHECK(rep.certified->attained > 1e-6);
  CHECK(rep.certified->attained <= rep.certified->upper);
  REQUIRE(rep.find("on_P"));
  CHECK(Measure(rep.find("on_P")->geometric_error) <= Measure(rep.certified->upper));  // the samples lie within
  CHECK(rep.geometric_error >= rep.certified->attained);
  // the direct route in a local frame is right everywhere: certified within the target
  const Vec3<double> o(c[0], c[1], c[2]);
  Mat4<double> T = Mat4<double>::Identity();
  T.topRightCorner<3, 1>() = o;  // x_world = x_local + o (exact: o is binary)
  const Mat4<double> A_local = T.transpose() * A * T;
  const Vec4<double> L_local(L(0) - o(0), L(1) - o(1), L(2) - o(2), 1);
  ShadowCandidate<double> local = candidate_of(shadow<double>(A_local, L_local, Method::direct));
  local.origin = o;
  const CheckReport good = check_shadow<double>(A, L, local);
  INFO(good.summary());
  CHECK(good.passed);
  REQUIRE(good.certified);
  CHECK(good.certified->upper <= 1e-9);
}

// ------------------------------------------------------------------ batches

namespace {

/// n spheres (centre (i, i/2, -i/3), radius 1 + i/7) lit from (10/3, 4 + i, 8), as batch rows.
void sphere_rows(Eigen::Index n, SymBatch<double>& A, Vec4Batch<double>& L) {
  A.resize(n, 10);
  L.resize(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = static_cast<double>(i);
    scatter_sym(A, i, sphere_quadric<double>(Vec3<double>(d, d / 2, -d / 3), 1 + d / 7));
    L.row(i) = Eigen::RowVector4d(10.0 / 3, 4 + d, 8, 1);
  }
}

void same_report(const CheckReport& a, const CheckReport& b) {
  CHECK(a.passed == b.passed);
  CHECK(a.points == b.points);
  CHECK(a.problems == b.problems);
  CHECK(a.object_size == b.object_size);
  CHECK(a.geometric_error == b.geometric_error);
  REQUIRE(a.checks.size() == b.checks.size());
  for (std::size_t k = 0; k < a.checks.size(); ++k) CHECK(a.checks[k].geometric_error == b.checks[k].geometric_error);
}

}  // namespace

TEST_CASE("positive multiples of A, L and the mirror plane get the very same report", "[check]") {
  // The same quadric, light and mirror: the same points in the same representation, sizes and bounds
  // (ItemPoints from canonical_quadric / canonical_light; the sampler on primitive integers). A
  // multiple once moved the polar plane's points and the generator offsets, and sizes in their last
  // digits.
  const Mat4<Q> A = [] {
    Mat4<Q> m;
    m << Q(2), Q(1, 3), Q(0), Q(1, 5), Q(1, 3), Q(3), Q(1, 7), Q(-1), Q(0), Q(1, 7), Q(1), Q(0), Q(1, 5), Q(-1), Q(0), Q(-4);
    return m;
  }();
  for (const Vec4<Q>& L : {Vec4<Q>(Q(1, 10), Q(1, 5), Q(97, 10), Q(1)), Vec4<Q>(Q(-1), Q(2), Q(4), Q(0))}) {
    const ShadowResult<double> s = shadow<double>(A.unaryExpr([](const Q& q) { return q.convert_to<double>(); }).eval(),
                                                  L.unaryExpr([](const Q& q) { return q.convert_to<double>(); }).eval(),
                                                  Method::direct);
    ExactShadowCandidate c;
    c.P = s.P.unaryExpr([](double x) { return Q(x); }).eval();
    c.polar_plane = s.polar_plane.unaryExpr([](double x) { return Q(x); }).eval();
    c.R = s.R.unaryExpr([](double x) { return Q(x); }).eval();
    const Measure eps = std::numeric_limits<double>::epsilon() / 2;
    const CheckReport base = check_shadow_exact(A, L, c, CheckOptions{}, eps);
    for (const Q& k : {Q(7), Q(1, 3), Q(4)})
      for (const Q& lk : {Q(1), Q(3), Q(2, 9)}) {
        INFO("A times " << k << ", L times " << lk);
        const CheckReport r = check_shadow_exact(Mat4<Q>(A * k), Vec4<Q>(L * lk), c, CheckOptions{}, eps);
        same_report(base, r);
        CHECK(r.second_plane_error == base.second_plane_error);
        REQUIRE(r.certified.has_value() == base.certified.has_value());
        if (r.certified) CHECK(r.certified->upper == base.certified->upper);
      }
  }
  const Vec4<Q> plane(Q(1, 3), Q(2, 3), Q(2, 3), Q(-5));
  ExactReflectionCandidate m;
  m.B = mirror_image_of_plane<Rational>(A, plane).unaryExpr([](const Q& q) { return Q(q.convert_to<double>()); }).eval();
  const Measure eps = std::numeric_limits<double>::epsilon() / 2;
  const CheckReport base = check_reflection_exact(A, plane, m, CheckOptions{}, eps);
  for (const Q& k : {Q(7), Q(1, 3)}) {
    const CheckReport r = check_reflection_exact(Mat4<Q>(A * k), Vec4<Q>(plane * Q(3)), m, CheckOptions{}, eps);
    same_report(base, r);
  }
}

TEST_CASE("check_shadow_batch: each report is its item's alone, on any number of threads", "[check][batch]") {
  const Eigen::Index n = 9;
  SymBatch<double> A, P, R;
  Vec4Batch<double> L, pi;
  sphere_rows(n, A, L);
  shadow_batch(A, L, Method::direct, P, pi, R, 2);
  // item 4: the wrong sign of the rank-one term (P = s A + (AL)(AL)^T vanishes on the terminator too)
  {
    const Mat4<double> A4 = gather_sym(A, 4);
    const Vec4<double> l = L.row(4).transpose(), p = A4 * l;
    scatter_sym(P, 4, Mat4<double>(l.dot(p) * A4 + p * p.transpose()));
  }
  std::vector<std::size_t> seen;
  BatchCheckOptions opt;
  opt.check.samples = 16;
  opt.progress = [&](std::size_t done, std::size_t total) {
    CHECK(total == static_cast<std::size_t>(n));
    seen.push_back(done);
  };
  const std::vector<CheckReport> two = check_shadow_batch(A, L, P, pi, R, opt);
  opt.threads = 1;
  opt.progress = nullptr;
  const std::vector<CheckReport> one = check_shadow_batch(A, L, P, pi, R, opt);
  REQUIRE(two.size() == static_cast<std::size_t>(n));
  CHECK(seen.size() == static_cast<std::size_t>(n));
  CHECK(std::is_sorted(seen.begin(), seen.end()));
  CHECK(seen.back() == static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    INFO("item " << i);
    ShadowCandidate<double> c;
    c.P = gather_sym(P, i);
    c.polar_plane = Vec4<double>(pi.row(i).transpose());
    c.R = gather_sym(R, i);
    const CheckReport alone = check_shadow<double>(gather_sym(A, i), L.row(i).transpose(), c, opt.check);
    same_report(two[static_cast<std::size_t>(i)], alone);
    same_report(one[static_cast<std::size_t>(i)], alone);
    CHECK(alone.passed == (i != 4));
  }
  // the status words the program reported, one per item: a wrong one fails its item alone, as in
  // check_shadow (audit 31b F4: the batch doors took none, so could not fail a wrong word)
  std::vector<std::string> words(static_cast<std::size_t>(n), "ok");
  words[6] = "light-on-surface";
  words[7] = "";  // none reported
  const std::vector<CheckReport> worded = check_shadow_batch(A, L, P, pi, R, opt, words);
  for (Eigen::Index i = 0; i < n; ++i) {
    INFO("item " << i);
    CHECK(worded[static_cast<std::size_t>(i)].passed == (i != 4 && i != 6));
    CHECK(worded[static_cast<std::size_t>(i)].item_status == (i == 6 ? "light-on-surface" : "ok"));
  }
  CHECK_THROWS_AS(check_shadow_batch(A, L, P, pi, R, opt, std::vector<std::string>(3, "ok")), InputError);
  // only P given: the other arrays empty
  const std::vector<CheckReport> onlyP = check_shadow_batch(A, L, P, Vec4Batch<double>(), SymBatch<double>(), opt);
  CHECK(onlyP[4].find("on_P"));
  CHECK_FALSE(onlyP[4].find("on_polar_plane"));
  CHECK_FALSE(onlyP[4].passed);
  CHECK(onlyP[3].passed);
}

TEST_CASE("check_reflection_batch checks reflection_batch's arrays item by item", "[check][batch]") {
  const Eigen::Index n = 6;
  SymBatch<double> A, B;
  Vec4Batch<double> L, planes(n, 4);
  AffineBatch<double> M;
  sphere_rows(n, A, L);
  for (Eigen::Index i = 0; i < n; ++i) planes.row(i) = Eigen::RowVector4d(1, 2 + static_cast<double>(i), -1, 3);
  reflection_batch(A, planes, Method::direct, M, B, 2);
  B(2, 0) *= 1 + 1e-6;  // item 2: B00 off by a millionth
  BatchCheckOptions opt;
  opt.check.samples = 16;
  const std::vector<CheckReport> r = check_reflection_batch(A, planes, M, B, opt);
  REQUIRE(r.size() == static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    INFO("item " << i << "\n" << r[static_cast<std::size_t>(i)].summary());
    CHECK(r[static_cast<std::size_t>(i)].passed == (i != 2));
  }
  std::vector<std::string> words(static_cast<std::size_t>(n), "ok");
  words[4] = "degenerate-quadric";
  const std::vector<CheckReport> worded = check_reflection_batch(A, planes, M, B, opt, words);
  for (Eigen::Index i = 0; i < n; ++i) CHECK(worded[static_cast<std::size_t>(i)].passed == (i != 2 && i != 4));
  CHECK_THROWS_AS(check_reflection_batch(A, planes, M, B, opt, std::vector<std::string>(1, "ok")), InputError);
}

TEST_CASE("batch checks reject bad input before computing anything, naming the item", "[check][batch][errors]") {
  const Eigen::Index n = 5;
  SymBatch<double> A, P, R;
  Vec4Batch<double> L, pi;
  sphere_rows(n, A, L);
  shadow_batch(A, L, Method::direct, P, pi, R, 1);
  bool called = false;
  BatchCheckOptions opt;
  opt.progress = [&](std::size_t, std::size_t) { called = true; };
  auto error_of = [&](auto&& f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.file + " | " + e.path;
    }
    return "no error";
  };
  SymBatch<double> bad = P;
  bad(3, 1) = std::numeric_limits<double>::quiet_NaN();
  // (errors name the function called, the item and the entry of its matrix: audit 42d named check_shadows)
  CHECK(error_of([&] { check_shadow_batch(A, L, bad, pi, R, opt); }) == "check_shadow_batch | [3].P[0][1]");
  CHECK(error_of([&] { check_shadow_batch(A, Vec4Batch<double>(L.topRows(4)), P, pi, R, opt); }) == "check_shadow_batch | L");
  CHECK(error_of([&] { check_shadow_batch(A, L, SymBatch<double>(), Vec4Batch<double>(), SymBatch<double>(), opt); }) ==
        "check_shadow_batch | candidate");
  Vec4Batch<double> dark = L;
  dark.row(1).setZero();
  CHECK(error_of([&] { check_shadow_batch(A, dark, P, pi, R, opt); }) == "check_shadow_batch | [1].L");
  std::vector<Mat4<double>> As{unit_sphere<double>()};
  std::vector<Vec4<double>> Ls{lamp<double>(), lamp<double>()};
  std::vector<ShadowCandidate<double>> cs(1);
  CHECK(error_of([&] { check_shadows<double>(As, Ls, cs, opt); }) == "check_shadows | L");
  opt.check.accuracy = -1;
  CHECK(error_of([&] { check_shadow_batch(A, L, P, pi, R, opt); }) == "check_shadow_batch | accuracy");
  CHECK_FALSE(called);
  // an empty batch is no error and no work, from vectors and from arrays alike (a frame without
  // objects: the arrays' "no rows, not given" had made it "nothing to check", audit 42d)
  CHECK(check_shadows<double>({}, {}, {}, BatchCheckOptions{}).empty());
  CHECK(check_shadow_batch(SymBatch<double>(), Vec4Batch<double>(), SymBatch<double>(), Vec4Batch<double>(),
                           SymBatch<double>()).empty());
  CHECK(check_reflection_batch(SymBatch<double>(), Vec4Batch<double>(), AffineBatch<double>(), SymBatch<double>()).empty());
  CHECK(error_of([&] { check_reflection_batch(SymBatch<double>(), Vec4Batch<double>(), AffineBatch<double>(),
                                              SymBatch<double>(A.topRows(1))); }) == "check_reflection_batch | B");
}
