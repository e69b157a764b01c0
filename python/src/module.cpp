// The Python module qverify._qverify (re-exported by the package qverify):
// shadow volumes and mirror images of one quadric, whole scenes (eval,
// verify) and, in check_bindings.cpp, the checks of a user's own matrices.
#include "convert.hpp"
#include "options.hpp"

#include <qverify/verify/adaptive.hpp>
#include <qverify/verify/check.hpp>
#include <qverify/eval/eval.hpp>
#include <qverify/verify/verifier.hpp>
#include <qverify/report/eval_document.hpp>
#include <qverify/report/verify_document.hpp>

#include <pybind11/stl.h>

#include <cmath>

namespace py = pybind11;
using namespace qverify;
using namespace qverify::py_glue;
using json = nlohmann::ordered_json;

namespace qverify::py_glue {

std::string text_arg(const py::object& x, const char* name, const char* expected) {
  if (!py::isinstance<py::str>(x)) bad_argument(name, std::string("expected ") + expected + ", found " + type_name(x));
  return x.cast<std::string>();
}

double number_arg(const py::object& x, const char* name) {
  if (x.is_none() || py::isinstance<py::bool_>(x) || py::isinstance<py::str>(x) || py::isinstance<py::bytes>(x) ||
      py::isinstance<py::type>(x) || !py::hasattr(x, "__float__"))
    bad_argument(name, "expected a number, found " + type_name(x));
  try {
    return py::float_(x).cast<double>();
  } catch (const py::error_already_set&) {  // float() refused it: 10**400, a Fraction beyond double
    bad_argument(name, "expected a number a double holds, found " + short_repr(x));
  }
}

py::int_ integer_arg(const py::object& x, const char* name) {
  if (x.is_none() || py::isinstance<py::bool_>(x) || py::isinstance<py::type>(x) || !py::hasattr(x, "__index__"))
    bad_argument(name, "expected an integer, found " + type_name(x));
  try {
    return py::int_(x.attr("__index__")());
  } catch (const py::error_already_set&) {
    bad_argument(name, "expected an integer, found " + type_name(x));
  }
}

Precision precision_arg(const py::object& arg) {
  const std::string text = text_arg(arg, "precision", "a precision name (str)");
  const auto p = parse_precision(text);
  if (!p)
    bad_argument("precision", "unknown precision \"" + text +
                                  "\" (expected float, double, long-double, float128, mpfr:BITS with 16 <= BITS <= "
                                  "65536, interval or exact)");
  return *p;
}

Method method_arg(const py::object& arg) {
  const std::string text = text_arg(arg, "method", "\"direct\" or \"paper\"");
  if (text == "direct") return Method::direct;
  if (text == "paper") return Method::paper;
  bad_argument("method", "unknown method \"" + text + "\" (expected direct or paper)");
}

std::optional<Frame> frame_arg(const py::object& frame) {
  if (frame.is_none()) return std::nullopt;
  if (!py::isinstance<py::str>(frame)) bad_argument("frame", "expected \"local\", \"world\" or None");
  const std::string t = frame.cast<std::string>();
  if (t == "local") return Frame::local;
  if (t == "world") return Frame::world;
  bad_argument("frame", "unknown frame \"" + t + "\" (expected local, world or None for the default)");
}

double accuracy_arg(const py::object& arg) {
  const double accuracy = number_arg(arg, "accuracy");
  if (!(std::isfinite(accuracy) && accuracy > 0))
    bad_argument("accuracy", "the accuracy target must be a positive finite number, found " + short_repr(arg) +
                                 (accuracy == 0 ? " (0 as a double)" : ""));
  return accuracy;
}

int samples_arg(const py::object& arg) {
  const py::int_ samples = integer_arg(arg, "samples");
  if (samples < py::int_(1) || samples > py::int_(kMaxSamples))
    bad_argument("samples", "expected 1 to " + std::to_string(kMaxSamples) + " sample points, found " + short_repr(samples));
  return samples.cast<int>();
}

std::uint64_t seed_arg(const py::object& arg) {
  const py::int_ seed = integer_arg(arg, "seed");
  if (seed < py::int_(0) || seed > py::int_(std::numeric_limits<std::uint64_t>::max()))
    bad_argument("seed", "expected a seed from 0 to 2^64 - 1, found " + short_repr(seed));
  return seed.cast<std::uint64_t>();
}

int threads_arg(const py::object& arg) {
  const py::int_ threads = integer_arg(arg, "threads");
  if (threads < py::int_(0) || threads > py::int_(1 << 16))
    bad_argument("threads", "expected 0 (one per logical processor) or a positive count up to 65536, found " +
                                short_repr(threads));
  return threads.cast<int>();
}

std::unique_lock<std::mutex> mpfr_lock(bool needed) {
  static std::mutex m;
  return needed ? std::unique_lock<std::mutex>(m) : std::unique_lock<std::mutex>();
}

void bind_checks(py::module_& m);  // check_bindings.cpp
void bind_stress(py::module_& m);  // stress_bindings.cpp

}  // namespace qverify::py_glue

