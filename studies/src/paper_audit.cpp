#include <qverify/core/core.hpp>
#include <qverify/exact/polynomial.hpp>
#include <qverify/studies/paper_audit.hpp>
#include <qverify/eval/number.hpp>

#include <sstream>

namespace qverify {
namespace {

using P = Poly;
using Q = Rational;

// Symbol numbering of the audit.
constexpr int kSym[4][4] = {{0, 1, 2, 3}, {1, 4, 5, 6}, {2, 5, 7, 8}, {3, 6, 8, 9}};
constexpr int LX = 10, LY = 11, LZ = 12, MA = 13, MB = 14, MC = 15, MD = 16, X = 17, Y = 18, Z = 19;

std::vector<std::string> names_for(bool c_frame) {
  std::vector<std::string> n = c_frame ? std::vector<std::string>{"a1", "b1", "b2", "c1", "a2", "b3", "c2", "a3", "c3", "d"}
                                       : std::vector<std::string>{"A11", "A12", "A13", "A14", "A22",
                                                                  "A23", "A24", "A33", "A34", "A44"};
  for (const char* s : {"l_x", "l_y", "l_z", "a", "b", "c", "d", "x", "y", "z"}) n.emplace_back(s);
  return n;
}

Mat4<P> symbolic_symmetric() {
  Mat4<P> A;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) A(i, j) = P::var(kSym[i][j]);
  return A;
}

template <class Derived> bool all_zero(const Eigen::MatrixBase<Derived>& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i)
    if (!(m(i) == P(0))) return false;
  return true;
}

std::string entry_name(int i, int j) { return "(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ")"; }

Vec4<P> light_symbolic() { return Vec4<P>(P::var(LX), P::var(LY), P::var(LZ), P(1)); }

/// The matrix printed as (6), with the reading z -> l_z in entry (3,3) and
/// `dval` for the symbol printed "d" in entries (3,4) and (4,3).
template <class S> Mat4<S> printed_R(const Mat4<S>& C, const S& lx, const S& ly, const S& lz, const S& dval) {
  const S b2 = C(0, 2), b3 = C(1, 2), a3 = C(2, 2), c3 = C(2, 3);
  const S w = b2 * lx + b3 * ly + a3 * lz - c3;
  Mat4<S> R;
  R << S(0), S(0), S(-b2), S(b2 * lz),  //
      S(0), S(0), S(-b3), S(b3 * lz),    //
      S(-b2), S(-b3), S(S(2) * (c3 / lz - a3)), S(w - dval), S(b2 * lz), S(b3 * lz), S(w - dval), S(S(-2) * w);
  return R;
}

/// The corrected (6): entries (3,4) = w - c3 and (4,4) = 2 l_z (a3 l_z - w).
template <class S> Mat4<S> corrected_R(const Mat4<S>& C, const S& lx, const S& ly, const S& lz) {
  Mat4<S> R = printed_R<S>(C, lx, ly, lz, S(0));
  const S b2 = C(0, 2), b3 = C(1, 2), a3 = C(2, 2), c3 = C(2, 3);
  const S w = b2 * lx + b3 * ly + a3 * lz - c3;
  R(2, 3) = R(3, 2) = w - c3;
  R(3, 3) = S(2) * lz * (a3 * lz - w);
  return R;
}

/// The mirror matrix printed as (9) (unit normal (a, b, c), constant term d).
template <class S> Mat4<S> printed_M(const S& a, const S& b, const S& c, const S& d) {
  Mat4<S> M;
  M << S(1) - S(2) * a * a, S(-2) * a * b, S(-2) * a * c, S(-(a * d)),  //
      S(-2) * a * b, S(1) - S(2) * b * b, S(-2) * b * c, S(-(b * d)),   //
      S(-2) * a * c, S(-2) * b * c, S(1) - S(2) * c * c, S(-(c * d)),   //
      S(0), S(0), S(0), S(1);
  return M;
}

/// The reflection in n.x + d = 0 for a unit normal, division-free:
/// [[I - 2 n n^T, -2 d n], [0, 1]].
template <class S> Mat4<S> unit_reflection(const S& a, const S& b, const S& c, const S& d) {
  const Vec3<S> n(a, b, c);
  Mat4<S> M = Mat4<S>::Identity();
  M.template topLeftCorner<3, 3>() -= S(2) * (n * n.transpose());
  M.template topRightCorner<3, 1>() = S(-2) * d * n;
  return M;
}

