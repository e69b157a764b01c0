#include <qverify/verify/item_candidate.hpp>

#include <qverify/eval/number.hpp>
#include <qverify/exact/rounding.hpp>

#include <cmath>
#include <sstream>

namespace qverify {

namespace {

using Q = Rational;

/// The exact matrix or vector correctly rounded to double, entry by entry.
/// An entry beyond the range of a double fails the call: no double function
/// can be given this scene (the reason names the entry).
template <int R, int C>
Eigen::Matrix<double, R, C> rounded(const Eigen::Matrix<Q, R, C>& m, const std::string& item, const std::string& name) {
  Eigen::Matrix<double, R, C> out;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) {
      RoundingReport rep;
      out(i, j) = round_rational<double>(m(i, j), rep);
      if (rep.overflow) {
        std::ostringstream s;
        s << item << ": input " << name << "[" << i << "]";
        if (C > 1) s << "[" << j << "]";
        s << " is beyond the range of a double: the function cannot be given this scene";
        throw CandidateFailure(s.str());
      }
    }
  return out;
}

/// "" when every entry is finite, else the first non-finite entry, e.g. "P[1][2] = nan".
template <int R, int C> std::string first_non_finite(const Eigen::Matrix<double, R, C>& m, const std::string& name) {
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j)
      if (!std::isfinite(m(i, j))) {
        std::ostringstream s;
        s << name << "[" << i << "]";
        if (C > 1) s << "[" << j << "]";
        s << " = " << m(i, j);
        return s.str();
      }
  return "";
}

/// Checks a returned part: throws CandidateFailure when it has a non-finite entry.
template <int R, int C> void require_finite(const Eigen::Matrix<double, R, C>& m, const std::string& item, const std::string& name) {
  const std::string bad = first_non_finite(m, name);
  if (!bad.empty()) throw CandidateFailure(item + ": the function returned a non-finite entry: " + bad);
}

/// Calls the user's function; a std::exception it throws fails the call with its message, after the item.
template <class F> auto call_user(const F& f, const std::string& item) -> decltype(f()) {
  try {
    return f();
  } catch (const CandidateFailure& e) {
    throw CandidateFailure(item + ": " + e.what(), e.partial);
  } catch (const std::exception& e) {
    throw CandidateFailure(item + ": " + e.what());
  }
  // Anything else passes through unchanged and stops the sweep (call_candidate lets it pass too):
  // the Python module stops on KeyboardInterrupt this way.
}

}  // namespace

ResultSet item_results(const Scene& sc, const std::string& name, const ShadowItemFunction& shadow_fn,
                       const ReflectionItemFunction& reflection_fn) {
  // The exact inputs: each number of the scene exactly, the shapes made matrices exactly.
  const TypedScene<Q> ex = typed_scene<Q>(sc);
  ResultSet rs;
  rs.precision = *parse_precision("double");
  rs.method = Method::direct;
  rs.source = name;
  // The quadrics as the functions get them (correctly rounded; zero where a double cannot hold one:
  // an item using such a quadric fails below).
  for (const Mat4<Q>& A : ex.A) {
    Mat4<double> d;
    bool ok = true;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        RoundingReport rep;
        d(i, j) = round_rational<double>(A(i, j), rep);
        ok = ok && !rep.overflow;
      }
    rs.A.push_back(ok ? exact_matrix(d) : Mat4<Q>(Mat4<Q>::Zero()));
  }
  bool partial = false;  // a part left out (written as zero)
  for (const Pair& p : sc.shadows) {
    const std::string item = "shadow (" + sc.quadrics[p.quadric].id + ", " + sc.lights[p.other].id + ")";
    if (!shadow_fn) throw CandidateFailure(item + ": no shadow function was given");
    const Mat4<double> A = rounded(ex.A[p.quadric], item, "A");
    const Vec4<double> L = rounded(ex.L[p.other], item, "L");
    const ShadowCandidate<double> got = call_user([&] { return shadow_fn(A, L); }, item);
    if (!got.P) throw CandidateFailure(item + ": the function returned no P (the shadow cone is required)");
    require_finite(*got.P, item, "P");
    if (got.polar_plane) require_finite(*got.polar_plane, item, "polar_plane");
    if (got.R) require_finite(*got.R, item, "R");
    if (got.origin) require_finite(*got.origin, item, "origin");
    if (got.A) require_finite(*got.A, item, "A");
    ShadowMatrices m;
    m.present = true;
    m.status = got.status;
    m.P = exact_matrix(*got.P);
    partial = partial || !got.polar_plane || !got.R;
    m.polar = got.polar_plane ? exact_matrix(*got.polar_plane) : Vec4<Q>(Vec4<Q>::Zero());
    m.R = got.R ? exact_matrix(*got.R) : Mat4<Q>(Mat4<Q>::Zero());
    m.polar_given = got.polar_plane.has_value(), m.R_given = got.R.has_value();
    if (got.origin) m.origin = exact_matrix(*got.origin);
    if (got.A) m.A = exact_matrix(*got.A);
    else if (!got.origin) m.A = exact_matrix(A);
    rs.shadows.push_back(std::move(m));
  }
  for (const Pair& p : sc.reflections) {
    const std::string item = "reflection (" + sc.quadrics[p.quadric].id + ", " + sc.mirrors[p.other].id + ")";
    if (!reflection_fn) throw CandidateFailure(item + ": no reflection function was given");
    const Mat4<double> A = rounded(ex.A[p.quadric], item, "A");
    const Vec4<double> plane = rounded(ex.planes[p.other], item, "plane");
    const ReflectionCandidate<double> got = call_user([&] { return reflection_fn(A, plane); }, item);
    if (!got.B) throw CandidateFailure(item + ": the function returned no B (the mirror image is required)");
    require_finite(*got.B, item, "B");
    if (got.M) require_finite(*got.M, item, "M");
    if (got.origin) require_finite(*got.origin, item, "origin");
    ReflectionMatrices m;
    m.present = true;
    m.status = got.status;
    m.B = exact_matrix(*got.B);
    partial = partial || !got.M;
    m.M = got.M ? exact_matrix(*got.M) : Mat4<Q>(Mat4<Q>::Zero());
    m.M_given = got.M.has_value();
    if (got.origin) m.origin = exact_matrix(*got.origin);
    rs.reflections.push_back(std::move(m));
  }
  if (partial)
    rs.notes.push_back(name + " left out parts (polar plane or R of a shadow, M of a reflection): written as zero, "
                              "they add nothing to stress's geometric error and are not checked");
  return rs;
}

Candidate item_candidate(std::string name, ShadowItemFunction shadow_fn, ReflectionItemFunction reflection_fn) {
  if (const std::string problem = candidate_name_problem(name); !problem.empty())
    throw InputError("", "name", problem);
  Candidate c;
  c.name = name;
  c.description = std::string("functions (") + (shadow_fn ? "shadow" : "") + (shadow_fn && reflection_fn ? ", " : "") +
                  (reflection_fn ? "reflection" : "") + ")";
  c.call = [name, shadow_fn = std::move(shadow_fn), reflection_fn = std::move(reflection_fn)](const CandidateInput& in) {
    CandidateOutput out;
    out.results = item_results(in.scene, name, shadow_fn, reflection_fn);
    return out;
  };
  return c;
}

}  // namespace qverify
