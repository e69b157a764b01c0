#include "convert.hpp"

#include <qverify/exact/number_text.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/eval/frames.hpp>  // floor_log2, exact_pow2

#include <gmp.h>

#include <cmath>
#include <limits>
#include <string>

namespace qverify::py_glue {

std::string type_name(py::handle h) { return py::str(py::type::handle_of(h).attr("__name__")).cast<std::string>(); }

py::module_& numpy() {
  static py::module_* np = new py::module_(py::module_::import("numpy"));  // intentionally leaked: lives as long as the interpreter
  return *np;
}

std::string shape_text(py::handle arr) { return py::str(arr.attr("shape")).cast<std::string>(); }

namespace {

/// Python's builtins (hex, int): integers cross in base 16, which has no size limit; str() and
/// int(text) refuse integers beyond 4300 decimal digits (sys.set_int_max_str_digits), which a
/// scene's exact numbers may have (10**5000 raised a bare ValueError).
py::object builtin(const char* name) { return py::module_::import("builtins").attr(name); }

/// z in a base, by GMP into our own buffer (its size: mpz_sizeinbase, plus sign and terminator).
std::string mpz_text(mpz_srcptr z, int base) {
  std::string out(mpz_sizeinbase(z, base) + 2, '\0');
  mpz_get_str(out.data(), base, z);
  out.resize(std::char_traits<char>::length(out.c_str()));
  return out;
}

Rational exact_text(const std::string& text, const std::string& path) {
  std::string err;
  const std::optional<Rational> v = parse_rational(text, err);
  if (!v) bad_argument(path, err);
  return *v;
}

Rational from_ratio(py::handle num, py::handle den, const std::string& path) {
  const std::string d = int_text(den);
  if (d == "0") bad_argument(path, "a fraction with zero denominator (" + int_text(num) + "/0)");
  return exact_text(int_text(num) + "/" + d, path);
}

bool is_sequence(py::handle h) {
  return !py::isinstance<py::str>(h) && !py::isinstance<py::bytes>(h) && py::isinstance<py::sequence>(h);
}

}  // namespace

/// A memoryview read as the numpy array over the same buffer (numpy reads its format exactly), so that
/// its shape is checked as an array's: indexed as a sequence, a multi-dimensional view raised
/// NotImplementedError, not InputError (audit 37b F7). Anything else as it is.
py::object buffers_as_arrays(py::handle h, const std::string& name) {
  if (!py::isinstance<py::memoryview>(h)) return py::reinterpret_borrow<py::object>(h);
  const py::object obj = h.attr("obj");  // (a view of text is text, as bytes are: no numbers)
  if (py::isinstance<py::bytes>(obj) || py::isinstance<py::bytearray>(obj))
    bad_argument(name, "expected numbers, found a memoryview of " + type_name(obj));
  try {
    return numpy().attr("asarray")(h);
  } catch (py::error_already_set& e) {
    bad_argument(name, std::string("a memoryview numpy cannot read: ") + e.what());
  }
}

std::string short_repr(py::handle h) {
  std::string r;
  try {
    r = py::repr(h).cast<std::string>();
  } catch (const py::error_already_set&) {  // repr() of an int beyond Python's 4300-digit limit raises
    return "a " + type_name(h) + " (no repr)";
  }
  return r.size() > 60 ? r.substr(0, 57) + "..." : r;
}

/// An int-valued Python object (int, numpy integer) as decimal text (through hex: any size).
std::string int_text(py::handle h) {
  const std::string hex = builtin("hex")(py::int_(py::reinterpret_borrow<py::object>(h))).cast<std::string>();
  mpz_t z;
  mpz_init(z);
  mpz_set_str(z, hex.c_str(), 0);  // "0x..." or "-0x...": base from the prefix
  std::string text = mpz_text(z, 10);
  mpz_clear(z);
  return text;
}

void bad_argument(const std::string& path, const std::string& problem) { throw InputError("", path, problem); }

Rational to_rational(py::handle h, const std::string& path, Kinds& kinds) {
  if (h.is_none()) bad_argument(path, "expected a number, found None");
  if (py::isinstance<py::bool_>(h) || py::isinstance(h, numpy().attr("bool_")))
    bad_argument(path, "expected a number, found a bool");
  if (PyFloat_Check(h.ptr())) {  // Python float and numpy.float64
    const double d = PyFloat_AsDouble(h.ptr());
    if (!std::isfinite(d)) bad_argument(path, std::string("not a finite number (") + (std::isnan(d) ? "NaN" : "infinite") + ")");
    kinds.add(NumberKind::f64);
    return qverify::to_rational(d);
  }
  if (PyLong_Check(h.ptr()) || py::isinstance(h, numpy().attr("integer"))) {
    kinds.add(NumberKind::exact);
    return exact_text(int_text(h), path);
  }
  if (py::isinstance<py::str>(h)) {
    kinds.add(NumberKind::exact);
    return exact_text(h.cast<std::string>(), path);
  }
  if (py::isinstance(h, numpy().attr("floating"))) {
    // float16 / float32: exact in double; wider (long double): its exact ratio below
    const long size = h.attr("itemsize").cast<long>();
    if (!numpy().attr("isfinite")(h).cast<bool>()) bad_argument(path, "not a finite number (" + short_repr(h) + ")");
    if (size <= 8) {
      kinds.add(size == 8 ? NumberKind::f64 : NumberKind::f32);
      return qverify::to_rational(h.cast<double>());
    }
  }
  if (py::hasattr(h, "numerator") && py::hasattr(h, "denominator")) {  // fractions.Fraction and look-alikes
    const py::object num = h.attr("numerator"), den = h.attr("denominator");
    if (!(PyLong_Check(num.ptr()) || py::isinstance(num, numpy().attr("integer"))) ||
        !(PyLong_Check(den.ptr()) || py::isinstance(den, numpy().attr("integer"))))
      bad_argument(path, "a fraction needs integer numerator and denominator, found " + short_repr(h));
    kinds.add(NumberKind::exact);
    return from_ratio(num, den, path);
  }
  if (py::hasattr(h, "as_integer_ratio")) {  // decimal.Decimal, numpy long double
    py::tuple pq;
    try {
      pq = h.attr("as_integer_ratio")();
    } catch (py::error_already_set&) {
      bad_argument(path, "not a finite number (" + short_repr(h) + ")");
    }
    kinds.add(NumberKind::exact);
    return from_ratio(pq[0], pq[1], path);
  }
  bad_argument(path, "expected a number (int, float, Fraction, or a decimal or \"p/q\" string), found " + type_name(h) +
                         " " + short_repr(h));
}

Mat4<Rational> to_matrix(py::handle h_given, const std::string& name, Kinds& kinds) {
  const py::object arr = buffers_as_arrays(h_given, name);
  const py::handle h = arr;
  py::object rows = arr;
  if (py::isinstance(h, numpy().attr("ndarray"))) {
    if (h.attr("ndim").cast<long>() != 2 || h.attr("shape").cast<py::tuple>()[0].cast<long>() != 4 ||
        h.attr("shape").cast<py::tuple>()[1].cast<long>() != 4)
      bad_argument(name, "expected a 4x4 matrix, found an array of shape " + shape_text(h));
    rows = h.attr("tolist")();  // floats stay exact (float32 -> float exactly), objects stay themselves
  }
  if (!is_sequence(rows)) bad_argument(name, "expected a 4x4 matrix (rows of numbers), found " + type_name(rows));
  const py::sequence seq = rows.cast<py::sequence>();
  if (seq.size() != 4) bad_argument(name, "expected a 4x4 matrix, found " + std::to_string(seq.size()) + " rows");
  Mat4<Rational> m;
  for (int i = 0; i < 4; ++i) {
    const std::string rp = name + "[" + std::to_string(i) + "]";
    const py::object row = seq[static_cast<size_t>(i)];
    if (!is_sequence(row)) bad_argument(rp, "expected a row of 4 numbers, found " + type_name(row));
    const py::sequence r = row.cast<py::sequence>();
    if (r.size() != 4) bad_argument(rp, "expected a row of 4 numbers, found " + std::to_string(r.size()));
    for (int j = 0; j < 4; ++j) m(i, j) = to_rational(r[static_cast<size_t>(j)], rp + "[" + std::to_string(j) + "]", kinds);
  }
  return m;
}

template <int N> Eigen::Matrix<Rational, N, 1> to_vector(py::handle h_given, const std::string& name, Kinds& kinds) {
  const py::object arr = buffers_as_arrays(h_given, name);
  const py::handle h = arr;
  py::object items = arr;
  if (py::isinstance(h, numpy().attr("ndarray"))) {
    if (h.attr("ndim").cast<long>() != 1 || h.attr("shape").cast<py::tuple>()[0].cast<long>() != N)
      bad_argument(name, "expected " + std::to_string(N) + " numbers, found an array of shape " + shape_text(h));
    items = h.attr("tolist")();
  }
  if (!is_sequence(items)) bad_argument(name, "expected " + std::to_string(N) + " numbers, found " + type_name(items));
  const py::sequence seq = items.cast<py::sequence>();
  if (seq.size() != static_cast<size_t>(N))
    bad_argument(name, "expected " + std::to_string(N) + " numbers, found " + std::to_string(seq.size()));
  Eigen::Matrix<Rational, N, 1> v;
  for (int i = 0; i < N; ++i) v(i) = to_rational(seq[static_cast<size_t>(i)], name + "[" + std::to_string(i) + "]", kinds);
  return v;
}
template Eigen::Matrix<Rational, 3, 1> to_vector<3>(py::handle, const std::string&, Kinds&);
template Eigen::Matrix<Rational, 4, 1> to_vector<4>(py::handle, const std::string&, Kinds&);

py::object fraction(const Rational& q) {
  static py::object* cls = new py::object(py::module_::import("fractions").attr("Fraction"));  // leaked on purpose
  const auto py_int = [](const auto& z) {  // through hex: any size (short_repr's note)
    return builtin("int")(py::str(mpz_text(z.backend().data(), 16)), 16);
  };
  return (*cls)(py_int(numerator(q)), py_int(denominator(q)));
}

double nearest_double(const Rational& q) {
  RoundingReport rep;
  return round_rational<double>(q, rep);
}

namespace {

Rational json_exact(const nlohmann::ordered_json& v) {
  std::string err;
  if (v.is_number_float()) return qverify::to_rational(v.get<double>());
  if (v.is_number_integer()) return Rational(v.get<long long>());
  if (v.is_string()) {
    // qverify's own result, not a user's input: no limit on its size (a light at 1e9000 gives a cone
    // with 36,000-digit entries, and an mpfr result may have an exponent beyond a scene's 10^10000)
    constexpr long kNoLimit = std::numeric_limits<long>::max();
    const auto q = parse_rational(v.get<std::string>(), err, NumberLimits{kNoLimit, kNoLimit});
    if (q) return *q;
  }
  if (v.is_object() && v.contains("lo") && v.contains("hi")) return (json_exact(v["lo"]) + json_exact(v["hi"])) / 2;
  throw std::runtime_error("qverify: unexpected entry in a result: " + v.dump());
}

double json_double(const nlohmann::ordered_json& v) {
  if (v.is_null()) return std::nan("");
  if (v.is_number_float()) return v.get<double>();
  return nearest_double(json_exact(v));
}

}  // namespace

namespace {
/// 2^-e, e the binary exponent of the largest |entry| of m, when that lies beyond 2^+-960 (the
/// entries, up to 2^64 times smaller, then stay normal doubles); else 1.
Rational range_scale(const nlohmann::ordered_json& m) {
  Rational big = 0;
  for (const auto& row : m)
    for (const auto& x : (row.is_array() ? row : nlohmann::ordered_json::array({row})))
      if (!x.is_null()) big = std::max(big, Rational(abs(json_exact(x))));
  if (big == 0) return 1;
  const long e = floor_log2(big);
  return e < 960 && e > -960 ? Rational(1) : exact_pow2(-e);
}
}  // namespace

py::array_t<double> json_to_array(const nlohmann::ordered_json& m, bool projective) {
  const Rational scale = projective ? range_scale(m) : Rational(1);
  const auto entry = [&](const nlohmann::ordered_json& x) {
    return scale == 1 || x.is_null() ? json_double(x) : nearest_double(Rational(json_exact(x) * scale));
  };
  const bool matrix = !m.empty() && m[0].is_array();
  if (!matrix) {
    py::array_t<double> out(static_cast<py::ssize_t>(m.size()));
    auto v = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < m.size(); ++i) v(static_cast<py::ssize_t>(i)) = entry(m[i]);
    return out;
  }
  const auto rows = static_cast<py::ssize_t>(m.size()), cols = static_cast<py::ssize_t>(m[0].size());
  py::array_t<double> out({rows, cols});
  auto v = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < rows; ++i)
    for (py::ssize_t j = 0; j < cols; ++j) v(i, j) = entry(m[static_cast<size_t>(i)][static_cast<size_t>(j)]);
  return out;
}

