#pragma once
/// \file check.hpp
/// Checking a user's matrices directly, no scene file: the verifier of
/// `qverify verify` as a library call, for other projects' test suites.
///
///   auto rep = qverify::check_shadow(A, L, qverify::ShadowCandidate<double>{P, polar, R});
///   if (!rep.passed) std::cerr << rep.summary();
///
/// The inputs A and L (or the mirror plane) are taken *exactly*: a float or a
/// double is the dyadic rational it holds, a rational is itself, an interval
/// is its midpoint. Exact points are sampled on the exact geometry (terminator
/// points A ∩ {(A L) . x = 0} for a shadow, points of A reflected exactly for
/// a reflection, in Q(sqrt d)) and each candidate quadric is measured at them
/// exactly (accuracy.hpp). The verdict is that of `verify`:
///  - a floating candidate passes when the geometric error of every quadric it
///    gives (largest first-order distance of the points from it, divided by
///    the object size) is at most the accuracy target, its signs agree with
///    references computed here from A, L and the plane (not by the core under
///    test), and it is the object it claims to be (P a cone from L through the
///    terminator, R the plane pair through the polar plane and the second
///    plane of the paper's frame, M the reflection);
///  - an exact candidate (rationals) passes only when every residual is
///    exactly zero: a proof on the sampled points.
///
/// Many items at once (a test suite's whole table, a renderer's frame):
/// check_shadows / check_reflections over vectors, check_shadow_batch /
/// check_reflection_batch over the batch API's arrays; threads over items, a
/// progress callback, and each report the one its item would get alone.

#include <qverify/batch/rows.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/exact/precision.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace qverify {

/// Options of a check (the same defaults as `qverify verify`).
struct CheckOptions {
  int samples = kDefaultSamples;
  std::uint64_t seed = 1;
  double accuracy = kDefaultAccuracy;  ///< the accuracy target T, relative to the object size
  /// Information only: the shadow was computed by the paper's route (its
  /// frame's conditioning enters consistent_with_precision's kappa).
  Method method = Method::direct;
  /// Where the geometry has no real point at all (a lamp inside an ellipsoid, an imaginary
  /// quadric): false, verify's way, skips the item, neither pass nor fail (CheckReport::skipped);
  /// true judges the results as matrices against the exact ones, up to a factor (as_matrices), as
  /// where the real points lie at infinity, and M on its own. The test-framework matchers
  /// (testing/checks.hpp) set it: their verdict is pass or fail, and a right result passes
  /// (audit 42d: a right P of a lamp inside a sphere failed every matcher as "SKIPPED").
  bool judge_without_points = false;
};

/// A shadow to check, every part optional (a renderer may compute only P):
/// the cone P (eq. 2), the polar plane A L, the quadric R (eq. 6).
template <class S> struct ShadowCandidate {
  std::optional<Mat4<S>> P;
  std::optional<Vec4<S>> polar_plane;
  std::optional<Mat4<S>> R;
  /// The frame the matrices are written in: local coordinates x - origin.
  std::optional<Vec3<S>> origin;
  /// The status word the candidate reported (checked against the exact one when given).
  std::string status;
  /// The quadric as the candidate used it, in its frame (information only: on_A).
  std::optional<Mat4<S>> A;
};

/// A reflection to check: the mirror matrix M (eq. 7) and the image B = M^T A M (eq. 11).
template <class S> struct ReflectionCandidate {
  std::optional<Mat4<S>> M;
  std::optional<Mat4<S>> B;
  std::optional<Vec3<S>> origin;
  std::string status;
};

/// One quadric (or plane) of the candidate measured at one set of exact points.
struct QuadricCheck {
  std::string name;  ///< on_P, on_polar_plane, on_R, on_generators, R_on_polar_plane, on_B, on_A
  Metric metric;
  double geometric_error = 0;  ///< relative(metric, object size); +inf when a point sits where the gradient vanishes
  bool passed = true;
  bool judged = true;          ///< false: information only (on_A)
  /// The worst point (largest distance), exactly and rounded, in the candidate's frame.
  std::optional<RootPoint> worst;
  std::optional<Vec3<double>> worst_approx;
};

