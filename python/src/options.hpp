#pragma once
/// \file options.hpp
/// Keyword arguments shared by the bindings, checked before anything is
/// computed (bad values raise qverify.InputError with the argument's name).

#include "convert.hpp"

#include <qverify/eval/eval.hpp>
#include <qverify/exact/precision.hpp>

#include <mutex>
#include <optional>
#include <string>

namespace qverify::py_glue {

// Each takes the Python object as given: a value of the wrong type (accuracy="1e-9", samples=64.0,
// precision=None) is an InputError naming the argument too, never pybind's TypeError.
Precision precision_arg(const py::object& text);
Method method_arg(const py::object& text);
std::optional<Frame> frame_arg(const py::object& frame);
double accuracy_arg(const py::object& accuracy);
int samples_arg(const py::object& samples);
std::uint64_t seed_arg(const py::object& seed);
/// threads of the batch checks: 0 (one per logical processor) or a positive count.
int threads_arg(const py::object& threads);
/// A str argument, else InputError naming it.
std::string text_arg(const py::object& x, const char* name, const char* expected);
/// A real number (int, float, numpy scalar, Fraction, Decimal: what float() takes; not bool or str) as a double.
double number_arg(const py::object& x, const char* name);
/// An integer (int, numpy integer: what operator.index() takes; not bool or float) as a Python int.
py::int_ integer_arg(const py::object& x, const char* name);

/// Boost 1.74 keeps MPFR's default precision in one global (not per thread):
/// computations in precision mpfr (and the adaptive mode, which uses MPFI)
/// run one at a time. Taken with the GIL released.
std::unique_lock<std::mutex> mpfr_lock(bool needed);

}  // namespace qverify::py_glue