py::object json_to_fractions(const nlohmann::ordered_json& m) {
  py::list out;
  for (const auto& x : m) {
    if (x.is_array()) out.append(json_to_fractions(x));
    else if (x.is_null()) out.append(py::none());
    else out.append(fraction(json_exact(x)));
  }
  return out;
}

namespace {
/// Text from C++ as Python's str, bytes that are no UTF-8 (a file name's) escaped as os.fsdecode does
/// (surrogateescape), not an error.
py::str os_text(const std::string& s) {
  PyObject* u = PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "surrogateescape");
  if (!u) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(u);
}
}  // namespace

py::object json_to_python(const nlohmann::ordered_json& j) {
  switch (j.type()) {
    case nlohmann::ordered_json::value_t::null: return py::none();
    case nlohmann::ordered_json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer: return py::int_(j.get<long long>());
    case nlohmann::ordered_json::value_t::number_unsigned: return py::int_(j.get<unsigned long long>());
    case nlohmann::ordered_json::value_t::number_float: return py::float_(j.get<double>());
    case nlohmann::ordered_json::value_t::string: return os_text(j.get<std::string>());
    case nlohmann::ordered_json::value_t::array: {
      py::list out;
      for (const auto& x : j) out.append(json_to_python(x));
      return out;
    }
    case nlohmann::ordered_json::value_t::object: {
      py::dict out;
      for (auto it = j.begin(); it != j.end(); ++it) out[os_text(it.key())] = json_to_python(it.value());
      return out;
    }
    default: return py::none();
  }
}

