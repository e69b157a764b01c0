// The exact twin: Q(sqrt d) points, exact sampling, symbolic scalar, paper audit verdicts,
// and the double core against the exact one on random rational data.
#include "laws.hpp"

#include <qverify/exact/polynomial.hpp>
#include <qverify/exact/root_point.hpp>
#include <qverify/exact/sampling.hpp>
#include <qverify/eval/eval.hpp>
#include <qverify/report/eval_document.hpp>
#include <qverify/verify/adaptive.hpp>
#include <qverify/studies/paper_audit.hpp>

using namespace qverify;
using Q = Rational;

TEST_CASE("Q(sqrt d) arithmetic agrees with the closed form of a quadratic form", "[exact][root]") {
  test::RandomRationals rng(7);
  for (int k = 0; k < 30; ++k) {
    const Mat4<Q> A = rng.symmetric();
    const Vec4<Q> p = rng.vec4(), q = rng.vec4();
    const Q delta = Q(1 + k * 3, 1 + k % 4);
    const RootPoint x(p, q, delta);
    const RootNumber f = x.form(A);
    // x^T A x = p^T A p + delta q^T A q + 2 sqrt(delta) p^T A q, with q rescaled by the normalisation
    const Q a0 = p.dot(A * p) + delta * q.dot(A * q);
    const Q a1 = 2 * p.dot(A * q);
    // compare numerically to 60 digits and exactly through the sign of the difference
    const Measure expect = to_measure(a0) + to_measure(a1) * sqrt(to_measure(delta));
    CHECK(abs(to_measure(f) - expect) <= Measure("1e-60") * (1 + abs(expect)));
  }
}

TEST_CASE("values that leave the point's field are refused - in release builds too", "[exact][root]") {
  // A point whose q is zero is rational; mapping keeps the field; a forged mix cannot be built through the API,
  // so check the guard directly through a non-integer delta normalisation.
  const RootPoint x(Vec4<Q>(1, 2, 3, 1), Vec4<Q>(1, 0, 0, 0), Q(2, 3));
  CHECK(x.delta() == 6);  // sqrt(2/3) = sqrt(6)/3
  CHECK(x.q()(0) == Q(1, 3));
  CHECK_NOTHROW(x.form(Mat4<Q>::Identity()));
}

TEST_CASE("points made from an integer radicand equal the constructor's, enclosures included", "[exact][root]") {
  test::RandomRationals rng(11);
  auto same = [](const RootPoint& a, const RootPoint& b) {
    CHECK(a.p() == b.p());
    CHECK(a.q() == b.q());
    CHECK(a.delta() == b.delta());
    for (std::size_t i = 0; i < 4; ++i) {
      CHECK(a.enclosure()[i].inf() == b.enclosure()[i].inf());
      CHECK(a.enclosure()[i].sup() == b.enclosure()[i].sup());
    }
  };
  for (int k = 0; k < 40; ++k) {
    const Vec4<Q> p = rng.vec4();
    Vec4<Q> q = rng.vec4();
    if (k % 5 == 0) q(k % 4) = 0;  // a rational coordinate
    // a radicand beyond the range of a double too (the enclosure takes another route there)
    const Q n = k % 7 == 0 ? Q(boost::multiprecision::mpz_int(1) << 1100) + k : Q(2 + 3 * k);
    const RootPoint x(p, q, n), y(p, Vec4<Q>(-q), n);
    same(RootPoint::with_integer_radicand(p, q, n), x);
    const auto both = RootPoint::conjugates(p, q, n);
    same(both[0], x);
    same(both[1], y);
    // and they enclose the point; with the huge radicand also for a q of 2^-549, whose
    // coordinates are of order 1 (the product sqrt(delta) q_i is then what is enclosed)
    const RootPoint z(p, Vec4<Q>(q / Q(boost::multiprecision::mpz_int(1) << 549)), n);
    for (const RootPoint* w : {&x, &y, &z})
      for (std::size_t i = 0; i < 4; ++i) {
        const Measure xi = to_measure(w->coords()[i]);
        CHECK(Measure(w->enclosure()[i].inf()) <= xi);
        CHECK(xi <= Measure(w->enclosure()[i].sup()));
        CHECK(w->enclosure()[i].sup() - w->enclosure()[i].inf() <= 1e-14 * (1 + abs(xi.convert_to<double>())));
      }
  }
  same(RootPoint::with_integer_radicand(Vec4<Q>(1, 2, 3, 1), Vec4<Q>(1, 1, 1, 0), Q(0)),
       RootPoint(Vec4<Q>(1, 2, 3, 1), Vec4<Q>(1, 1, 1, 0), Q(0)));
  CHECK_THROWS_AS(RootPoint::with_integer_radicand(Vec4<Q>::Zero(), Vec4<Q>::Zero(), Q(2, 3)), std::domain_error);
  CHECK_THROWS_AS(RootPoint::with_integer_radicand(Vec4<Q>::Zero(), Vec4<Q>::Zero(), Q(-2)), std::domain_error);
  CHECK_THROWS_AS(RootPoint::conjugates(Vec4<Q>::Zero(), Vec4<Q>::Zero(), Q(0)), std::domain_error);
}