/// The typed report of a check: everything `verify` writes for one item.
struct CheckReport {
  std::string kind;  ///< "shadow" or "reflection"
  bool passed = false;
  bool skipped = false;               ///< nothing to sample (no real point): neither pass nor fail
  bool exact = false;                 ///< proof mode: every residual must be exactly zero
  std::vector<std::string> problems;  ///< every reason it fails (empty when it passes)
  std::string exact_status;           ///< the status word of the exact inputs
  std::string item_status;            ///< the candidate's status (or the exact one when it gave none)
  double accuracy = kDefaultAccuracy;
  double object_size = 0;
  /// The geometric error (cli.md): the largest over the judged checks of P, the polar plane and R on
  /// the terminator, or B (+inf: unbounded). The checks of the results' shapes (on_generators,
  /// R_on_polar_plane, second_plane_error) are beside it and fail the check on their own.
  double geometric_error = 0;
  std::size_t points = 0;      ///< exact points sampled
  bool exhausted = false;      ///< fewer real points than asked
  std::vector<QuadricCheck> checks;
  /// Extra shadow checks: R on the paper's second plane (first-order, relative).
  std::optional<double> second_plane_error;
  /// Reflection: largest entry of M - M_ref relative to max(1, |M_ref|_max).
  std::optional<double> M_error;
  int proved_exactly = 0;  ///< exact mode: points at which every residual is exactly 0
  /// Floating candidates whose terminator is a real ellipse (shadows) or of an ellipsoid
  /// (reflections): the geometric error of the results in certified_for
  /// ("P", "polar_plane", "R" on the terminator, "B") bounded over every point of their geometry,
  /// not only the samples (certified_bound.hpp); a pass needs its upper bound within the accuracy
  /// target.
  std::optional<CertifiedBound> certified;
  std::vector<std::string> certified_for;
  /// The rounding verdict of earlier versions (64 eps kappa), information only.
  bool consistent_with_precision = true;
  double rounding_tolerance = 0, kappa = 1;
  /// The exact reference (computed here, not by the core under test), for messages:
  /// P_ref = (L^T A L) A - (A L)(A L)^T, polar = A L, B_ref = M^T A M (in the candidate's frame).
  std::optional<Mat4<Rational>> reference;
  /// Reflections with M given: the exact reflection in the candidate's frame, for messages, and
  /// whether M is off it (not equal when exact; M_error beyond the target otherwise).
  std::optional<Mat4<Rational>> mirror_reference;
  bool M_off = false;
  /// The results the check was given ("A", "P", "polar_plane", "R"; "M", "B"): where there is no
  /// finite point to sample, the document writes a measure of no point for each (verify_document).
  std::vector<std::string> given;
  std::vector<std::string> notes;
  std::optional<Vec3<Rational>> origin;  ///< the candidate's frame (local coordinates x - origin)

  /// The check named `name`, or nullptr.
  const QuadricCheck* find(const std::string& name) const;
  /// The failing check with the largest geometric error, or nullptr.
  const QuadricCheck* worst_check() const;
  /// A paragraph a person can act on: verdict, every problem, the worst point
  /// (which point, how far, relative to what, in which frame), the expected matrix rounded.
  std::string summary() const;
};

/// The same candidate in exact rationals (what every check works on).
using ExactShadowCandidate = ShadowCandidate<Rational>;
using ExactReflectionCandidate = ReflectionCandidate<Rational>;

/// The core of a check, on exact inputs. `eps`: the machine epsilon of the
/// precision the candidate was computed in (0 = exact: proof mode).
CheckReport check_shadow_exact(const Mat4<Rational>& A, const Vec4<Rational>& L, const ExactShadowCandidate& c,
                               const CheckOptions& opt, const Measure& eps);
CheckReport check_reflection_exact(const Mat4<Rational>& A, const Vec4<Rational>& plane,
                                   const ExactReflectionCandidate& c, const CheckOptions& opt, const Measure& eps);
/// The same with the quadric's natural centre given (a shape's centre, point
/// or apex: kappa of consistent_with_precision is measured in that frame);
/// the overload above takes the centre of A's quadratic part when it has one.
CheckReport check_reflection_exact(const Mat4<Rational>& A, const Vec4<Rational>& plane,
                                   const ExactReflectionCandidate& c, const CheckOptions& opt, const Measure& eps,
                                   const std::optional<Vec3<Rational>>& center);

/// The status word of exact inputs: a shadow's (the paper method adds
/// singular-frame where l_z = 0) and a reflection's.
std::string exact_shadow_word(const Mat4<Rational>& A, const Vec4<Rational>& L, Method method);
std::string exact_reflection_word(const Mat4<Rational>& A);