namespace {

/// The result of qverify.shadow: one item of a qverify-eval/1 document, its
/// matrices converted.
struct PyShadow {
  py::object P, polar_plane, R, origin, error_bound, item;
  std::string status, precision, method, frame, reason, escalated, fallback;
  std::vector<std::string> flags, inputs_rounded;
};

struct PyReflection {
  py::object M, B, origin, error_bound, item;
  std::string status, precision, method, frame, reason, escalated;
  std::vector<std::string> flags, inputs_rounded;
};

template <int N> std::vector<Num> nums(const std::string& name, const Eigen::Matrix<Rational, N, 1>& v) {
  std::vector<Num> out;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    out.push_back(Num{v(i), name + "[" + std::to_string(i) + "]", ""});
  return out;
}

QuadricSpec quadric_spec(const Mat4<Rational>& A) {
  QuadricSpec q;
  q.id = "A";
  q.path = "A";
  q.shape = Shape::matrix;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      q.params.push_back(Num{A(i, j), "A[" + std::to_string(i) + "][" + std::to_string(j) + "]", ""});
  return q;
}

/// The eval document of a one-item scene, computed with the GIL released.
json eval_one(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame, double accuracy) {
  py::gil_scoped_release nogil;
  auto lock = mpfr_lock(prec.kind == Precision::Kind::mpfr);
  return eval_json(eval_report(sc, prec, method, frame, AccuracyOptions{accuracy}));
}

/// A result as returned: Fractions (exact), else float64 (json_to_array; `projective`: P, polar_plane, R, B).
py::object matrix_out(const json& m, bool exact, bool projective = true) {
  return exact ? json_to_fractions(m) : py::object(json_to_array(m, projective));
}

/// A float64 array with an entry that is not finite although the document's is (a wider precision's
/// M beyond double's range): flagged "non-finite", as eval flags a result that overflowed.
template <class T> void flag_overflow(T& r, const py::object& array, const json& m) {
  bool doc_finite = true;
  for (const auto& row : m)
    for (const auto& x : row) doc_finite = doc_finite && !x.is_null();
  const auto a = py::array_t<double>::ensure(array);
  bool finite = true;
  for (py::ssize_t i = 0; i < a.size(); ++i) finite = finite && std::isfinite(a.data()[i]);
  if (doc_finite && !finite)
    for (const char* flag : {"non-finite", "inaccurate"})  // (as eval flags a result that overflowed)
      if (std::find(r.flags.begin(), r.flags.end(), flag) == r.flags.end()) r.flags.emplace_back(flag);
}

py::object negated(const py::object& v, bool exact) {
  if (!exact) return v.attr("__neg__")();
  py::list out;
  for (py::handle x : v) out.append(x.is_none() ? py::none() : py::reinterpret_borrow<py::object>(x).attr("__neg__")());
  return out;
}

template <class T> void common_fields(T& r, const json& doc, const json& item) {
  r.status = item.at("status").get<std::string>();
  r.flags = item.at("flags").get<std::vector<std::string>>();
  r.error_bound = item.contains("error_bound") && item["error_bound"].is_number() ? py::object(py::float_(item["error_bound"].get<double>()))
                                                                                  : py::object(py::none());
  r.reason = item.value("reason", "");
  r.escalated = item.value("escalated", "");
  r.origin = item.contains("origin") ? py::object(json_to_array(item["origin"])) : py::object(py::none());
  r.precision = doc.at("precision").get<std::string>();
  r.method = doc.at("method").get<std::string>();
  r.frame = doc.at("frame").get<std::string>();
  r.inputs_rounded = doc.at("inputs_rounded").get<std::vector<std::string>>();
  r.item = json_to_python(item);
}

PyShadow shadow_py(py::handle A_in, py::handle L_in, const py::object& method_text, const py::object& precision_text,
                   const py::object& accuracy_in, const py::object& frame_in) {
  Kinds kinds;
  const Mat4<Rational> A = to_matrix(A_in, "A", kinds);
  const Vec4<Rational> L = to_vector<4>(L_in, "L", kinds);
  const Method method = method_arg(method_text);
  const Precision prec = precision_arg(precision_text);
  const std::optional<Frame> frame = frame_arg(frame_in);
  const double accuracy = accuracy_arg(accuracy_in);
  validate_quadric(A, "", "A");
  validate_light(L, "", "L");

  Scene sc;
  sc.name = "qverify.shadow";
  sc.quadrics.push_back(quadric_spec(A));
  LightSpec l;
  l.id = "L";
  l.path = "L";
  l.parallel = L(3) == 0;
  for (int i = 0; i < 3; ++i)  // a point light at (x/w, y/w, z/w); a parallel light L = (-d, 0): d = -(x, y, z)
    l.xyz.push_back(Num{l.parallel ? Rational(-L(i)) : Rational(L(i) / L(3)), "L[" + std::to_string(i) + "]", ""});
  sc.lights.push_back(l);
  sc.shadows.push_back(Pair{0, 0});

  const json doc = eval_one(sc, prec, method, frame ? frame : Frame::world_rounded, accuracy);
  const json& item = doc.at("shadows").at(0);
  const bool exact = prec.kind == Precision::Kind::exact;
  PyShadow r;
  common_fields(r, doc, item);
  r.P = matrix_out(item.at("P"), exact);
  r.polar_plane = matrix_out(item.at("polar_plane"), exact);
  r.R = matrix_out(item.at("R"), exact);
  // The scene's light is (x/w, y/w, z/w, 1): its polar plane is A L / w. For w < 0 turn it back
  // into A L up to a positive factor (P, quadratic in L, and R, defined up to sign, are unchanged).
  if (!l.parallel && L(3) < 0) r.polar_plane = negated(r.polar_plane, exact);
  r.fallback = item.value("fallback", "");
  return r;
}

PyReflection reflection_py(py::handle A_in, py::handle plane_in, const py::object& method_text,
                           const py::object& precision_text, const py::object& accuracy_in, const py::object& frame_in) {
  Kinds kinds;
  const Mat4<Rational> A = to_matrix(A_in, "A", kinds);
  const Vec4<Rational> plane = to_vector<4>(plane_in, "plane", kinds);
  const Method method = method_arg(method_text);
  const Precision prec = precision_arg(precision_text);
  const std::optional<Frame> frame = frame_arg(frame_in);
  const double accuracy = accuracy_arg(accuracy_in);
  validate_quadric(A, "", "A");
  validate_plane(plane, "", "plane");

  Scene sc;
  sc.name = "qverify.reflection";
  sc.quadrics.push_back(quadric_spec(A));
  MirrorSpec mir;
  mir.id = "plane";
  mir.path = "plane";
  mir.plane = nums("plane", plane);
  sc.mirrors.push_back(mir);
  sc.reflections.push_back(Pair{0, 0});

  const json doc = eval_one(sc, prec, method, frame ? frame : Frame::world_rounded, accuracy);
  const json& item = doc.at("reflections").at(0);
  const bool exact = prec.kind == Precision::Kind::exact;
  PyReflection r;
  common_fields(r, doc, item);
  r.M = matrix_out(item.at("M"), exact, false);  // M itself (last row 0 0 0 1), never scaled
  if (!exact) flag_overflow(r, r.M, item.at("M"));
  r.B = matrix_out(item.at("B"), exact);
  return r;
}

/// A file path argument as the operating system's bytes (os.fsencode: a non-UTF-8 name works too); an
/// InputError naming `name` for what is no path, or holds a NUL (the system would cut the path there).
std::string path_arg(const py::object& p, const std::string& name) {
  py::object encoded;
  try {
    encoded = py::module_::import("os").attr("fsencode")(p);
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    bad_argument(name, "expected a file path (str, bytes or os.PathLike), found " + type_name(p));
  }
  const std::string out = encoded.cast<std::string>();
  if (out.find('\0') != std::string::npos) bad_argument(name, "a file path with a NUL character");
  return out;
}

/// A scene from a file (`path`) or from JSON text (`text`, named `name` in messages).
Scene scene_arg(const py::object& path, const py::object& text, const std::string& name) {
  if (!text.is_none()) {
    const std::string t = text.cast<std::string>();
    py::gil_scoped_release nogil;
    return parse_scene(t, name);
  }
  const std::string p = path_arg(path, "scene");
  py::gil_scoped_release nogil;
  return load_scene(p);
}

py::object eval_scene_py(const py::object& path, const py::object& text, const std::string& name,
                         const py::object& precision_text, const py::object& method_text, const py::object& frame_in,
                         const py::object& accuracy_in, const py::object& tolerance_in) {
  const Precision prec = precision_arg(precision_text);
  const Method method = method_arg(method_text);
  const std::optional<Frame> frame = frame_arg(frame_in);
  const double accuracy = accuracy_arg(accuracy_in);
  std::optional<double> tolerance;
  if (!tolerance_in.is_none()) {
    const double t = number_arg(tolerance_in, "tolerance");
    if (!(t >= std::ldexp(1.0, -53) && t <= 1))
      bad_argument("tolerance", "the adaptive tolerance must lie in [2^-53, 1] (below 2^-53 a double result cannot be "
                                "certified: use precision=\"exact\")");
    if (prec.kind != Precision::Kind::f64)
      bad_argument("tolerance", "the adaptive mode produces double results: leave precision at \"double\"");
    tolerance = t;
  }
  const Scene sc = scene_arg(path, text, name);
  json doc;
  {
    py::gil_scoped_release nogil;
    auto lock = mpfr_lock(prec.kind == Precision::Kind::mpfr || tolerance.has_value());
    doc = tolerance ? eval_json(adaptive_eval_report(sc, method, *tolerance))
                    : eval_json(eval_report(sc, prec, method, frame, AccuracyOptions{accuracy}));
  }
  return json_to_python(doc);
}

py::object verify_scene_py(const py::object& path, const py::object& text, const std::string& name,
                           const py::object& cand_path, const py::object& cand_text, const std::string& cand_name,
                           const py::object& precision_text, const py::object& method_text, const py::object& frame_in,
                           const py::object& samples_in, const py::object& seed_in, const py::object& accuracy_in) {
  const Precision prec = precision_arg(precision_text);
  const Method method = method_arg(method_text);
  const std::optional<Frame> frame = frame_arg(frame_in);
  const double accuracy = accuracy_arg(accuracy_in);
  const int samples = samples_arg(samples_in);
  const std::uint64_t seed = seed_arg(seed_in);
  const Scene sc = scene_arg(path, text, name);
  std::optional<std::string> cpath, ctext;
  if (!cand_text.is_none()) ctext = cand_text.cast<std::string>();
  else if (!cand_path.is_none())
    cpath = path_arg(cand_path, "candidate");
  VerifyReport v;
  {
    py::gil_scoped_release nogil;
    auto lock = mpfr_lock(prec.kind == Precision::Kind::mpfr);
    const ResultSet rs = ctext   ? candidate_results_text(sc, *ctext, cand_name, prec)
                         : cpath ? candidate_results(sc, *cpath, prec)
                                 : computed_results(sc, prec, method, frame, AccuracyOptions{accuracy});  // eval's results
    VerifyOptions vo{samples, seed, accuracy};
    vo.prove = (ctext || cpath) && prec.kind == Precision::Kind::exact;  // as `verify --precision exact --candidate`
    v = verify_results(sc, rs, vo);
  }
  return json_to_python(verify_document(sc, v));
}

std::string repr_value(const py::object& o) { return py::repr(o).cast<std::string>(); }

}  // namespace