std::string mat_text(const Mat4<Q>& m) {
  std::string s = "[";
  for (int i = 0; i < 4; ++i) {
    s += i ? " [" : "[";
    for (int j = 0; j < 4; ++j) s += (j ? " " : "") + m(i, j).str();
    s += "]";
  }
  return s + "]";
}

AuditEntry eq1() {
  return {"(1)", "a quadric surface is x^T A x = 0 with A a symmetric 4x4 matrix and x homogeneous",
          "x = (x, y, z, 1) for points, column vectors throughout", "definition",
          "notation; every shape of the scene format is converted to such an A without square roots", "", ""};
}

AuditEntry eq2() {
  AuditEntry e{"(2)",
               "C = (T^-1)^T (M^-1)^T A M^-1 T^-1 is A after the translation M and the perspective T; in this frame the "
               "light is a parallel light along Z",
               "M = translation by (-l_x, -l_y, 0); T = perspective transformation along Z, w' = w - z/l_z, i.e. "
               "T = E except T(4,3) = -1/l_z: the plane z = l_z through the light goes to infinity (the text's "
               "'vanishing point (0, 0, l_z)' read as the point T sends to infinity; it is the only reading under which "
               "the light becomes parallel). Requires l_z != 0.",
               "", "", "", ""};
  const Mat4<P> A = symbolic_symmetric();
  const Vec4<P> L = light_symbolic();
  const PaperFrame<P> f = paper_frame<P>(L);
  const Mat4<P> N = f.T * f.M, Ninv = f.Minv * f.Tinv;
  const bool inverse = all_zero(Mat4<P>(Ninv * N - Mat4<P>::Identity()));
  const bool light = all_zero(Vec4<P>(N * L - Vec4<P>(P(0), P(0), P::var(LZ), P(0))));
  const Mat4<P> C = paper_C<P>(A, f);
  const bool congruent = all_zero(Mat4<P>(N.transpose() * C * N - A));
  e.verdict = inverse && light && congruent ? "holds" : "fails";
  e.evidence = std::string("symbolic identities in the 10 entries of A and l_x, l_y, l_z (Laurent polynomials): ") +
               "M^-1 T^-1 T M = E " + (inverse ? "holds" : "FAILS") + "; (T M)^T C (T M) = A " +
               (congruent ? "holds" : "FAILS") + ", so x lies on A exactly when y = T M x lies on C; " +
               "T M (l_x, l_y, l_z, 1)^T = (0, 0, l_z, 0)^T " + (light ? "holds" : "FAILS") +
               ": the light goes to the point at infinity of the Z axis";
  return e;
}

AuditEntry eq3() {
  AuditEntry e{"(3)",
               "P = M^T T^T D T M is the cone with the light at its apex that touches A along the shadow boundary",
               "as (2); D as printed in (4)", "", "", "", ""};
  const Mat4<P> A = symbolic_symmetric();
  const Vec4<P> L = light_symbolic();
  const PaperFrame<P> f = paper_frame<P>(L);
  const Mat4<P> Pp = paper_P<P>(paper_D<P>(paper_C<P>(A, f)), f);
  const P lz = P::var(LZ);
  const bool cone = all_zero(Mat4<P>(lz * lz * Pp - tangent_cone<P>(A, L)));
  const bool apex = all_zero(Vec4<P>(Pp * L));
  e.verdict = cone && apex ? "holds-up-to-factor" : "fails";
  e.factor = "1/l_z^2 (positive)";
  e.evidence = std::string("symbolic identity: l_z^2 M^T T^T D T M = (L^T A L) A - (A L)(A L)^T ") +
               (cone ? "holds" : "FAILS") +
               ", the tangent cone of A from L = (l_x, l_y, l_z, 1); P L = 0 (apex at the light) " +
               (apex ? "holds" : "FAILS") + ". As a quadric P is the tangent cone; as a matrix it is 1/l_z^2 times it.";
  return e;
}

AuditEntry eq4() {
  AuditEntry e{"(4)",
               "D = [[a1a3-b2^2, a3b1-b2b3, 0, a3c1-b2c3] [a3b1-b2b3, a2a3-b3^2, 0, a3c2-b3c3] [0 0 0 0] "
               "[a3c1-b2c3, a3c2-b3c3, 0, a3d-c3^2]] is the elliptic cylinder along Z through the curve of C where "
               "dC/dz = 0",
               "a1..d are the entries of C as named under (2)", "", "", "", ""};
  const Mat4<P> C = symbolic_symmetric();
  const Mat4<P> D = paper_D<P>(C);
  const Vec4<P> s = C.col(2);
  const bool formula = all_zero(Mat4<P>(D - C(2, 2) * C + s * s.transpose()));
  const bool along_z = all_zero(Vec4<P>(D.col(2)));
  e.verdict = formula && along_z ? "holds" : "fails";
  e.evidence = std::string("symbolic identity in the entries of C: D = a3 C - (C e3)(C e3)^T ") +
               (formula ? "holds" : "FAILS") +
               ", so D vanishes wherever C and (C e3)^T y = 0 (that is dC/dz = 0) both do; D e3 = 0 " +
               (along_z ? "holds" : "FAILS") +
               " (generators parallel to Z). D is the tangent cone of C from the point at infinity of Z. It is an "
               "elliptic cylinder when the outline is an ellipse (an ellipsoid, say); for other quadrics it can be "
               "hyperbolic or parabolic: 'elliptic' is the common case, not a property of the formula.";
  return e;
}

