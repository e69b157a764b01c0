#pragma once
/// \file instantiate.hpp
/// Explicit instantiation (QVERIFY_INSTANTIATE) and suppression of implicit
/// instantiation (QVERIFY_EXTERN) of the generic pipeline for a scalar type.
#include <qverify/eval/eval.hpp>
#include <qverify/eval/eval_report.hpp>
#include <qverify/eval/timed.hpp>
#include <qverify/exact/scalar_list.hpp>

#define QVERIFY_INSTANTIATE(T)                                                                                       \
  template qverify::EvalReport qverify::eval_report<T>(const qverify::Scene&, const qverify::Precision&,             \
                                                      qverify::Method, std::optional<qverify::Frame>,                \
                                                      const qverify::AccuracyOptions&);                              \
  template qverify::ResultSet qverify::computed_results<T>(const qverify::Scene&, const qverify::Precision&,          \
                                                          qverify::Method, std::optional<qverify::Frame>,            \
                                                          const std::optional<qverify::AccuracyOptions>&);           \
  template qverify::TimedResult qverify::timed_results<T>(const qverify::Scene&, const qverify::Precision&,          \
                                                          qverify::Method, double, int);                             \
  template qverify::Evaluation<T> qverify::evaluate<T>(const qverify::Scene&, qverify::Method,                       \
                                                       std::optional<qverify::Frame>);                               \
  template qverify::TypedScene<T> qverify::typed_scene<T>(const qverify::Scene&);

#define QVERIFY_EXTERN(T)                                                                                            \
  extern template qverify::EvalReport qverify::eval_report<T>(const qverify::Scene&, const qverify::Precision&,      \
                                                             qverify::Method, std::optional<qverify::Frame>,         \
                                                             const qverify::AccuracyOptions&);                       \
  extern template qverify::ResultSet qverify::computed_results<T>(const qverify::Scene&, const qverify::Precision&,   \
                                                                  qverify::Method, std::optional<qverify::Frame>,    \
                                                                  const std::optional<qverify::AccuracyOptions>&);   \
  extern template qverify::TimedResult qverify::timed_results<T>(const qverify::Scene&, const qverify::Precision&,    \
                                                                 qverify::Method, double, int);
