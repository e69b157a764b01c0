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

Precision precision_arg(const std::string& text);
Method method_arg(const std::string& text);
std::optional<Frame> frame_arg(const py::object& frame);
double accuracy_arg(double accuracy);
int samples_arg(long samples);
std::uint64_t seed_arg(long long seed);

/// Boost 1.74 keeps MPFR's default precision in one global (not per thread):
/// computations in precision mpfr (and the adaptive mode, which uses MPFI)
/// run one at a time. Taken with the GIL released.
std::unique_lock<std::mutex> mpfr_lock(bool needed);

}  // namespace qverify::py_glue
