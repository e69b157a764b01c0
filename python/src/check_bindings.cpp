// qverify.check_shadow / qverify.check_reflection: the typed check API of
// verify/check.hpp on a user's own matrices, and its report.
#include "convert.hpp"
#include "options.hpp"

#include <qverify/batch/items.hpp>
#include <qverify/verify/check.hpp>

#include <pybind11/stl.h>

#include <limits>

namespace py = pybind11;
using namespace qverify;
using namespace qverify::py_glue;

namespace {

double measure_double(const Measure& m) { return m.convert_to<double>(); }

py::dict check_dict(const QuadricCheck& c) {
  py::dict d;
  d["name"] = c.name;
  d["geometric_error"] = c.geometric_error;
  d["passed"] = c.passed;
  d["judged"] = c.judged;
  d["max_distance"] = c.metric.singular ? std::numeric_limits<double>::infinity() : measure_double(c.metric.distance);
  d["max_residual"] = measure_double(c.metric.residual);
  d["all_zero"] = c.metric.all_zero;
  d["singular"] = c.metric.singular;
  if (c.worst) {
    py::dict w;
    w["p"] = fractions(c.worst->p());
    w["q"] = fractions(c.worst->q());
    w["delta"] = fraction(c.worst->delta());
    d["worst"] = w;  // x = p + sqrt(delta) q, homogeneous
  } else {
    d["worst"] = py::none();
  }
  d["worst_approx"] = c.worst_approx ? py::object(py::make_tuple((*c.worst_approx)(0), (*c.worst_approx)(1), (*c.worst_approx)(2)))
                                     : py::object(py::none());
  return d;
}

template <class T> py::object optional_out(const std::optional<T>& v) {
  return v ? py::cast(*v) : py::object(py::none());
}

/// Converts an optional Python argument.
template <class F> auto optional_in(const py::object& o, F&& convert) -> std::optional<decltype(convert(o))> {
  if (o.is_none()) return std::nullopt;
  return convert(o);
}

template <class S, int R, int C> Eigen::Matrix<S, R, C> cast_to(const Eigen::Matrix<Rational, R, C>& m) {
  if constexpr (std::is_same_v<S, Rational>) return m;
  else {
    Eigen::Matrix<S, R, C> out;
    for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = nearest_double(m(i));  // exact: every entry came from a double
    return out;
  }
}
template <class S, int R, int C>
std::optional<Eigen::Matrix<S, R, C>> cast_to(const std::optional<Eigen::Matrix<Rational, R, C>>& m) {
  if (!m) return std::nullopt;
  return cast_to<S>(*m);
}

/// How a check is run: proof mode (exact candidate), doubles throughout, or
/// exact inputs with a floating candidate (judged by the accuracy target).
enum class Mode { proof, doubles, mixed };

Mode mode_of(const Kinds& inputs, const Kinds& candidate, const py::object& exact) {
  if (!exact.is_none() && !py::isinstance<py::bool_>(exact) &&
      !py::isinstance(exact, py::module_::import("numpy").attr("bool_")))
    bad_argument("exact", "expected True, False or None, found " + type_name(exact));
  const bool proof = exact.is_none() ? candidate.any_exact : exact.cast<bool>();
  if (proof) return Mode::proof;
  return inputs.all_floating() && candidate.all_floating() && !candidate.any_f32 ? Mode::doubles : Mode::mixed;
}

/// Machine epsilon of a floating candidate (information only: consistent_with_precision).
Measure candidate_epsilon(const Kinds& candidate) {
  Precision p;
  p.kind = candidate.any_f32 && !candidate.any_f64 ? Precision::Kind::f32 : Precision::Kind::f64;
  return machine_epsilon(p);
}

CheckOptions options(const py::object& samples, const py::object& seed, const py::object& accuracy,
                     const py::object& method, const py::object& judge_without_points) {
  CheckOptions opt;
  if (!py::isinstance<py::bool_>(judge_without_points))
    bad_argument("judge_without_points", "expected True or False, found " + type_name(judge_without_points));
  opt.judge_without_points = judge_without_points.cast<bool>();
  opt.samples = samples_arg(samples);
  opt.seed = seed_arg(seed);
  opt.accuracy = accuracy_arg(accuracy);
  opt.method = method_arg(method);
  return opt;
}

/// A reported status word; "" is not one (the library's "none reported" is None here: an empty word
/// passed as unreported, audit 37b F8).
std::string status_word(const py::object& w, const std::string& path) {
  if (!py::isinstance<py::str>(w)) bad_argument(path, "expected a status word (str) or None, found " + type_name(w));
  std::string s = w.cast<std::string>();
  if (s.empty()) bad_argument(path, "expected a status word, found \"\" (None: no status reported)");
  return s;
}

std::string status_arg(const py::object& status) {
  if (status.is_none()) return "";
  return status_word(status, "status");
}

/// One check as read from Python (with the GIL): the exact inputs, the candidate, and the mode
/// the kinds of their numbers decide. Run without the GIL by run_check, the same for a single
/// check and for each item of a batch.
struct ShadowCall {
  Mat4<Rational> A;
  Vec4<Rational> L;
  ExactShadowCandidate c;
  Mode mode = Mode::proof;
  Kinds cand;
};
struct ReflectionCall {
  Mat4<Rational> A;
  Vec4<Rational> plane;
  ExactReflectionCandidate c;
  Mode mode = Mode::proof;
  Kinds cand;
};

/// Reads and validates one shadow check; `A`, `L`, ... are the arguments (None: not given)
/// and `name(arg)` their names in errors ("P", or "P[7]" for item 7 of a batch).
template <class Name>
ShadowCall read_shadow(py::handle A_in, py::handle L_in, const py::object& P_in, const py::object& polar_in,
                       const py::object& R_in, const py::object& origin_in, const std::string& status,
                       const py::object& exact, Name&& name) {
  ShadowCall call;
  Kinds inputs;
  call.A = to_matrix(A_in, name("A"), inputs);
  call.L = to_vector<4>(L_in, name("L"), inputs);
  call.c.P = optional_in(P_in, [&](const py::object& o) { return to_matrix(o, name("P"), call.cand); });
  call.c.polar_plane = optional_in(polar_in, [&](const py::object& o) { return to_vector<4>(o, name("polar_plane"), call.cand); });
  call.c.R = optional_in(R_in, [&](const py::object& o) { return to_matrix(o, name("R"), call.cand); });
  Kinds origin_kinds;  // the frame's origin does not decide the mode
  call.c.origin = optional_in(origin_in, [&](const py::object& o) { return to_vector<3>(o, name("origin"), origin_kinds); });
  inputs.add(origin_kinds);
  call.c.status = status;
  validate_quadric(call.A, "", name("A"));
  validate_light(call.L, "", name("L"));
  if (!call.c.P && !call.c.polar_plane && !call.c.R) bad_argument("P", "nothing to check: give P, polar_plane or R");
  call.mode = mode_of(inputs, call.cand, exact);
  return call;
}

template <class Name>
ReflectionCall read_reflection(py::handle A_in, py::handle plane_in, const py::object& M_in, const py::object& B_in,
                               const py::object& origin_in, const std::string& status, const py::object& exact,
                               Name&& name) {
  ReflectionCall call;
  Kinds inputs;
  call.A = to_matrix(A_in, name("A"), inputs);
  call.plane = to_vector<4>(plane_in, name("plane"), inputs);
  call.c.M = optional_in(M_in, [&](const py::object& o) { return to_matrix(o, name("M"), call.cand); });
  call.c.B = optional_in(B_in, [&](const py::object& o) { return to_matrix(o, name("B"), call.cand); });
  Kinds origin_kinds;
  call.c.origin = optional_in(origin_in, [&](const py::object& o) { return to_vector<3>(o, name("origin"), origin_kinds); });
  inputs.add(origin_kinds);
  call.c.status = status;
  validate_quadric(call.A, "", name("A"));
  validate_plane(call.plane, "", name("plane"));
  if (!call.c.M && !call.c.B) bad_argument("B", "nothing to check: give M or B");
  call.mode = mode_of(inputs, call.cand, exact);
  return call;
}

/// Runs a check in its mode (no Python object is touched: called without the GIL).
CheckReport run_check(const ShadowCall& call, const CheckOptions& opt) {
  switch (call.mode) {
    case Mode::proof: return check_shadow<Rational>(call.A, call.L, call.c, opt);
    case Mode::doubles: {
      ShadowCandidate<double> d;
      d.P = cast_to<double>(call.c.P);
      d.polar_plane = cast_to<double>(call.c.polar_plane);
      d.R = cast_to<double>(call.c.R);
      d.origin = cast_to<double>(call.c.origin);
      d.status = call.c.status;
      return check_shadow<double>(cast_to<double>(call.A), cast_to<double>(call.L), d, opt);
    }
    case Mode::mixed: break;
  }
  return check_shadow_exact(call.A, call.L, call.c, opt, candidate_epsilon(call.cand));
}

CheckReport run_check(const ReflectionCall& call, const CheckOptions& opt) {
  switch (call.mode) {
    case Mode::proof: return check_reflection<Rational>(call.A, call.plane, call.c, opt);
    case Mode::doubles: {
      ReflectionCandidate<double> d;
      d.M = cast_to<double>(call.c.M);
      d.B = cast_to<double>(call.c.B);
      d.origin = cast_to<double>(call.c.origin);
      d.status = call.c.status;
      return check_reflection<double>(cast_to<double>(call.A), cast_to<double>(call.plane), d, opt);
    }
    case Mode::mixed: break;
  }
  return check_reflection_exact(call.A, call.plane, call.c, opt, candidate_epsilon(call.cand));
}

/// An argument's name as it is (a single check).
const auto plain_name = [](const char* arg) { return std::string(arg); };

CheckReport check_shadow_py(py::handle A_in, py::handle L_in, const py::object& P_in, const py::object& polar_in,
                            const py::object& R_in, const py::object& origin_in, const py::object& status_in,
                            const py::object& samples, const py::object& seed, const py::object& accuracy,
                            const py::object& method, const py::object& exact, const py::object& judge) {
  const CheckOptions opt = options(samples, seed, accuracy, method, judge);
  const ShadowCall call = read_shadow(A_in, L_in, P_in, polar_in, R_in, origin_in, status_arg(status_in), exact, plain_name);
  py::gil_scoped_release nogil;
  return run_check(call, opt);
}

CheckReport check_reflection_py(py::handle A_in, py::handle plane_in, const py::object& M_in, const py::object& B_in,
                                const py::object& origin_in, const py::object& status_in, const py::object& samples,
                                const py::object& seed, const py::object& accuracy, const py::object& exact,
                                const py::object& judge) {
  const CheckOptions opt = options(samples, seed, accuracy, py::str("direct"), judge);
  const ReflectionCall call = read_reflection(A_in, plane_in, M_in, B_in, origin_in, status_arg(status_in), exact, plain_name);
  py::gil_scoped_release nogil;
  return run_check(call, opt);
}

// ------------------------------------------------------------------ batches

/// One argument of check_shadows / check_reflections: n items with a leading item axis
/// ((n, 4, 4) matrices, (n, 4) vectors), or one item (4, 4) / (4,) given once for every item.
/// A numpy array is told by its ndim; a list by its nesting (its first entry's first entry a
/// sequence: a list of matrices). Each item is then read as the single check reads its argument
/// (nested lists entry by entry, never coerced to one dtype first).
struct BatchArg {
  std::string name;
  py::object value = py::none();  ///< the argument; None when not given
  bool per_item = false;
  long items = 0;                 ///< the leading axis (per_item only)

