#include <qverify/exact/statuses.hpp>

namespace qverify {

namespace {
template <int R, int C> Eigen::Matrix<Interval, R, C> enclosure(const Eigen::Matrix<Rational, R, C>& m) {
  Eigen::Matrix<Interval, R, C> out;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = enclose(m(i));
  return out;
}
}  // namespace

StatusDecision exact_shadow_status(const Mat4<Rational>& A, const Vec4<Rational>& L) {
  const StatusDecision filtered = shadow_status<Interval>(enclosure(A), enclosure(L));
  return filtered.decided() ? filtered : shadow_status<Rational>(A, L);
}

bool exact_degenerate(const Mat4<Rational>& A) {
  const Truth t = degenerate_quadric<Interval>(enclosure(A));
  return t == Truth::unknown ? degenerate_quadric<Rational>(A) == Truth::yes : t == Truth::yes;
}

}  // namespace qverify