namespace {
PyObject* input_error_type = nullptr;  // a new reference kept for the interpreter's lifetime
}

void register_input_error(py::module_& m) {
  py::dict ns;
  ns["__name__"] = "qverify";
  py::exec(R"(
class InputError(ValueError):
    """Bad input to qverify: nothing was computed from it.

    Attributes:
        path: where the offending value is. For an argument of a call, its
            name and index, e.g. "A[3][1]", "L", "plane", "precision"; for a
            scene or candidate document, the JSON path, e.g.
            "quadrics[0].matrix[1][3]".
        file: the scene or candidate file ("<dict>" for a dict, "" for a
            call's arguments).
        problem: what is wrong with it, in words.
    """

    def __init__(self, message, path="", file="", problem=""):
        super().__init__(message)
        self.path = path
        self.file = file
        self.problem = problem
)",
           ns, ns);
  py::object cls = ns["InputError"];
  input_error_type = cls.inc_ref().ptr();
  m.attr("InputError") = cls;
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      std::rethrow_exception(p);
    } catch (const InputError& e) {
      const std::string msg = e.file.empty() ? (e.path.empty() ? e.problem : e.path + ": " + e.problem) : e.what();
      py::object inst =
          py::reinterpret_borrow<py::object>(input_error_type)(os_text(msg), os_text(e.path), os_text(e.file), os_text(e.problem));
      PyErr_SetObject(input_error_type, inst.ptr());
    }
  });
}

}  // namespace qverify::py_glue