TEST_CASE("exact samples lie exactly on the terminator and on the quadric - same seed - same points", "[exact][sampling]") {
  const Mat4<Q> A = ellipsoid_quadric<Q>(Vec3<Q>(Q(3, 2), Q(-1, 2), 3), Vec3<Q>(1, 2, Q(3, 4)), Mat3<Q>::Identity());
  const Vec4<Q> L(1, -2, 9, 1);
  const Vec4<Q> pi = A * L;
  const SampleReport s = sample_section(A, pi, 32, 5, Q(1));
  REQUIRE(s.points.size() == 32);
  for (const RootPoint& x : s.points) {
    CHECK(CGAL::is_zero(x.form(A)));
    CHECK(CGAL::is_zero(x.linear(pi)));
    CHECK(CGAL::is_zero(x.form(tangent_cone<Q>(A, L))));
    CHECK(CGAL::is_zero(x.form(terminator_quadric<Q>(A, L))));
    CHECK(!CGAL::is_zero(x.coords()[3]));
  }
  const SampleReport again = sample_section(A, pi, 32, 5, Q(1));
  CHECK(again.points[7].p() == s.points[7].p());
  const SampleReport other = sample_section(A, pi, 32, 6, Q(1));
  CHECK(!(other.points[7].p() == s.points[7].p() && other.points[7].q() == s.points[7].q()));
  const SampleReport onA = sample_quadric(A, 16, 3, Q(1));
  REQUIRE(onA.points.size() == 16);
  const Mat4<Q> M = mirror_matrix<Q>(Vec4<Q>(1, 1, 0, -10));
  const Mat4<Q> B = mirror_image<Q>(A, M);
  for (const RootPoint& x : onA.points) {
    CHECK(CGAL::is_zero(x.form(A)));
    CHECK(CGAL::is_zero(x.mapped(M).form(B)));
  }
}

TEST_CASE("no real terminator: nothing is sampled - a single real point is found exactly", "[exact][sampling]") {
  const Mat4<Q> S = sphere_quadric<Q>(Vec3<Q>::Zero(), Q(1));
  const Vec4<Q> inside(0, Q(1, 2), 0, 1);
  CHECK(sample_section(S, Vec4<Q>(S * inside), 8, 1, Q(1)).points.empty());
  // cone lit along its axis from infinity: the terminator is the apex alone
  const Mat4<Q> cone = cone_quadric<Q>(Vec3<Q>(2, 2, 0), Vec3<Q>(0, 0, 1), Q(1, 3));
  const Vec4<Q> sun(0, 0, 1, 0);
  const SampleReport s = sample_section(cone, Vec4<Q>(cone * sun), 8, 1, Q(1));
  REQUIRE(s.points.size() == 1);
  CHECK(s.points[0].p() == Vec4<Q>(2, 2, 0, 1));
}

TEST_CASE("symbolic scalar: Laurent polynomials through the generic core", "[exact][poly]") {
  const Poly x = Poly::var(0), y = Poly::var(1);
  CHECK((x + y) * (x - y) == x * x - y * y);
  CHECK((x * y) / y == x);
  CHECK(Poly(1) / x * x == Poly(1));
  CHECK_THROWS_AS(x / (x + y), std::domain_error);
  CHECK_THROWS_AS((void)(x < y), std::domain_error);
  CHECK((x * x * y).derivative(0) == Poly(2) * x * y);
  // the tangent cone through the generic core: P L = 0 identically
  Mat4<Poly> A;
  int k = 2;
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j) A(i, j) = A(j, i) = Poly::var(k++);
  const Vec4<Poly> L(x, y, Poly(1), Poly(1));
  const Vec4<Poly> PL = tangent_cone<Poly>(A, L) * L;
  for (int i = 0; i < 4; ++i) CHECK(PL(i) == Poly(0));
}