/// Machine epsilon of a precision (0 for exact), without touching global state.
Measure machine_epsilon(const Precision& p);
/// Throws InputError(where, "NAME[i][j]", problem) for a non-symmetric matrix
/// (named at the entry below the diagonal, i > j), a zero light or plane
/// normal. Nothing is computed from rejected inputs. The zero matrix is a
/// degenerate quadric, not an error (as in a scene).
void validate_quadric(const Mat4<Rational>& A, const std::string& where, const std::string& name);
void validate_light(const Vec4<Rational>& L, const std::string& where, const std::string& name);
void validate_plane(const Vec4<Rational>& plane, const std::string& where, const std::string& name);

namespace detail {
template <class S, int R, int C>
Eigen::Matrix<Rational, R, C> exact_checked(const Eigen::Matrix<S, R, C>& m, const std::string& where,
                                            const std::string& name);
}  // namespace detail

/// Checks a shadow computed in any scalar type S (float, double, long double,
/// float128, mpfr, interval, Rational). A, L are the inputs as the caller
/// holds them (taken exactly); S = Rational is proof mode.
template <class S>
CheckReport check_shadow(const Mat4<S>& A, const Vec4<S>& L, const ShadowCandidate<S>& c, const CheckOptions& opt = {});
/// Checks a reflection in the mirror plane a x + b y + c z + d = 0.
template <class S>
CheckReport check_reflection(const Mat4<S>& A, const Vec4<S>& plane, const ReflectionCandidate<S>& c,
                             const CheckOptions& opt = {});

// ------------------------------------------------------------------ batches

/// Options of a batch of checks.
struct BatchCheckOptions {
  CheckOptions check;  ///< of every item
  /// Threads over the items (0: one per logical processor); the reports do not depend on it.
  int threads = 0;
  /// Called after each item is checked with (items done, items in all), from one thread at a time.
  std::function<void(std::size_t, std::size_t)> progress = nullptr;
};

/// n items at once: report k is what check_shadow(A[k], L[k], candidates[k], opt.check)
/// returns (the same sample points: each item is checked as if alone), computed on
/// threads. Every item's inputs are validated before anything is computed: an
/// InputError names the item, e.g. "check_shadows: [7].P[0][1]: not a finite number".
template <class S>
std::vector<CheckReport> check_shadows(const std::vector<Mat4<S>>& A, const std::vector<Vec4<S>>& L,
                                       const std::vector<ShadowCandidate<S>>& candidates, const BatchCheckOptions& opt = {});
/// The same for reflections: report k is check_reflection(A[k], planes[k], candidates[k], opt.check).
template <class S>
std::vector<CheckReport> check_reflections(const std::vector<Mat4<S>>& A, const std::vector<Vec4<S>>& planes,
                                           const std::vector<ReflectionCandidate<S>>& candidates,
                                           const BatchCheckOptions& opt = {});

/// Checks the arrays of the batch API (batch/batch.hpp: one row per item, a symmetric
/// matrix as its 10 entries A00 A01 A02 A03 A11 A12 A13 A22 A23 A33): what
/// shadow_batch returns for A and L, or another program's results in that layout.
/// An array with no rows is a result not given (not checked); any other must have
/// one row per item (InputError naming it). No items at all (A with no rows, a frame
/// without objects) is no error: no reports. `status`: the status words the program
/// reported, one per item ("" where it gave none), each checked against the exact word
/// as check_shadow checks ShadowCandidate::status; empty: none given. An InputError
/// names this function, the item [k] and the entry of its matrix ([k].A[i][j]).
/// The matrices are in world coordinates (there is no origin here; check_shadows takes
/// one per item).
std::vector<CheckReport> check_shadow_batch(const SymBatch<double>& A, const Vec4Batch<double>& L,
                                            const SymBatch<double>& P, const Vec4Batch<double>& polar_plane,
                                            const SymBatch<double>& R, const BatchCheckOptions& opt = {},
                                            const std::vector<std::string>& status = {});
/// The same for reflection_batch's results: M as its three rows (n x 12), B (n x 10).
std::vector<CheckReport> check_reflection_batch(const SymBatch<double>& A, const Vec4Batch<double>& planes,
                                                const AffineBatch<double>& M, const SymBatch<double>& B,
                                                const BatchCheckOptions& opt = {},
                                                const std::vector<std::string>& status = {});

}  // namespace qverify
