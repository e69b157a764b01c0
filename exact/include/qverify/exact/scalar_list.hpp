#pragma once
/// \file scalar_list.hpp
/// The scalar types every generic entry point is instantiated for, one
/// translation unit each (src/inst_*.cpp), so that the slow multiprecision
/// instantiations build in parallel and only once.
#include <qverify/exact/interval.hpp>
#include <qverify/exact/scalars.hpp>

#define QVERIFY_FOR_EACH_SCALAR(X) \
  X(float)                         \
  X(double)                        \
  X(long double)                   \
  X(::qverify::Float128)           \
  X(::qverify::Mpfr)               \
  X(::qverify::Interval)           \
  X(::qverify::Rational)