PYBIND11_MODULE(_qverify, m) {
  m.doc() = "qverify: shadow volumes and mirror images of quadrics, exact and verified (compiled part; use the "
            "package `qverify`).";
  py::module_::import("numpy");
  register_input_error(m);

  py::class_<PyShadow>(m, "ShadowResult", R"(The shadow volume of a quadric A lit by L (qverify.shadow).

Matrices are float64 numpy arrays (each entry the nearest double to the
computed value; an interval enclosure: to its midpoint), or nested lists of
fractions.Fraction with precision="exact", in world coordinates: computed
in a local frame where that is more accurate (an object far from the world
origin), moved back exactly and rounded once. Only with frame="local" may
`origin` be set: they are then written in local coordinates x - origin.

Attributes:
    P: the shadow cone (tangent cone of A with apex L), up to a positive
        factor the matrix (L^T A L) A - (A L)(A L)^T.
    polar_plane: A L up to a positive factor; it cuts A in the terminator.
    R: the plane pair of the polar plane and the paper's second plane h.
    status: "ok" or the first special case (degenerate-quadric,
        light-on-surface, no-real-silhouette, singular-frame): decided
        exactly from the exact inputs, whatever the precision.
    flags: every special case that applies, "inaccurate" when error_bound
        exceeds the accuracy target, and "non-finite" (with "inaccurate")
        when the result overflowed the precision (its entries are NaN).
    error_bound: an upper bound of the geometric error (distance of exact
        terminator points from the results, relative to the object size) of
        the result in its precision (a wider precision's float64 arrays
        round it once more: the full digits are in `item`):
        certified over every point for the results item["certified_for"]
        names, the others measured exactly on 64 seeded points, times 2;
        0 for precision "exact"; None with `reason` where none can be given.
    reason, origin, escalated ("float128" when recomputed in binary128),
    fallback, precision, method, frame, inputs_rounded (inputs the
    precision cannot hold, rounded once), item (the qverify-eval/1 item as
    a dict, numbers as the CLI writes them).
)")
      .def_readonly("P", &PyShadow::P, "The shadow cone P (4x4).")
      .def_readonly("polar_plane", &PyShadow::polar_plane, "The polar plane A L (4 entries a, b, c, d).")
      .def_readonly("R", &PyShadow::R, "The quadric R (4x4): polar plane and second plane h.")
      .def_readonly("status", &PyShadow::status, "Status word (exact predicate of the inputs).")
      .def_readonly("flags", &PyShadow::flags, "Every special case that applies, and 'inaccurate'.")
      .def_readonly("error_bound", &PyShadow::error_bound, "Bound of the geometric error (float), or None.")
      .def_readonly("reason", &PyShadow::reason, "Why error_bound is None (empty otherwise).")
      .def_readonly("origin", &PyShadow::origin, "None, or the origin of the local frame of the matrices.")
      .def_readonly("escalated", &PyShadow::escalated, "'float128' when recomputed in binary128, else ''.")
      .def_readonly("fallback", &PyShadow::fallback, "Method paper: why the direct formulas were used, else ''.")
      .def_readonly("precision", &PyShadow::precision, "The precision computed in.")
      .def_readonly("method", &PyShadow::method, "'direct' or 'paper'.")
      .def_readonly("frame", &PyShadow::frame, "'local' or 'world'.")
      .def_readonly("inputs_rounded", &PyShadow::inputs_rounded, "Inputs the precision cannot hold (rounded once).")
      .def_readonly("item", &PyShadow::item, "The qverify-eval/1 shadow item as a dict.")
      .def("__repr__", [](const PyShadow& s) {
        return "ShadowResult(status=" + repr_value(py::str(s.status)) + ", flags=" + repr_value(py::cast(s.flags)) +
               ", error_bound=" + repr_value(s.error_bound) + ", precision=" + repr_value(py::str(s.precision)) +
               ",\n  P=" + repr_value(s.P) + ",\n  polar_plane=" + repr_value(s.polar_plane) + ",\n  R=" +
               repr_value(s.R) + ")";
      });

  py::class_<PyReflection>(m, "ReflectionResult", R"(The mirror image of a quadric A in a plane (qverify.reflection).

Matrices as in ShadowResult (float64 numpy arrays, or lists of Fraction with
precision="exact"; in world coordinates unless frame="local" set `origin`).

Attributes:
    M: the reflection in the mirror plane (last row 0 0 0 1).
    B: the mirror image M^T A M, up to a positive factor.
    status: "ok" or "degenerate-quadric" (flags may add "non-finite").
    flags, error_bound, reason, origin, escalated, precision, method, frame,
    inputs_rounded, item: as in ShadowResult.
)")
      .def_readonly("M", &PyReflection::M, "The reflection matrix M (4x4).")
      .def_readonly("B", &PyReflection::B, "The mirror image B = M^T A M (4x4).")
      .def_readonly("status", &PyReflection::status, "Status word.")
      .def_readonly("flags", &PyReflection::flags, "Special cases, and 'inaccurate'.")
      .def_readonly("error_bound", &PyReflection::error_bound, "Bound of the geometric error (float), or None.")
      .def_readonly("reason", &PyReflection::reason, "Why error_bound is None (empty otherwise).")
      .def_readonly("origin", &PyReflection::origin, "None, or the origin of the local frame of the matrices.")
      .def_readonly("escalated", &PyReflection::escalated, "'float128' when recomputed in binary128, else ''.")
      .def_readonly("precision", &PyReflection::precision, "The precision computed in.")
      .def_readonly("method", &PyReflection::method, "'direct' or 'paper'.")
      .def_readonly("frame", &PyReflection::frame, "'local' or 'world'.")
      .def_readonly("inputs_rounded", &PyReflection::inputs_rounded, "Inputs the precision cannot hold (rounded once).")
      .def_readonly("item", &PyReflection::item, "The qverify-eval/1 reflection item as a dict.")
      .def("__repr__", [](const PyReflection& r) {
        return "ReflectionResult(status=" + repr_value(py::str(r.status)) + ", flags=" + repr_value(py::cast(r.flags)) +
               ", error_bound=" + repr_value(r.error_bound) + ", precision=" + repr_value(py::str(r.precision)) +
               ",\n  M=" + repr_value(r.M) + ",\n  B=" + repr_value(r.B) + ")";
      });

  m.def("shadow", &shadow_py, py::arg("A"), py::arg("L"), py::arg("method") = "direct",
        py::arg("precision") = "double", py::arg("accuracy") = kDefaultAccuracy, py::arg("frame") = py::none(),
        R"(Shadow volume of the quadric x^T A x = 0 lit by L (equations (2)-(6)).

Args:
    A: the quadric's symmetric 4x4 matrix: a numpy array (float64, float32,
        int or object dtype) or nested lists of int, float, Fraction or
        decimal / "p/q" strings. Every number is taken exactly (a float is
        the dyadic rational it holds).
    L: the light, 4 numbers: (x, y, z, w) with w != 0 is the point light
        at (x/w, y/w, z/w); (v, 0) is a parallel light travelling along -v
        (L = (-d, 0) for a direction d).
    method: "direct" (projective formulas) or "paper" (the paper's route).
    precision: "float", "double", "long-double", "float128", "mpfr:BITS",
        "interval" or "exact".
    accuracy: the accuracy target of error_bound (default 1e-9).
    frame: None (default): results in world coordinates, computed in a
        local frame where that is more accurate and moved back exactly
        (rounded once); "local": results in that local frame (`origin`);
        "world": computed in world coordinates throughout.

Returns:
    ShadowResult: P, polar_plane, R, status, flags, error_bound, ...

Raises:
    qverify.InputError: a bad argument (not 4x4, not symmetric, NaN or inf,
        light (0, 0, 0, 0), zero denominator, unknown precision or method,
        non-positive accuracy); `path` names it, e.g. "A[3][1]".

Example:
    >>> s = qverify.shadow(np.diag([1.0, 1, 1, -1]), [3.0, 4, 8, 1])
    >>> s.status, s.polar_plane
    ('ok', array([ 3.,  4.,  8., -1.]))
)");

  m.def("reflection", &reflection_py, py::arg("A"), py::arg("plane"), py::arg("method") = "direct",
        py::arg("precision") = "double", py::arg("accuracy") = kDefaultAccuracy, py::arg("frame") = py::none(),
        R"(Mirror image of the quadric x^T A x = 0 in a plane mirror (equations (7)-(11)).

Args:
    A: the quadric's symmetric 4x4 matrix (as in qverify.shadow).
    plane: (a, b, c, d) of the mirror plane a x + b y + c z + d = 0;
        (a, b, c) must be non-zero.
    method, precision, accuracy, frame: as in qverify.shadow.

Returns:
    ReflectionResult: M, B, status, flags, error_bound, ...

Raises:
    qverify.InputError: a bad argument; `path` names it ("plane" for a zero
        normal).
)");

  m.def("_decimal", [](const py::int_& x) { return int_text(x); },
        "Decimal text of an int of any size (str() refuses more than 4300 digits); for scenes given as dicts.");
  m.def("_eval_scene", &eval_scene_py, py::arg("path"), py::arg("text"), py::arg("name"), py::arg("precision"),
        py::arg("method"), py::arg("frame"), py::arg("accuracy"), py::arg("tolerance"),
        "eval of a scene file (path) or JSON text; see qverify.eval_scene.");
  m.def("_verify_scene", &verify_scene_py, py::arg("path"), py::arg("text"), py::arg("name"), py::arg("candidate_path"),
        py::arg("candidate_text"), py::arg("candidate_name"), py::arg("precision"), py::arg("method"),
        py::arg("frame"), py::arg("samples"), py::arg("seed"), py::arg("accuracy"),
        "verify of a scene file (path) or JSON text; see qverify.verify_scene.");

  m.attr("DEFAULT_ACCURACY") = kDefaultAccuracy;
  m.attr("DEFAULT_SAMPLES") = kDefaultSamples;
  m.attr("PRECISIONS") = py::make_tuple("float", "double", "long-double", "float128", "mpfr:BITS", "interval", "exact");
  bind_checks(m);
  bind_stress(m);
  for (const char* cls : {"ShadowResult", "ReflectionResult", "CheckReport"}) m.attr(cls).attr("__module__") = "qverify";
}
