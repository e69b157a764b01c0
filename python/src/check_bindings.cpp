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

CheckOptions options(long samples, long long seed, double accuracy, const std::string& method) {
  CheckOptions opt;
  opt.samples = samples_arg(samples);
  opt.seed = seed_arg(seed);
  opt.accuracy = accuracy_arg(accuracy);
  opt.method = method_arg(method);
  return opt;
}

std::string status_arg(const py::object& status) {
  if (status.is_none()) return "";
  if (!py::isinstance<py::str>(status)) bad_argument("status", "expected a status word (str) or None");
  return status.cast<std::string>();
}

CheckReport check_shadow_py(py::handle A_in, py::handle L_in, const py::object& P_in, const py::object& polar_in,
                            const py::object& R_in, const py::object& origin_in, const py::object& status_in,
                            long samples, long long seed, double accuracy, const std::string& method,
                            const py::object& exact) {
  Kinds inputs, cand;
  const Mat4<Rational> A = to_matrix(A_in, "A", inputs);
  const Vec4<Rational> L = to_vector<4>(L_in, "L", inputs);
  ExactShadowCandidate c;
  c.P = optional_in(P_in, [&](const py::object& o) { return to_matrix(o, "P", cand); });
  c.polar_plane = optional_in(polar_in, [&](const py::object& o) { return to_vector<4>(o, "polar_plane", cand); });
  c.R = optional_in(R_in, [&](const py::object& o) { return to_matrix(o, "R", cand); });
  Kinds origin_kinds;  // the frame's origin does not decide the mode
  c.origin = optional_in(origin_in, [&](const py::object& o) { return to_vector<3>(o, "origin", origin_kinds); });
  inputs.add(origin_kinds);
  c.status = status_arg(status_in);
  const CheckOptions opt = options(samples, seed, accuracy, method);
  validate_quadric(A, "", "A");
  validate_light(L, "", "L");
  if (!c.P && !c.polar_plane && !c.R) bad_argument("P", "nothing to check: give P, polar_plane or R");
  const Mode mode = mode_of(inputs, cand, exact);
  const Measure eps = mode == Mode::mixed ? candidate_epsilon(cand) : Measure(0);

  py::gil_scoped_release nogil;
  switch (mode) {
    case Mode::proof: return check_shadow<Rational>(A, L, c, opt);
    case Mode::doubles: {
      ShadowCandidate<double> d;
      d.P = cast_to<double>(c.P);
      d.polar_plane = cast_to<double>(c.polar_plane);
      d.R = cast_to<double>(c.R);
      d.origin = cast_to<double>(c.origin);
      d.status = c.status;
      return check_shadow<double>(cast_to<double>(A), cast_to<double>(L), d, opt);
    }
    case Mode::mixed: break;
  }
  return check_shadow_exact(A, L, c, opt, eps);
}

CheckReport check_reflection_py(py::handle A_in, py::handle plane_in, const py::object& M_in, const py::object& B_in,
                                const py::object& origin_in, const py::object& status_in, long samples,
                                long long seed, double accuracy, const py::object& exact) {
  Kinds inputs, cand;
  const Mat4<Rational> A = to_matrix(A_in, "A", inputs);
  const Vec4<Rational> plane = to_vector<4>(plane_in, "plane", inputs);
  ExactReflectionCandidate c;
  c.M = optional_in(M_in, [&](const py::object& o) { return to_matrix(o, "M", cand); });
  c.B = optional_in(B_in, [&](const py::object& o) { return to_matrix(o, "B", cand); });
  Kinds origin_kinds;
  c.origin = optional_in(origin_in, [&](const py::object& o) { return to_vector<3>(o, "origin", origin_kinds); });
  inputs.add(origin_kinds);
  c.status = status_arg(status_in);
  const CheckOptions opt = options(samples, seed, accuracy, "direct");
  validate_quadric(A, "", "A");
  validate_plane(plane, "", "plane");
  if (!c.M && !c.B) bad_argument("B", "nothing to check: give M or B");
  const Mode mode = mode_of(inputs, cand, exact);
  const Measure eps = mode == Mode::mixed ? candidate_epsilon(cand) : Measure(0);

  py::gil_scoped_release nogil;
  switch (mode) {
    case Mode::proof: return check_reflection<Rational>(A, plane, c, opt);
    case Mode::doubles: {
      ReflectionCandidate<double> d;
      d.M = cast_to<double>(c.M);
      d.B = cast_to<double>(c.B);
      d.origin = cast_to<double>(c.origin);
      d.status = c.status;
      return check_reflection<double>(cast_to<double>(A), cast_to<double>(plane), d, opt);
    }
    case Mode::mixed: break;
  }
  return check_reflection_exact(A, plane, c, opt, eps);
}