AuditEntry eq5() {
  AuditEntry e{"(5)", "the plane S: b2 x + b3 y + a3 z + c3 = 0, i.e. dC/dz = 0, contains the shadow boundary on C",
               "dC/dz: derivative of y^T C y with y = (x, y, z, 1)", "", "", "", ""};
  const Mat4<P> C = symbolic_symmetric();
  const Vec4<P> y(P::var(X), P::var(Y), P::var(Z), P(1));
  const P q = y.dot(C * y);
  const P S = C(0, 2) * P::var(X) + C(1, 2) * P::var(Y) + C(2, 2) * P::var(Z) + C(2, 3);
  const bool derivative = q.derivative(Z) == P(2) * S;
  // S carried back through T and M is the polar plane of the light.
  const Mat4<P> A = symbolic_symmetric();
  const Vec4<P> L = light_symbolic();
  const PaperFrame<P> f = paper_frame<P>(L);
  const Vec4<P> back = (f.T * f.M).transpose() * paper_S<P>(paper_C<P>(A, f));
  const bool polar = all_zero(Vec4<P>(P::var(LZ) * back - A * L));
  e.verdict = derivative && polar ? "holds" : "fails";
  e.evidence = std::string("symbolic: d/dz (y^T C y) = 2 (b2 x + b3 y + a3 z + c3) ") + (derivative ? "holds" : "FAILS") +
               "; S is C e3, the polar plane of the light (now at infinity on Z), so C ∩ S is where the light grazes C. "
               "Carried back: l_z (T M)^T S = A L " +
               (polar ? "holds" : "FAILS") + " (the polar plane of the light with respect to A).";
  return e;
}

