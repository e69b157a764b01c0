#pragma once
/// \file adaptive.hpp
/// `qverify eval --tolerance T`: each item escalates double -> interval ->
/// exact until its result is *certified* within T (relative to its largest
/// entry) of the exact result of the same formula. The document says, per item,
/// which stage certified it. (There is no MPFR stage: certifying an MPFR result
/// needs MPFR intervals, MPFI, which qverify does not depend on.)

#include <qverify/verify/eval.hpp>

namespace qverify {

nlohmann::ordered_json adaptive_eval_document(const Scene& sc, Method method, double tolerance);

}  // namespace qverify