// ------------------------------------------------------------------ batches

/// One argument of check_shadows / check_reflections: an array with a leading
/// item axis (n, 4, 4) / (n, 4), or a single item (4, 4) / (4,) given once for
/// every item. Entries are read exactly, as in check_shadow.
struct BatchArg {
  std::string name;
  py::object array = py::none();  ///< numpy.asarray of the argument; None when not given
  bool per_item = false;
  long items = 0;    ///< the leading axis (per_item only)
  int item_ndim = 2; ///< 2: a 4x4 matrix, 1: a vector

  BatchArg(const std::string& n, const py::object& value, int ndim) : name(n), item_ndim(ndim) {
    if (value.is_none()) return;
    array = numpy().attr("asarray")(value);
    const long nd = array.attr("ndim").cast<long>();
    if (nd == item_ndim + 1) {
      per_item = true;
      items = array.attr("shape").cast<py::tuple>()[0].cast<long>();
    } else if (nd != item_ndim) {
      bad_argument(name, std::string("expected an array of shape ") + (item_ndim == 2 ? "(n, 4, 4) or (4, 4)" : "(n, 4) or (4,)") +
                             " (one entry per item, or one for all), found shape " + shape_text(array));
    }
  }
  bool given() const { return !array.is_none(); }
  /// Item k's entry, as the exact argument named "NAME[k]" (or "NAME" when given once).
  py::object item(long k, std::string& path) const {
    path = per_item ? name + "[" + std::to_string(k) + "]" : name;
    return per_item ? py::object(array[py::int_(k)]) : array;
  }
  Mat4<Rational> matrix(long k, Kinds& kinds) const {
    std::string path;
    const py::object v = item(k, path);
    return to_matrix(v, path, kinds);
  }
  Vec4<Rational> vector(long k, Kinds& kinds) const {
    std::string path;
    const py::object v = item(k, path);
    return to_vector<4>(v, path, kinds);
  }
  Vec3<Rational> vector3(long k, Kinds& kinds) const {
    std::string path;
    const py::object v = item(k, path);
    return to_vector<3>(v, path, kinds);
  }
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

BatchCheckOptions batch_options(const CheckOptions& check, int threads, const py::object& progress) {
  if (threads < 0) bad_argument("threads", "expected 0 (one per logical processor) or a positive count");
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    bad_argument("progress", "expected a callable progress(done, total), found " + type_name(progress));
  BatchCheckOptions opt;
  opt.check = check;
  opt.threads = threads;
  if (!progress.is_none())
    opt.progress = [progress](std::size_t done, std::size_t total) {
      py::gil_scoped_acquire gil;  // the checks run with the GIL released
      progress(done, total);
    };
  return opt;
}

/// Runs check(k) for every item on opt.threads threads, the GIL released.
template <class Check> std::vector<CheckReport> run_batch(std::size_t n, const BatchCheckOptions& opt, Check check) {
  std::vector<CheckReport> out(n);
  py::gil_scoped_release nogil;
  for_each_item(n, opt.threads, opt.progress, [&](std::size_t k) { out[k] = check(k); });
  return out;
}

std::vector<CheckReport> check_shadows_py(const py::object& A_in, const py::object& L_in, const py::object& P_in,
                                          const py::object& polar_in, const py::object& R_in,
                                          const py::object& origin_in, long samples, long long seed, double accuracy,
                                          const std::string& method, const py::object& exact, int threads,
                                          const py::object& progress) {
  const CheckOptions opt = options(samples, seed, accuracy, method);
  const BatchCheckOptions bopt = batch_options(opt, threads, progress);
  const BatchArg A("A", A_in, 2), L("L", L_in, 1), P("P", P_in, 2), polar("polar_plane", polar_in, 1), R("R", R_in, 2),
      origin("origin", origin_in, 1);
  if (!A.given()) bad_argument("A", "the quadrics are needed");
  if (!L.given()) bad_argument("L", "the lights are needed");
  if (!P.given() && !polar.given() && !R.given()) bad_argument("P", "nothing to check: give P, polar_plane or R");
  const long n = batch_items({&A, &L, &P, &polar, &R, &origin});
  // Every item read and validated before anything is computed.
  Kinds inputs, cand;
  std::vector<Mat4<Rational>> As;
  std::vector<Vec4<Rational>> Ls;
  std::vector<ExactShadowCandidate> cs(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k) {
    const auto u = static_cast<std::size_t>(k);
    As.push_back(A.matrix(k, inputs));
    Ls.push_back(L.vector(k, inputs));
    validate_quadric(As[u], "", A.per_item ? "A[" + std::to_string(k) + "]" : "A");
    validate_light(Ls[u], "", L.per_item ? "L[" + std::to_string(k) + "]" : "L");
    if (P.given()) cs[u].P = P.matrix(k, cand);
    if (polar.given()) cs[u].polar_plane = polar.vector(k, cand);
    if (R.given()) cs[u].R = R.matrix(k, cand);
    Kinds origin_kinds;  // the frame's origin does not decide the mode
    if (origin.given()) cs[u].origin = origin.vector3(k, origin_kinds);
  }
  const Mode mode = mode_of(inputs, cand, exact);
  const Measure eps = mode == Mode::proof ? Measure(0) : candidate_epsilon(cand);
  return run_batch(static_cast<std::size_t>(n), bopt, [&](std::size_t k) {
    return check_shadow_exact(As[k], Ls[k], cs[k], opt, eps);  // item 0: the sample points it gets alone
  });
}

std::vector<CheckReport> check_reflections_py(const py::object& A_in, const py::object& plane_in, const py::object& M_in,
                                              const py::object& B_in, const py::object& origin_in, long samples,
                                              long long seed, double accuracy, const py::object& exact, int threads,
                                              const py::object& progress) {
  const CheckOptions opt = options(samples, seed, accuracy, "direct");
  const BatchCheckOptions bopt = batch_options(opt, threads, progress);
  const BatchArg A("A", A_in, 2), plane("plane", plane_in, 1), M("M", M_in, 2), B("B", B_in, 2), origin("origin", origin_in, 1);
  if (!A.given()) bad_argument("A", "the quadrics are needed");
  if (!plane.given()) bad_argument("plane", "the mirror planes are needed");
  if (!M.given() && !B.given()) bad_argument("B", "nothing to check: give M or B");
  const long n = batch_items({&A, &plane, &M, &B, &origin});
  Kinds inputs, cand;
  std::vector<Mat4<Rational>> As;
  std::vector<Vec4<Rational>> planes;
  std::vector<ExactReflectionCandidate> cs(static_cast<std::size_t>(n));
  for (long k = 0; k < n; ++k) {
    const auto u = static_cast<std::size_t>(k);
    As.push_back(A.matrix(k, inputs));
    planes.push_back(plane.vector(k, inputs));
    validate_quadric(As[u], "", A.per_item ? "A[" + std::to_string(k) + "]" : "A");
    validate_plane(planes[u], "", plane.per_item ? "plane[" + std::to_string(k) + "]" : "plane");
    if (M.given()) cs[u].M = M.matrix(k, cand);
    if (B.given()) cs[u].B = B.matrix(k, cand);
    Kinds origin_kinds;
    if (origin.given()) cs[u].origin = origin.vector3(k, origin_kinds);
  }
  const Mode mode = mode_of(inputs, cand, exact);
  const Measure eps = mode == Mode::proof ? Measure(0) : candidate_epsilon(cand);
  return run_batch(static_cast<std::size_t>(n), bopt, [&](std::size_t k) {
    return check_reflection_exact(As[k], planes[k], cs[k], opt, eps);
  });
}

std::string report_repr(const CheckReport& r) {
  std::string verdict = r.skipped ? "skipped" : r.passed ? "passed" : "FAILED";
  char buf[160];
  std::snprintf(buf, sizeof buf, ", geometric_error=%.3g, object_size=%.6g, points=%zu", r.geometric_error, r.object_size,
                r.points);
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
        point lies off a result at a vanishing gradient).
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
    (floating candidates of an ellipsoid: the bound over every point, or None).
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
      .def_readonly("geometric_error", &CheckReport::geometric_error, "Largest judged geometric error (inf: unbounded).")
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
      }, "Floating candidates of an ellipsoid: the geometric error of P and the polar plane (over the whole "
         "terminator) or of B (over all of A reflected) bounded at every point, not only the samples: a dict "
         "(results, geometric_error_bound, geometric_error_attained, boxes), or None. A pass needs the bound "
         "within the accuracy target.")
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
        py::arg("samples") = kDefaultSamples, py::arg("seed") = 1, py::arg("accuracy") = kDefaultAccuracy,
        py::arg("method") = "direct", py::arg("exact") = py::none(), py::arg("threads") = 0,
        py::arg("progress") = py::none(),
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
    samples, seed, accuracy, method, exact: as in check_shadow (the mode
        is decided once for the whole batch).
    threads: 0 (default) for one per logical processor.
    progress: None, or a callable progress(done, total) called after each
        item (one call at a time, done = 1, 2, ..., n).