  BatchArg(const std::string& n, const py::object& v, int item_ndim) : name(n), value(buffers_as_arrays(v, n)) {
    if (value.is_none()) return;
    const std::string expected = item_ndim == 2 ? "(n, 4, 4) or (4, 4)" : "(n, 4) or (4,)";
    if (py::isinstance(value, numpy().attr("ndarray"))) {
      const long nd = value.attr("ndim").cast<long>();
      if (nd != item_ndim && nd != item_ndim + 1)
        bad_argument(name, "expected an array of shape " + expected + " (one entry per item, or one for all), found shape " +
                               shape_text(value));
      per_item = nd == item_ndim + 1;
      if (per_item) items = value.attr("shape").cast<py::tuple>()[0].cast<long>();
      return;
    }
    if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value))
      bad_argument(name, "expected " + expected + " numbers (a numpy array or nested lists), found " + type_name(value));
    const py::sequence seq = value.cast<py::sequence>();
    auto is_seq = [](const py::handle& h) { return py::isinstance<py::sequence>(h) && !py::isinstance<py::str>(h); };
    if (seq.size() == 0) {  // an empty batch
      per_item = true;
      return;
    }
    const py::object first = seq[0];
    per_item = item_ndim == 2 ? is_seq(first) && py::len(first) > 0 && is_seq(first.cast<py::sequence>()[0]) : is_seq(first);
    if (per_item) items = static_cast<long>(seq.size());
  }
  bool given() const { return !value.is_none(); }
  /// Item k's entry (None when not given).
  py::object item(long k) const {
    if (!given() || !per_item) return value;
    return value[py::int_(k)];
  }
  /// Item k's name in errors: "P[7]", or "P" when given once for all.
  std::string item_name(long k) const { return per_item ? name + "[" + std::to_string(k) + "]" : name; }
};

