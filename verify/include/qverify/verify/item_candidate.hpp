#pragma once
/// \file item_candidate.hpp
/// A candidate made of plain functions: the user's shadow and mirror-image
/// code audited by `run_stress` / `run_audit` without writing files or a
/// `qverify-eval/1` document (issue 19; the Python module's `qverify.stress`
/// is built on it).
///
///   auto c = qverify::item_candidate("mine",
///       [](const Mat4<double>& A, const Vec4<double>& L) {
///         ShadowCandidate<double> r;
///         r.P = my_shadow_cone(A, L);   // P is required; polar_plane and R are optional
///         return r;
///       },
///       nullptr);                        // no reflection function: reflection items fail
///   StressOptions opt;  opt.candidate = c;  opt.families = {"far-from-origin"};
///
/// Contract of one call (one scene, CandidateFunction):
///  - for every requested item of the scene, in scene order, the item
///    function is called once with the scene's *exact* inputs, each entry
///    correctly rounded to double: A (the quadric's matrix, built exactly
///    from the shape and then rounded entry by entry, so it is the double
///    matrix nearest to the exact quadric, which a program building A in
///    double need not reach), L = (p, 1) for a point light or (-d, 0) for a
///    parallel light travelling along d, and the mirror plane (a, b, c, d)
///    of a x + b y + c z + d = 0. These are the inputs of qverify::shadow /
///    qverify::reflection (core/shadow.hpp, core/mirror.hpp);
///  - what the function returns is taken exactly (a double is the dyadic
///    rational it holds) into the typed ResultSet, precision "double",
///    method "direct" (information only), in the world frame, or in local
///    coordinates x - origin when the function sets `origin`;
///  - a part the function leaves out (the polar plane or R of a shadow, M of
///    a reflection) is written as zero. The zero form vanishes at every point,
///    so it adds nothing to the geometric error that `run_stress` measures:
///    a stress point's item error is then over the parts returned. (The
///    verifier of `run_audit` / `verify_results` checks every part and judges
///    a zero part wrong: return every part there.) P of a shadow and B of a
///    reflection are required;
///  - the call fails (CandidateFailure, the point's "candidate-failed" with
///    the reason) when an item function throws (the reason is its what(),
///    after the item, e.g. "shadow (obj, light): division by zero"), returns
///    no P (B), returns a non-finite entry, is missing for a requested kind
///    (an empty std::function), or when an input is out of the range of a
///    double (then no double function can be given the scene).
/// An exception that is not a std::exception passes through the adapter and
/// call_candidate unchanged and stops the sweep (the Python module's
/// KeyboardInterrupt). Several items of one scene are one call: the first
/// failure fails it.
/// The functions are called from the thread that runs the sweep (one call at
/// a time in run_stress), never concurrently by this adapter.

#include <qverify/verify/candidate_run.hpp>
#include <qverify/verify/check.hpp>

#include <functional>
#include <string>

namespace qverify {

/// A user's shadow: given A (4x4) and the light L, returns P (required) and
/// optionally the polar plane A L and R (and `origin`, `status`, `A` as in
/// check_shadow; `status` is shown as the candidate's claimed status).
using ShadowItemFunction = std::function<ShadowCandidate<double>(const Mat4<double>& A, const Vec4<double>& L)>;

/// A user's mirror image: given A (4x4) and the mirror plane (a, b, c, d),
/// returns B = M^T A M up to a positive factor (required) and optionally M.
using ReflectionItemFunction =
    std::function<ReflectionCandidate<double>(const Mat4<double>& A, const Vec4<double>& plane)>;

/// The candidate named `name` (candidate_name_problem: InputError with path
/// "name" when it cannot label one) that answers every requested item of a
/// scene with `shadow_fn` / `reflection_fn` (see the file comment). Either
/// function may be empty when the scenes it is given never request that kind
/// (a stress sweep of shadow families only); an item of a kind without a
/// function is a failed call saying so.
Candidate item_candidate(std::string name, ShadowItemFunction shadow_fn, ReflectionItemFunction reflection_fn);

/// The typed results of one scene computed by the two functions: what each
/// call of item_candidate returns (CandidateOutput::results). Throws
/// CandidateFailure as described above.
ResultSet item_results(const Scene& sc, const std::string& name, const ShadowItemFunction& shadow_fn,
                       const ReflectionItemFunction& reflection_fn);

}  // namespace qverify