Every entry is read exactly (float64 and float32 arrays, object arrays of
Fraction, nested lists, decimal strings) and every item is validated before
anything is computed.

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
        py::arg("B") = py::none(), py::kw_only(), py::arg("origin") = py::none(), py::arg("samples") = kDefaultSamples,
        py::arg("seed") = 1, py::arg("accuracy") = kDefaultAccuracy, py::arg("exact") = py::none(),
        py::arg("threads") = 0, py::arg("progress") = py::none(),
        R"(Checks many mirror images at once (as check_shadows does shadows).

Report k is what check_reflection(A[k], plane[k], M=M[k], B=B[k], ...)
returns for item k alone.

Args:
    A: the quadrics, (n, 4, 4) or one (4, 4) for all.
    plane: the mirror planes (a, b, c, d), (n, 4) or one (4,) for all.
    M, B: the candidates' reflection matrices and mirror images, (n, 4, 4)
        or one for all; give either.
    origin, samples, seed, accuracy, exact, threads, progress: as in
        check_shadows.

Returns:
    list[CheckReport], one per item, in order.

Raises:
    qverify.InputError: a bad argument; `path` names the item ("B[3][2][1]").
)");

  m.def("check_reflection", &check_reflection_py, py::arg("A"), py::arg("plane"), py::arg("M") = py::none(),
        py::arg("B") = py::none(), py::kw_only(), py::arg("origin") = py::none(), py::arg("status") = py::none(),
        py::arg("samples") = kDefaultSamples, py::arg("seed") = 1, py::arg("accuracy") = kDefaultAccuracy,
        py::arg("exact") = py::none(),
        R"(Checks a mirror image computed by any program against the exact geometry.

Exact points of A are sampled, reflected exactly in the plane, and the given
B is measured at them exactly; M is compared with the exact reflection.

Args:
    A: the quadric's symmetric 4x4 matrix.
    plane: (a, b, c, d) of the mirror plane a x + b y + c z + d = 0.
    M, B: the candidate's reflection matrix and mirror image; give either.
    origin, status, samples, seed, accuracy, exact: as in check_shadow.

Returns:
    CheckReport.

Raises:
    qverify.InputError: a bad argument (zero mirror normal: path "plane").
)");
}

}  // namespace qverify::py_glue