TEST_CASE("paper audit verdicts", "[exact][paper]") {
  const auto entries = audit_paper();
  std::map<std::string, std::string> verdict;
  for (const auto& e : entries) {
    verdict[e.id] = e.verdict;
    CHECK(!e.evidence.empty());
    CHECK(e.evidence.find("FAILS") == std::string::npos);  // every symbolic sub-check came out as stated
    if (e.verdict == "fails") CHECK(!e.corrected.empty());
  }
  CHECK(verdict.size() == 11);
  CHECK(verdict["(1)"] == "definition");
  CHECK(verdict["(2)"] == "holds");
  CHECK(verdict["(3)"] == "holds-up-to-factor");
  CHECK(verdict["(4)"] == "holds");
  CHECK(verdict["(5)"] == "holds");
  CHECK(verdict["(6)"] == "fails");
  CHECK(verdict["(7)"] == "definition");
  CHECK(verdict["(8)"] == "definition");
  CHECK(verdict["(9)"] == "fails");
  CHECK(verdict["(10)"] == "definition");
  CHECK(verdict["(11)"] == "holds");
}

TEST_CASE("the double core is within a rounding-error bound of the exact twin", "[exact][twin]") {
  test::RandomRationals rng(99);
  const double eps = std::numeric_limits<double>::epsilon();
  for (int k = 0; k < 200; ++k) {
    const Mat4<Q> A = rng.symmetric();
    Vec4<Q> L = rng.vec4();
    L(3) = k % 4 == 0 ? 0 : 1;
    if (L(2) == 0) L(2) = 1;
    const Vec4<Q> plane = rng.vec4() + Vec4<Q>(0, 0, 1, 0) * Q(1, 7);
    for (Method m : {Method::direct, Method::paper}) {
      const auto e = shadow<Q>(A, L, m);
      const auto d = shadow<double>(test::to_scalar<double>(A), test::to_scalar<double>(L), m);
      // bound: 64 eps times the absolute-value evaluation of the formula over |P|
      const Mat4<Q> aA = A.cwiseAbs();
      const Vec4<Q> aL = L.cwiseAbs();
      const Mat4<Q> Pabs = aL.dot(aA * aL) * aA + (aA * aL) * (aA * aL).transpose();
      const double kappa = CGAL::to_double(to_gmpq(max_abs(Pabs))) / CGAL::to_double(to_gmpq(max_abs(e.P)));
      // the paper route goes through N = T M (1/l_z): its rounding is amplified by cond_inf(N)^2
      double frame = 1;
      if (m == Method::paper) {
        const PaperFrame<Q> f = paper_frame<Q>(L);
        auto inf = [](const Mat4<Q>& X) { return CGAL::to_double(to_gmpq(Q(X.cwiseAbs().rowwise().sum().maxCoeff()))); };
        const double cond = inf(Mat4<Q>(f.T * f.M)) * inf(Mat4<Q>(f.Minv * f.Tinv));
        frame = cond * cond;
      }
      INFO("case " << k);
      const Mat4<Q> dP = d.P.unaryExpr([](double v) { return to_rational(v); });
      CHECK(to_measure(cross_residual(dP, e.P)) <= Measure(64 * eps * kappa * frame));
    }
    const Mat4<Q> M = mirror_matrix<Q>(plane);
    const Mat4<double> Md = mirror_matrix<double>(test::to_scalar<double>(plane));
    CHECK(to_measure(cross_residual(Mat4<Q>(Md.unaryExpr([](double v) { return to_rational(v); })), M)) <=
          Measure(64 * eps * 10));
  }
}

TEST_CASE("interval results enclose the exact results of the same formula", "[exact][interval]") {
  const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/mixed-requests.json");
  for (Method m : {Method::direct, Method::paper}) {
    const Evaluation<Interval> iv = evaluate<Interval>(sc, m);
    const Evaluation<Q> ex = evaluate<Q>(sc, m);
    CHECK(iv.frame == Frame::world);
    auto inside = [](const auto& I, const auto& E) {
      for (Eigen::Index i = 0; i < E.size(); ++i)
        if (!(to_rational(I(i).inf()) <= E(i) && E(i) <= to_rational(I(i).sup()))) return false;
      return true;
    };
    for (std::size_t k = 0; k < ex.shadows.size(); ++k) {
      CHECK(inside(iv.shadows[k].result.P, ex.shadows[k].result.P));
      CHECK(inside(iv.shadows[k].result.polar_plane, ex.shadows[k].result.polar_plane));
      CHECK(inside(iv.shadows[k].result.R, ex.shadows[k].result.R));
    }
    for (std::size_t k = 0; k < ex.reflections.size(); ++k) {
      CHECK(inside(iv.reflections[k].M, ex.reflections[k].M));
      CHECK(inside(iv.reflections[k].result.B, ex.reflections[k].result.B));
    }
  }
}