AuditEntry eq6() {
  AuditEntry e{"(6)",
               "R = [[0 0 -b2 b2*l_z] [0 0 -b3 b3*l_z] [-b2 -b3 2(c3/z - a3) w-d] [b2*l_z b3*l_z w-d -2w]], "
               "w = b2 l_x + b3 l_y + a3 l_z - c3, is the plane S carried back through T and M as a quadric "
               "containing the shadow boundary on A",
               "'z' in entry (3,3) read as l_z (no constant z is defined; z is a coordinate); 'd' in (3,4) read as the "
               "entry d of C (as printed), the alternative reading d = c3 also tested; 'S as a quadric' = S e4^T + "
               "e4 S^T (the affine equation times w), carried back as (T M)^T (.) (T M)",
               "", "", "", ""};
  const Mat4<P> C = symbolic_symmetric();
  const Vec4<P> L = light_symbolic();
  const PaperFrame<P> f = paper_frame<P>(L);
  const P lx = P::var(LX), ly = P::var(LY), lz = P::var(LZ);
  const Mat4<P> truth = lz * paper_R<P>(paper_S<P>(C), f);  // l_z (T M)^T (S e4^T + e4 S^T) (T M)
  const Mat4<P> printed = printed_R<P>(C, lx, ly, lz, C(3, 3));
  const Mat4<P> printed_c3 = printed_R<P>(C, lx, ly, lz, C(2, 3));
  const auto names = names_for(true);
  std::string agree, differ;
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < 4; ++j) {
      if (printed(i, j) == truth(i, j)) agree += (agree.empty() ? "" : " ") + entry_name(i, j);
      else
        differ += (differ.empty() ? "" : "; ") + entry_name(i, j) + " printed " + printed(i, j).str(names) +
                  ", derived " + truth(i, j).str(names);
    }
  const bool corrected_ok = all_zero(Mat4<P>(corrected_R<P>(C, lx, ly, lz) - truth));
  const bool c3_reading = all_zero(Mat4<P>(printed_c3 - truth));
  const bool holds = all_zero(Mat4<P>(printed - truth));

  // Exact counterexample: unit sphere, light (3/5, 4/5, 2); x0 = (3/5, 4/5, 0) lies on A and on the polar plane.
  const Mat4<Q> A = sphere_quadric<Q>(Vec3<Q>::Zero(), Q(1));
  const Vec4<Q> Lq(Q(3, 5), Q(4, 5), Q(2), Q(1)), x0(Q(3, 5), Q(4, 5), Q(0), Q(1));
  const PaperFrame<Q> fq = paper_frame<Q>(Lq);
  const Mat4<Q> Cq = paper_C<Q>(A, fq);
  const Mat4<Q> Rp = printed_R<Q>(Cq, Lq(0), Lq(1), Lq(2), Cq(3, 3));
  const Mat4<Q> Rc = corrected_R<Q>(Cq, Lq(0), Lq(1), Lq(2));
  const Q on_A = x0.dot(A * x0), on_polar = x0.dot(A * Lq), printed_val = x0.dot(Rp * x0), corrected_val = x0.dot(Rc * x0);

  e.verdict = holds ? "holds" : "fails";
  e.evidence = "symbolic, in the entries of C and l_x, l_y, l_z, against the derived l_z (T M)^T (S e4^T + e4 S^T) (T M): "
               "entries " + agree + " agree (with z read as l_z); " + differ +
               ". Reading d as c3 instead: (3,4) would agree, (4,4) still " + (c3_reading ? "agrees" : "does not") +
               ", so no reading of the doubtful symbols makes (6) hold. Counterexample: A = unit sphere, "
               "light (3/5, 4/5, 2); x0 = (3/5, 4/5, 0) has x0^T A x0 = " + on_A.str() + " and (A L).x0 = " +
               on_polar.str() + " (a shadow-boundary point), but x0^T R x0 = " + printed_val.str() +
               " with the printed R (C = " + mat_text(Cq) + "), and " + corrected_val.str() +
               " with the corrected R. Note: projective maps send planes to planes; R is the plane pair "
               "{A L = 0} ∪ {z = l_z}, not a proper quadric (the text's 'affine transformation makes a plane a "
               "quadric' holds only in this sense).";
  e.corrected = std::string("R = [[0 0 -b2 b2 l_z] [0 0 -b3 b3 l_z] [-b2 -b3 2(c3/l_z - a3) w-c3] "
                            "[b2 l_z b3 l_z w-c3 2 l_z (a3 l_z - w)]], w = b2 l_x + b3 l_y + a3 l_z - c3; "
                            "equivalently R = pi h^T + h pi^T with pi = A L (polar plane) and h = (0, 0, 1, -l_z) "
                            "(symbolic check of the corrected matrix against the derived one: ") +
                (corrected_ok ? "holds" : "FAILS") + ")";
  return e;
}

AuditEntry eq7() {
  return {"(7)", "the mirror is the plane a x + b y + c z + 1 = 0",
          "(7) writes the constant term as 1 while (9) uses d and a unit normal (a, b, c): read as a x + b y + c z + d = 0 "
          "with a^2 + b^2 + c^2 = 1 (the form (9) needs); (7) as printed cannot describe planes through the origin",
          "definition",
          "notation; qverify accepts any plane a x + b y + c z + d = 0 with a non-zero, not necessarily unit, normal", "", ""};
}

AuditEntry eq8() {
  return {"(8)", "a point x seen in the mirror appears at y = M x", "column vectors: the last row of (9) is 0 0 0 1",
          "definition", "defines the mirror matrix M as the reflection in the mirror plane", "", ""};
}

