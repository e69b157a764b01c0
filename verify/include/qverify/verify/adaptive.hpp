#pragma once
/// \file adaptive.hpp
/// `qverify eval --tolerance T`: each item escalates double -> interval ->
/// mpfr (MPFI intervals, 256 bits) -> exact until its double result is
/// *certified* within T (relative to its largest entry) of the exact result of
/// the same formula: every entry within T x scale of every point of a
/// certified enclosure of the exact result. The document says, per item, which
/// stage certified it and the certified bound, and, like every floating
/// item of eval, its error_bound (the geometric error of the matrices written,
/// on exact points) with `inaccurate` when that may exceed the accuracy target.

#include <qverify/eval/eval_report.hpp>

namespace qverify {

/// The adaptive evaluation of `sc` (its `adaptive` facts and every item's `certified` stage set).
EvalReport adaptive_eval_report(const Scene& sc, Method method, double tolerance,
                                const AccuracyOptions& accuracy = AccuracyOptions{});

}  // namespace qverify