/// The number of items: the common leading axis of the arguments that have one
/// (1 when none has); a mismatch names the argument.
long batch_items(const std::vector<const BatchArg*>& args) {
  const BatchArg* first = nullptr;
  for (const BatchArg* a : args) {
    if (!a->given() || !a->per_item) continue;
    if (!first) first = a;
    else if (a->items != first->items)
      bad_argument(a->name, std::to_string(a->items) + " items where " + first->name + " gives " +
                                std::to_string(first->items) + ": every argument needs one entry per item (or one for all)");
  }
  return first ? first->items : 1;
}

/// The names of item k's arguments in errors, for read_shadow / read_reflection: "P[7]", or
/// "P" for an argument given once for all.
auto item_names(const std::vector<const BatchArg*>& args, long k) {
  return [&args, k](const char* arg) {
    for (const BatchArg* a : args)
      if (a->name == arg) return a->item_name(k);
    return std::string(arg);
  };
}

/// The batch's status words: None (none reported), one word for every item, or a sequence of n
/// words or None (an item that reported none); a count other than n names "status", an entry not a
/// word "status[k]".
std::vector<std::string> batch_status(const py::object& status, long n) {
  std::vector<std::string> out(static_cast<std::size_t>(n));
  if (status.is_none()) return out;
  if (py::isinstance<py::str>(status)) {
    std::fill(out.begin(), out.end(), status_word(status, "status"));
    return out;
  }
  if (!py::isinstance<py::sequence>(status) && !py::isinstance(status, numpy().attr("ndarray")))
    bad_argument("status", "expected a status word (str), a sequence of one per item (str or None), or None, found " +
                               type_name(status));
  const py::sequence seq = status.cast<py::sequence>();
  if (static_cast<long>(seq.size()) != n)
    bad_argument("status", std::to_string(seq.size()) + " words for " + std::to_string(n) +
                               " items: give one per item (None where none was reported), or one word for all");
  for (long k = 0; k < n; ++k) {
    const py::object w = seq[static_cast<std::size_t>(k)];
    if (w.is_none()) continue;
    out[static_cast<std::size_t>(k)] = status_word(w, "status[" + std::to_string(k) + "]");
  }
  return out;
}