AuditEntry eq9() {
  AuditEntry e{"(9)",
               "M = [[1-2a^2 -2ab -2ac -ad] [-2ab 1-2b^2 -2bc -bd] [-2ac -2bc 1-2c^2 -cd] [0 0 0 1]] is the reflection "
               "in the mirror plane",
               "plane a x + b y + c z + d = 0 with unit normal (a, b, c) (see (7))", "", "", "", ""};
  const P a = P::var(MA), b = P::var(MB), c = P::var(MC), d = P::var(MD);
  const Mat4<P> Mp = printed_M<P>(a, b, c, d), Mr = unit_reflection<P>(a, b, c, d);
  const Vec4<P> x(P::var(X), P::var(Y), P::var(Z), P(1));
  const P side = a * P::var(X) + b * P::var(Y) + c * P::var(Z) + d;  // n.x + d
  // Reflection law: M x = x - 2 (n.x + d) n (a reflection when |n| = 1).
  const Vec4<P> n4(a, b, c, P(0));
  const bool refl_law = all_zero(Vec4<P>(Mr * x - x + P(2) * side * n4));
  const Vec4<P> dcol(a * d, b * d, c * d, P(0));
  Mat4<P> diff = Mp - Mr;
  const bool only_last_col = all_zero(Mat4<P>(diff - [&] {
    Mat4<P> m = Mat4<P>::Zero();
    m.col(3) = dcol;
    return m;
  }()));
  // Counterexample: the plane z - 1 = 0; the point (0, 0, 1) lies on it.
  const Mat4<Q> Mq = printed_M<Q>(Q(0), Q(0), Q(1), Q(-1));
  const Vec4<Q> on(Q(0), Q(0), Q(1), Q(1)), origin(Q(0), Q(0), Q(0), Q(1));
  const Vec4<Q> img = Mq * on, oimg = Mq * origin;
  e.verdict = "fails";
  e.evidence = std::string("symbolic: printed M - reflection = last column (a d, b d, c d, 0) ") +
               (only_last_col ? "holds" : "FAILS") +
               ": the printed translation is half the right one, so the printed M is the reflection in the plane "
               "n.x + d/2 = 0, not in the mirror. Counterexample: mirror z - 1 = 0 (a, b, c, d) = (0, 0, 1, -1): the "
               "mirror point (0, 0, 1) is sent to (" +
               img(0).str() + ", " + img(1).str() + ", " + img(2).str() + ") instead of staying put; the origin to (" +
               oimg(0).str() + ", " + oimg(1).str() + ", " + oimg(2).str() + ") instead of (0, 0, 2).";
  e.corrected = std::string("last column -2ad, -2bd, -2cd: M = [[E - 2 n n^T, -2 d n] [0 0 0 1]] for a unit normal n; "
                            "for any non-zero n, M = [[E - 2 n n^T/(n.n), -2 d n/(n.n)] [0 0 0 1]] (no square root). "
                            "Symbolic check: the corrected M x = x - 2 (n.x + d) n ") +
                (refl_law ? "holds" : "FAILS");
  return e;
}

AuditEntry eq10() {
  return {"(10)", "the mirror image of A is the quadric x^T B x = 0", "", "definition",
          "defines B; (11) gives its matrix", "", ""};
}

AuditEntry eq11() {
  AuditEntry e{"(11)", "B = (M^-1)^T A M^-1 = M^T A M, because M M = E (M = M^-1)",
               "M as in (9), unit normal; E the identity", "", "", "", ""};
  const P a = P::var(MA), b = P::var(MB), c = P::var(MC), d = P::var(MD);
  const Vec3<P> n(a, b, c);
  const P nn1 = a * a + b * b + c * c - P(1);
  auto expected_defect = [&](const P& t) {  // M^2 - E for M = [[E - 2nn^T, -t n], [0, 1]]
    Mat4<P> m = Mat4<P>::Zero();
    m.topLeftCorner<3, 3>() = P(4) * nn1 * (n * n.transpose());
    m.topRightCorner<3, 1>() = P(2) * t * nn1 * n;
    return m;
  };
  const Mat4<P> Mr = unit_reflection<P>(a, b, c, d), Mp = printed_M<P>(a, b, c, d);
  const bool corrected = all_zero(Mat4<P>(Mr * Mr - Mat4<P>::Identity() - expected_defect(P(2) * d)));
  const bool printed = all_zero(Mat4<P>(Mp * Mp - Mat4<P>::Identity() - expected_defect(d)));
  e.verdict = corrected && printed ? "holds" : "fails";
  e.evidence = std::string("symbolic: for M = [[E - 2 n n^T, -2 d n] [0 1]], M M - E = 4 (a^2 + b^2 + c^2 - 1) "
                           "[[n n^T, d n] [0 0]] ") +
               (corrected ? "holds" : "FAILS") + ", and for the printed (9) M M - E = (a^2 + b^2 + c^2 - 1) [[4 n n^T, 2 d n] [0 0]] " +
               (printed ? "holds" : "FAILS") +
               ": M = M^-1 exactly when the normal is a unit vector, as (9) assumes (even for the printed (9), which "
               "is a reflection in another plane). B = (M^-1)^T A M^-1 is right by definition: (M x)^T B (M x) = x^T A x. "
               "For a non-unit normal M M != E (e.g. n = (0, 0, 2)): use the non-unit form of the corrected (9).";
  return e;
}

}  // namespace

std::vector<AuditEntry> audit_paper() {
  return {eq1(), eq2(), eq3(), eq4(), eq5(), eq6(), eq7(), eq8(), eq9(), eq10(), eq11()};
}

}  // namespace qverify
