#pragma once
/// \file convert.hpp
/// Glue of the Python module: Python values in (numbers, arrays, nested
/// lists) as exact Rationals with the argument path of every entry, results
/// out as numpy arrays, Fractions and plain Python containers.
///
/// Every number is taken exactly: a float (Python or numpy) is the dyadic
/// rational it holds, an int is itself, a Fraction (or anything with integer
/// `numerator` and `denominator`) is p/q, a string is a decimal or "p/q" read
/// exactly (exact/number_text.hpp), anything else with an exact
/// `as_integer_ratio()` (Decimal, numpy long double) is that ratio. Bad input
/// throws qverify::InputError with `path` naming the argument and the index
/// ("A[3][1]"); the module turns it into the Python `qverify.InputError`.

#include <qverify/scene/scene.hpp>

#include <nlohmann/json.hpp>
#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace qverify::py_glue {

namespace py = pybind11;

/// Which kind of Python number an input entry was.
enum class NumberKind {
  f32,    ///< a float32 (or narrower) binary float: exact in double
  f64,    ///< a double (Python float, numpy float64)
  exact,  ///< an int, Fraction, decimal or "p/q" string, Decimal, long double: exact rational
};

/// Kinds seen over a set of inputs.
struct Kinds {
  bool any_exact = false, any_f64 = false, any_f32 = false;
  void add(NumberKind k) {
    if (k == NumberKind::exact) any_exact = true;
    else if (k == NumberKind::f64) any_f64 = true;
    else any_f32 = true;
  }
  void add(const Kinds& o) {
    any_exact |= o.any_exact;
    any_f64 |= o.any_f64;
    any_f32 |= o.any_f32;
  }
  /// Every entry is a binary float (exactly a double).
  bool all_floating() const { return !any_exact; }
};

/// numpy, imported once (the module imports it at load time).
py::module_& numpy();
/// The Python type name of a value ("list", "ndarray"), for messages.
std::string type_name(py::handle h);
/// A numpy array's shape as "(3, 4)".
std::string shape_text(py::handle arr);

/// repr(h), cut to 60 characters; a placeholder where repr() raises (an int beyond Python's
/// 4300-digit str() limit).
std::string short_repr(py::handle h);

/// An int-valued Python object (int, numpy integer) as decimal text, of any size: Python's own
/// str() refuses integers beyond 4300 digits (sys.set_int_max_str_digits).
std::string int_text(py::handle h);

/// Throws InputError("", path, problem): an argument of a Python call.
[[noreturn]] void bad_argument(const std::string& path, const std::string& problem);

/// A memoryview as the numpy array over its buffer (a view of bytes or a bytearray is refused, as
/// they are), anything else as it is: arguments are then read as arrays or sequences.
pybind11::object buffers_as_arrays(pybind11::handle h, const std::string& name);

/// One number, exactly. `path` names it in errors.
Rational to_rational(py::handle h, const std::string& path, Kinds& kinds);

/// A 4x4 matrix (numpy array of any numeric or object dtype, or nested sequences).
Mat4<Rational> to_matrix(py::handle h, const std::string& name, Kinds& kinds);
/// A vector of N entries (N = 3 or 4).
template <int N> Eigen::Matrix<Rational, N, 1> to_vector(py::handle h, const std::string& name, Kinds& kinds);

/// A Rational as a Python fractions.Fraction.
py::object fraction(const Rational& q);
/// A Rational as the nearest double (correctly rounded).
double nearest_double(const Rational& q);

/// A matrix or vector of the eval document (JSON numbers, decimal strings,
/// "p/q" strings, {"lo", "hi"} enclosures or null) as a float64 numpy array:
/// each entry the nearest double to its exact value (an enclosure: to its
/// midpoint; null: NaN).
/// A document's vector or matrix as float64, each entry the nearest double (null: NaN). `projective`
/// (P, polar_plane, R, B: defined up to a positive factor): entries beyond double's range (a result in
/// a wider precision, long-double, float128 or mpfr) are first scaled by an exact power of two, so that
/// they neither overflow to inf nor underflow to 0.
py::array_t<double> json_to_array(const nlohmann::ordered_json& m, bool projective = false);
/// The same as nested lists of Fraction (exact results).
py::object json_to_fractions(const nlohmann::ordered_json& m);
/// An exact matrix or vector as nested lists of Fraction.
template <int R, int C> py::object fractions(const Eigen::Matrix<Rational, R, C>& m) {
  if constexpr (C == 1) {
    py::list out;
    for (int i = 0; i < R; ++i) out.append(fraction(m(i)));
    return out;
  } else {
    py::list out;
    for (int i = 0; i < R; ++i) {
      py::list row;
      for (int j = 0; j < C; ++j) row.append(fraction(m(i, j)));
      out.append(row);
    }
    return out;
  }
}
/// An exact matrix or vector as a float64 numpy array (each entry rounded to nearest).
template <int R, int C> py::array_t<double> doubles(const Eigen::Matrix<Rational, R, C>& m) {
  if constexpr (C == 1) {
    py::array_t<double> out(R);
    auto v = out.mutable_unchecked<1>();
    for (int i = 0; i < R; ++i) v(i) = nearest_double(m(i));
    return out;
  } else {
    py::array_t<double> out({R, C});
    auto v = out.mutable_unchecked<2>();
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j) v(i, j) = nearest_double(m(i, j));
    return out;
  }
}

/// Any JSON value as plain Python (dict, list, str, int, float, bool, None).
py::object json_to_python(const nlohmann::ordered_json& j);

/// Registers `InputError` (a ValueError with `path`, `file` and `problem`)
/// in module `m` and the translator of qverify::InputError into it.
void register_input_error(py::module_& m);

}  // namespace qverify::py_glue