BatchCheckOptions batch_options(const CheckOptions& check, const py::object& threads, const py::object& progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    bad_argument("progress", "expected a callable progress(done, total), found " + type_name(progress));
  BatchCheckOptions opt;
  opt.check = check;
  opt.threads = threads_arg(threads);
  if (!progress.is_none())
    opt.progress = [progress](std::size_t done, std::size_t total) {
      py::gil_scoped_acquire gil;  // the checks run with the GIL released
      progress(done, total);
    };
  return opt;
}

/// Every call run_check'ed on opt.threads threads, the GIL released.
template <class Call> std::vector<CheckReport> run_batch(const std::vector<Call>& calls, const BatchCheckOptions& opt) {
  std::vector<CheckReport> out(calls.size());
  py::gil_scoped_release nogil;
  for_each_item(calls.size(), opt.threads, opt.progress, [&](std::size_t k) { out[k] = run_check(calls[k], opt.check); });
  return out;
}

std::vector<CheckReport> check_shadows_py(const py::object& A_in, const py::object& L_in, const py::object& P_in,
                                          const py::object& polar_in, const py::object& R_in,
                                          const py::object& origin_in, const py::object& status_in,
                                          const py::object& samples, const py::object& seed,
                                          const py::object& accuracy, const py::object& method, const py::object& exact,
                                          const py::object& threads,
                                          const py::object& progress, const py::object& judge) {
  const CheckOptions opt = options(samples, seed, accuracy, method, judge);
  const BatchCheckOptions bopt = batch_options(opt, threads, progress);
  const BatchArg A("A", A_in, 2), L("L", L_in, 1), P("P", P_in, 2), polar("polar_plane", polar_in, 1), R("R", R_in, 2),
      origin("origin", origin_in, 1);
  if (!A.given()) bad_argument("A", "the quadrics are needed");
  if (!L.given()) bad_argument("L", "the lights are needed");
  if (!P.given() && !polar.given() && !R.given()) bad_argument("P", "nothing to check: give P, polar_plane or R");
  const std::vector<const BatchArg*> args{&A, &L, &P, &polar, &R, &origin};
  const long n = batch_items(args);
  const std::vector<std::string> status = batch_status(status_in, n);
  // Every item read and validated before anything is computed, each as check_shadow reads it.
  std::vector<ShadowCall> calls;
  calls.reserve(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k)
    calls.push_back(read_shadow(A.item(k), L.item(k), P.item(k), polar.item(k), R.item(k), origin.item(k),
                                status[static_cast<std::size_t>(k)], exact, item_names(args, k)));
  return run_batch(calls, bopt);
}

