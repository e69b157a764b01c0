// Escalation of the robust floating path to binary128 (see eval.hpp).
#include <qverify/eval/eval.hpp>

namespace qverify {

namespace {
/// Rounds once to S, after an exact power-of-two scaling into S's range.
template <class S, int R, int C> Eigen::Matrix<S, R, C> narrow(Eigen::Matrix<Float128, R, C> m) {
  const Float128 big = max_abs(m);
  if (big > 0) m *= boost::multiprecision::ldexp(Float128(1), -static_cast<int>(boost::multiprecision::ilogb(big)));
  return m.unaryExpr([](const Float128& x) { return static_cast<S>(x); }).eval();
}
}  // namespace

template <class S> ReflectionItem<S> escalated_reflection(const PreparedReflection<S>& pr) {
  const Mat4<Float128> A = rounded_scaled<Float128>(pr.exact->first);
  const Mat4<Float128> G = rounded_scaled<Float128>(pr.exact->second);
  ReflectionItem<S> item{pr.pair, pr.M, {}, pr.origin};
  set_reflection_status(item.result, reflection_degenerate<Float128>(A));
  item.result.B = narrow<S>(Mat4<Float128>(mirror_image<Float128>(A, G)));
  item.escalated = "float128";
  return item;
}

template <class S> ShadowItem<S> escalated_shadow(const PreparedShadow<S>& ps) {
  const Mat4<Float128> A = rounded_scaled<Float128>(ps.exact->first);
  const Vec4<Float128> L = rounded_scaled<Float128>(ps.exact->second);
  const ShadowResult<Float128> w = shadow<Float128>(A, L, Method::direct);
  ShadowItem<S> item;
  item.pair = ps.pair;
  item.origin = ps.origin;
  item.A = ps.A;
  item.result.flags = w.flags;
  item.result.P = narrow<S>(w.P);
  item.result.polar_plane = narrow<S>(w.polar_plane);
  item.result.R = narrow<S>(w.R);
  item.escalated = "float128";
  return item;
}

template ShadowItem<float> escalated_shadow<float>(const PreparedShadow<float>&);
template ShadowItem<double> escalated_shadow<double>(const PreparedShadow<double>&);
template ShadowItem<long double> escalated_shadow<long double>(const PreparedShadow<long double>&);
template ReflectionItem<float> escalated_reflection<float>(const PreparedReflection<float>&);
template ReflectionItem<double> escalated_reflection<double>(const PreparedReflection<double>&);
template ReflectionItem<long double> escalated_reflection<long double>(const PreparedReflection<long double>&);

}  // namespace qverify