TEST_CASE("adaptive mode: every item is within its certified bound of the exact result", "[exact][adaptive]") {
  CHECK_THROWS(eval_json(adaptive_eval_report(load_scene(std::string(QVERIFY_SCENES) + "/egg-sun-wall.json"), Method::direct, 1e-18)));
  std::map<std::string, int> stages;
  for (const char* file : {"mixed-requests.json", "egg-sun-wall.json", "far-ball-lamp-floor.json"})
    for (double tol : {1e-9, 1e-15, 2e-16, std::ldexp(1.0, -53)}) {
      INFO(file << " " << tol);
      const Scene sc = load_scene(std::string(QVERIFY_SCENES) + "/" + file);
      const auto doc = eval_json(adaptive_eval_report(sc, Method::direct, tol));
      const Evaluation<Q> ex = evaluate<Q>(sc, Method::direct, Frame::world);
      auto check = [&](const nlohmann::ordered_json& got, const auto& want, double bound) {
        Q scale = max_abs(want);
        for (Eigen::Index i = 0; i < want.size(); ++i) {
          const auto& v = want.cols() == 1 ? got[static_cast<std::size_t>(i)]
                                           : got[static_cast<std::size_t>(i / 4)][static_cast<std::size_t>(i % 4)];
          const Q g = to_rational(v.template get<double>());
          const Q w = want(i / want.cols(), i % want.cols());
          CHECK(to_measure(Q(g > w ? g - w : w - g)) <= Measure(bound) * to_measure(scale) * Measure("1.0000001"));
        }
      };
      // an item's certified bound: within the tolerance unless only the exact stage could certify it
      auto certified_bound = [&](const nlohmann::ordered_json& item) {
        const double bound = item["certified"]["relative_error_bound"].get<double>();
        ++stages[item["certified"]["by"].get<std::string>()];
        CHECK((bound <= tol || item["certified"]["by"] == "exact"));
        return bound;
      };
      for (std::size_t k = 0; k < ex.shadows.size(); ++k) {
        const auto& item = doc["shadows"][k];
        const double bound = certified_bound(item);
        check(item["P"], ex.shadows[k].result.P, bound);
        check(item["R"], ex.shadows[k].result.R, bound);
      }
      for (std::size_t k = 0; k < ex.reflections.size(); ++k) {
        const auto& item = doc["reflections"][k];
        check(item["B"], ex.reflections[k].result.B, certified_bound(item));
      }
    }
  // the ladder is exercised: tight tolerances need the MPFR-interval stage
  CHECK(stages["double"] > 0);
  CHECK(stages["mpfr"] > 0);
}

TEST_CASE("samples of unbounded quadrics far from the origin are found at the object, not along it", "[exact][sampling]") {
  // Lines drawn from the world origin 2.2e6 away from a cylinder of radius 1 missed it (so a
  // reflection was "skipped: no real point") or met its terminator 10^6 away along its axis (an object
  // size of 10^6): the base point is now the object's own (core_point): an axis point of the
  // cylinder, a cone's apex moved, a point inside a paraboloid.
  const Vec3<Q> far(1000000, 2000000, 0);
  const Mat4<Q> cylinder = cylinder_quadric<Q>(far, Vec3<Q>(0, 0, 1), Q(1));
  const Mat4<Q> cone = cone_quadric<Q>(Vec3<Q>(far + Vec3<Q>(0, 0, 5)), Vec3<Q>(0, 1, 1), Q(1, 2));
  Mat4<Q> paraboloid = Mat4<Q>::Zero();  // z - 3 = (x - 10^6)^2 + 2 (y - 2 10^6)^2
  paraboloid(0, 0) = 1, paraboloid(1, 1) = 2, paraboloid(0, 3) = paraboloid(3, 0) = -far(0);
  paraboloid(1, 3) = paraboloid(3, 1) = -2 * far(1), paraboloid(2, 3) = paraboloid(3, 2) = Q(-1, 2);
  paraboloid(3, 3) = far(0) * far(0) + 2 * far(1) * far(1) + 3;
  auto near = [&](const RootPoint& x, double within) {
    const auto c = x.coords();
    double d2 = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = CGAL::to_double(c[static_cast<std::size_t>(i)] / c[3]) - far(i).convert_to<double>();
      d2 += d * d;
    }
    return std::sqrt(d2) < within;
  };
  for (const Mat4<Q>& A : {cylinder, cone, paraboloid}) {
    const SampleReport s = sample_quadric(A, 32, 7, Q(1));
    REQUIRE(s.points.size() == 32);
    for (const RootPoint& x : s.points) {
      CHECK(CGAL::is_zero(x.form(A)));
      CHECK(near(x, 1e4));
    }
  }
  const Vec4<Q> lamp(far(0) + 3, far(1) + 1, 2, 1);
  const SampleReport t = sample_section(cylinder, Vec4<Q>(cylinder * lamp), 32, 7, Q(1));
  REQUIRE(t.points.size() == 32);
  for (const RootPoint& x : t.points) CHECK(near(x, 1e3));
}