std::vector<CheckReport> check_reflections_py(const py::object& A_in, const py::object& plane_in, const py::object& M_in,
                                              const py::object& B_in, const py::object& origin_in,
                                              const py::object& status_in, const py::object& samples,
                                              const py::object& seed, const py::object& accuracy, const py::object& exact,
                                              const py::object& threads, const py::object& progress,
                                              const py::object& judge) {
  const CheckOptions opt = options(samples, seed, accuracy, py::str("direct"), judge);
  const BatchCheckOptions bopt = batch_options(opt, threads, progress);
  const BatchArg A("A", A_in, 2), plane("plane", plane_in, 1), M("M", M_in, 2), B("B", B_in, 2), origin("origin", origin_in, 1);
  if (!A.given()) bad_argument("A", "the quadrics are needed");
  if (!plane.given()) bad_argument("plane", "the mirror planes are needed");
  if (!M.given() && !B.given()) bad_argument("B", "nothing to check: give M or B");
  const std::vector<const BatchArg*> args{&A, &plane, &M, &B, &origin};
  const long n = batch_items(args);
  const std::vector<std::string> status = batch_status(status_in, n);
  std::vector<ReflectionCall> calls;
  calls.reserve(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k)
    calls.push_back(read_reflection(A.item(k), plane.item(k), M.item(k), B.item(k), origin.item(k),
                                    status[static_cast<std::size_t>(k)], exact, item_names(args, k)));
  return run_batch(calls, bopt);
}

std::string report_repr(const CheckReport& r) {
  std::string verdict = r.skipped ? "skipped" : r.passed ? "passed" : "FAILED";
  char buf[160] = "";
  if (!r.skipped)
    std::snprintf(buf, sizeof buf, ", geometric_error=%.3g, object_size=%.6g, points=%zu", r.geometric_error,
                  r.object_size, r.points);
  std::string s = "<qverify.CheckReport " + r.kind + " " + verdict + (r.exact ? " (proof mode)" : "") + buf;
  if (!r.problems.empty()) {
    s += ", problems=[";
    for (std::size_t i = 0; i < r.problems.size(); ++i) s += (i ? "; " : "") + r.problems[i];
    s += "]";
  }
  return s + ">";
}

}  // namespace

namespace qverify::py_glue {

void bind_checks(py::module_& m) {
  py::class_<CheckReport>(m, "CheckReport", R"(The verdict of qverify.check_shadow / qverify.check_reflection.

The same semantics as `qverify verify`: exact points are sampled on the
exact geometry (terminator points for a shadow, reflected points of A for a
reflection) and every given matrix is measured at them exactly.

bool(report) is report.passed, and repr(report) names the problems, so
`assert qverify.check_shadow(...)` fails with a useful message; `summary`
says what a person needs to fix it.

Attributes:
    passed: every judged geometric error is within the accuracy target (in
        proof mode: every residual exactly zero), the signs agree with the
        references, P is the cone from L, M the reflection, the status the
        exact one.
    geometric_error: the largest over the judged quadrics (distance of the
        exact points from the result over the object size; inf where a
        point lies off a result at a vanishing gradient; None when skipped).
    object_size: the largest distance of the points from A's centre.
    points: exact sample points used.
    checks: one dict per checked quadric: name (on_P, on_polar_plane, on_R,
        on_generators, R_on_polar_plane, on_B, ...), geometric_error, passed,
        judged, max_distance, max_residual, all_zero, singular, worst (the
        worst point exactly: p + sqrt(delta) q, as Fractions) and
        worst_approx (its Cartesian coordinates, floats).
    problems: every reason it fails (empty when it passes).
    summary: a paragraph: verdict, problems, worst point, expected matrix.
    kind, skipped, exact (proof mode), exact_status, item_status, accuracy,
    exhausted, second_plane_error, M_error, proved_exactly,
    consistent_with_precision, rounding_tolerance, kappa, reference (the
    exact expected matrix as Fractions, or None), notes, origin, certified
    (floating candidates whose terminator is a real ellipse, or reflections of an ellipsoid: the
    bound over every point, or None).
)")
      .def_readonly("kind", &CheckReport::kind, "'shadow' or 'reflection'.")
      .def_readonly("passed", &CheckReport::passed, "True when the check passes.")
      .def_readonly("skipped", &CheckReport::skipped, "Nothing to sample (no real point): neither pass nor fail.")
      .def_readonly("exact", &CheckReport::exact, "Proof mode: every residual must be exactly zero.")
      .def_readonly("problems", &CheckReport::problems, "Every reason the check fails.")
      .def_readonly("exact_status", &CheckReport::exact_status, "The status word of the exact inputs.")
      .def_readonly("item_status", &CheckReport::item_status, "The candidate's status (or the exact one).")
      .def_readonly("accuracy", &CheckReport::accuracy, "The accuracy target.")
      .def_readonly("object_size", &CheckReport::object_size, "Largest distance of the points from A's centre.")
      .def_property_readonly("geometric_error", [](const CheckReport& r) -> py::object {
        // (a skipped check judged nothing: no error, as verify's JSON writes none, rather than 0.0)
        return r.skipped ? py::none() : py::object(py::float_(r.geometric_error));
      }, "Largest judged geometric error (inf: unbounded; None when skipped: nothing was judged).")
      .def_readonly("points", &CheckReport::points, "Exact sample points used.")
      .def_readonly("exhausted", &CheckReport::exhausted, "Fewer real points than asked.")
      .def_property_readonly("checks", [](const CheckReport& r) {
        py::list out;
        for (const QuadricCheck& c : r.checks) out.append(check_dict(c));
        return out;
      }, "One dict per checked quadric (name, geometric_error, passed, max_distance, max_residual, worst, ...).")
      .def_property_readonly("second_plane_error", [](const CheckReport& r) { return optional_out(r.second_plane_error); },
                             "Shadows: R's error on points of the second plane h (or None).")
      .def_property_readonly("M_error", [](const CheckReport& r) { return optional_out(r.M_error); },
                             "Reflections: largest entry of M - M_ref relative to max(1, |M_ref|) (or None).")
      .def_readonly("proved_exactly", &CheckReport::proved_exactly, "Proof mode: points proved on every checked quadric.")
      .def_readonly("consistent_with_precision", &CheckReport::consistent_with_precision,
                    "Information only: residuals within 64 eps kappa of the candidate's precision.")
      .def_readonly("rounding_tolerance", &CheckReport::rounding_tolerance, "64 eps kappa.")
      .def_readonly("kappa", &CheckReport::kappa, "Rounding amplification of the formulas at the exact data.")
      .def_property_readonly("reference", [](const CheckReport& r) {
        return r.reference ? fractions(*r.reference) : py::object(py::none());
      }, "The exact expected matrix (P_ref or B_ref, in the candidate's frame) as Fractions, or None.")
      .def_property_readonly("certified", [](const CheckReport& r) -> py::object {
        if (!r.certified) return py::none();
        py::dict d;
        d["results"] = r.certified_for;
        d["geometric_error_bound"] = r.certified->upper;
        d["geometric_error_attained"] = r.certified->attained;
        d["boxes"] = r.certified->boxes;
        return std::move(d);
      }, "Floating candidates whose terminator is a real ellipse (shadows) or of an ellipsoid (reflections): the "
         "geometric error of the results named in 'results' bounded "
         "at every point, not only the samples: P, the polar plane and R over the whole terminator (R also over "
         "the polar plane inside it, where R's second plane does not meet the terminator), B over all of A "
         "reflected. A dict (results, geometric_error_bound, geometric_error_attained, boxes), or None. A pass "
         "needs the bound within the accuracy target.")
      .def_readonly("notes", &CheckReport::notes, "Remarks (few real points, one-point terminator, ...).")
      .def_property_readonly("origin", [](const CheckReport& r) {
        return r.origin ? py::object(doubles(*r.origin)) : py::object(py::none());
      }, "The candidate's frame origin, or None.")
      .def_property_readonly("summary", &CheckReport::summary, "A paragraph a person can act on.")
      .def("__bool__", [](const CheckReport& r) { return r.passed; })
      .def("__repr__", &report_repr)
      .def("__str__", &CheckReport::summary);

  m.def("check_shadow", &check_shadow_py, py::arg("A"), py::arg("L"), py::arg("P") = py::none(),
        py::arg("polar_plane") = py::none(), py::arg("R") = py::none(), py::kw_only(), py::arg("origin") = py::none(),
        py::arg("status") = py::none(), py::arg("samples") = kDefaultSamples, py::arg("seed") = 1,
        py::arg("accuracy") = kDefaultAccuracy, py::arg("method") = "direct", py::arg("exact") = py::none(),
        py::arg("judge_without_points") = false,
        R"(Checks a shadow volume computed by any program against the exact geometry.

A and L are taken exactly (a float is the dyadic rational it holds). Exact
points of the terminator A ∩ {(A L) . x = 0} are sampled (seeded) and the
given P, polar plane and R are measured at them exactly, P also on exact
points of its generator lines (it must be *the* cone from L), R on the
polar plane and on its second plane; signs are compared with references
computed from A and L.

Args:
    A: the quadric's symmetric 4x4 matrix (numpy array or nested lists of
        int, float, Fraction or decimal / "p/q" strings).
    L: the light (x, y, z, w): a point light for w != 0, (-d, 0) for a
        parallel light along d.
    P, polar_plane, R: the candidate's results; give any of them.
    origin: the frame they are written in (local coordinates x - origin),
        e.g. ShadowResult.origin; None for world coordinates.
    status: the status word the candidate reported (checked against the
        exact one), or None.
    samples, seed: exact points to sample and the sampler's seed.
    accuracy: the accuracy target T (relative to the object size).
    method: "direct" or "paper" (information for consistent_with_precision).
    exact: None (default) decides the mode from the candidate: proof mode
        when any of P, polar_plane, R holds exact numbers (int, Fraction,
        strings), a floating check otherwise. True forces proof mode (every
        residual exactly zero), False the floating check.
    judge_without_points: where the terminator has no real point (a lamp
        inside an ellipsoid), False (default, as `verify`) skips the check:
        rep.skipped, neither passed nor failed; True judges the results as
        matrices against the exact ones, up to a factor, for a pass or fail
        (as the C++ test matchers do).

Returns:
    CheckReport: passed, geometric_error, object_size, points, checks, ...

Raises:
    qverify.InputError: a bad argument (shape, NaN, non-symmetric A,
        light (0, 0, 0, 0), zero denominator, non-positive accuracy,
        nothing to check); `path` names it.

Example:
    >>> s = qverify.shadow(A, L)
    >>> rep = qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R)
    >>> assert rep, rep.summary
)");

  m.def("check_shadows", &check_shadows_py, py::arg("A"), py::arg("L"), py::arg("P") = py::none(),
        py::arg("polar_plane") = py::none(), py::arg("R") = py::none(), py::kw_only(), py::arg("origin") = py::none(),
        py::arg("status") = py::none(), py::arg("samples") = kDefaultSamples, py::arg("seed") = 1,
        py::arg("accuracy") = kDefaultAccuracy, py::arg("method") = "direct", py::arg("exact") = py::none(),
        py::arg("threads") = 0,
        py::arg("progress") = py::none(), py::arg("judge_without_points") = false,
        R"(Checks many shadows at once: a test suite's whole table, a renderer's frame.

Report k is what check_shadow(A[k], L[k], P=P[k], ...) returns for item k
alone (the same sample points, the same verdict); the items are checked on
`threads` threads with the GIL released.

Args:
    A: the quadrics, shape (n, 4, 4); or one (4, 4) quadric for every item.
    L: the lights, shape (n, 4); or one light (4,) for every item.
    P, polar_plane, R: the candidates' results, (n, 4, 4) / (n, 4) (or one
        for all); give any of them.
    origin: the frames, (n, 3) or (3,), or None for world coordinates.
    status: the status words the candidates reported, checked against the
        exact ones as in check_shadow: None (none reported), one str for
        every item, or a sequence of n (str, or None for an item without).
    samples, seed, accuracy, method, exact, judge_without_points: as in
        check_shadow (each item's mode, proof or floating, decided from its
        own numbers).
    threads: 0 (default) for one per logical processor.
    progress: None, or a callable progress(done, total) called after each
        item (one call at a time, done = 1, 2, ..., n).

Every entry is read exactly, each item as check_shadow reads its arguments
(float64 and float32 arrays, object arrays of Fraction, nested lists of int,
float, Fraction or strings, entry by entry), and every item is validated
before anything is computed.

Returns:
    list[CheckReport], one per item, in order.

Raises:
    qverify.InputError: a bad argument; `path` names the item, e.g.
        "P[7][0][1]" (entry (0, 1) of item 7's P) or "L" for a count that
        does not match A's.

Example:
    >>> reps = qverify.check_shadows(As, Ls, P=Ps)
    >>> failed = [k for k, r in enumerate(reps) if not r]
)");

  m.def("check_reflections", &check_reflections_py, py::arg("A"), py::arg("plane"), py::arg("M") = py::none(),
        py::arg("B") = py::none(), py::kw_only(), py::arg("origin") = py::none(), py::arg("status") = py::none(),
        py::arg("samples") = kDefaultSamples, py::arg("seed") = 1, py::arg("accuracy") = kDefaultAccuracy,
        py::arg("exact") = py::none(), py::arg("threads") = 0, py::arg("progress") = py::none(),
        py::arg("judge_without_points") = false,
        R"(Checks many mirror images at once (as check_shadows does shadows).

Report k is what check_reflection(A[k], plane[k], M=M[k], B=B[k], ...)
returns for item k alone.

Args:
    A: the quadrics, (n, 4, 4) or one (4, 4) for all.
    plane: the mirror planes (a, b, c, d), (n, 4) or one (4,) for all.
    M, B: the candidates' reflection matrices and mirror images, (n, 4, 4)
        or one for all; give either.
    origin, status, samples, seed, accuracy, exact, threads, progress,
        judge_without_points: as in check_shadows.

Returns:
    list[CheckReport], one per item, in order.

Raises:
    qverify.InputError: a bad argument; `path` names the item ("B[3][2][1]").
)");

  m.def("check_reflection", &check_reflection_py, py::arg("A"), py::arg("plane"), py::arg("M") = py::none(),
        py::arg("B") = py::none(), py::kw_only(), py::arg("origin") = py::none(), py::arg("status") = py::none(),
        py::arg("samples") = kDefaultSamples, py::arg("seed") = 1, py::arg("accuracy") = kDefaultAccuracy,
        py::arg("exact") = py::none(), py::arg("judge_without_points") = false,
        R"(Checks a mirror image computed by any program against the exact geometry.

Exact points of A are sampled, reflected exactly in the plane, and the given
B is measured at them exactly; M is compared with the exact reflection.

Args:
    A: the quadric's symmetric 4x4 matrix.
    plane: (a, b, c, d) of the mirror plane a x + b y + c z + d = 0.
    M, B: the candidate's reflection matrix and mirror image; give either.
    origin, status, samples, seed, accuracy, exact, judge_without_points: as
        in check_shadow (a quadric without real points, M alone included).

Returns:
    CheckReport.

Raises:
    qverify.InputError: a bad argument (zero mirror normal: path "plane").
)");
}

}  // namespace qverify::py_glue
