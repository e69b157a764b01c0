#pragma once
/// \file polynomial.hpp
/// A symbolic scalar: sparse multivariate Laurent polynomials with exact
/// rational coefficients. Run through the *same* generic core as the numeric
/// types, it turns each formula into polynomials in the symbols (entries of
/// A, light, mirror), so that "X = Y" is decided as a polynomial identity: a
/// symbolic proof, not a sample.
///
/// Division is exact: by a constant or by a monomial (negative exponents, as
/// the paper's T divides by l_z). Dividing by anything else, or ordering two
/// non-constant polynomials, throws std::domain_error.

#include <qverify/exact/scalars.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace qverify {

class Poly {
 public:
  static constexpr int kVars = 20;
  using Exponents = std::array<std::int8_t, kVars>;

  Poly() = default;
  Poly(int c) : Poly(Rational(c)) {}  // NOLINT: implicit, as for any scalar
  Poly(const Rational& c) {           // NOLINT
    if (c != 0) terms_[Exponents{}] = c;
  }
  /// The symbol number i raised to `power`.
  static Poly var(int i, int power = 1) {
    Poly p;
    Exponents e{};
    e[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(power);
    p.terms_[e] = Rational(1);
    return p;
  }

  bool is_zero() const { return terms_.empty(); }
  bool is_constant() const { return terms_.empty() || (terms_.size() == 1 && terms_.begin()->first == Exponents{}); }
  Rational constant() const {
    const auto it = terms_.find(Exponents{});
    return it == terms_.end() ? Rational(0) : it->second;
  }
  std::size_t size() const { return terms_.size(); }

  Poly& operator+=(const Poly& o) {
    for (const auto& [e, c] : o.terms_) add_term(e, c);
    return *this;
  }
  Poly& operator-=(const Poly& o) {
    for (const auto& [e, c] : o.terms_) add_term(e, -c);
    return *this;
  }
  Poly& operator*=(const Poly& o) { return *this = *this * o; }
  Poly& operator/=(const Poly& o) { return *this = *this / o; }

  friend Poly operator+(Poly a, const Poly& b) { return a += b; }
  friend Poly operator-(Poly a, const Poly& b) { return a -= b; }
  friend Poly operator-(Poly a) {
    for (auto& t : a.terms_) t.second = -t.second;
    return a;
  }
  friend Poly operator*(const Poly& a, const Poly& b) {
    Poly r;
    for (const auto& [ea, ca] : a.terms_)
      for (const auto& [eb, cb] : b.terms_) {
        Exponents e;
        for (int i = 0; i < kVars; ++i) e[i] = static_cast<std::int8_t>(ea[i] + eb[i]);
        r.add_term(e, ca * cb);
      }
    return r;
  }
  /// Exact division by a constant or a monomial.
  friend Poly operator/(const Poly& a, const Poly& b) {
    if (b.terms_.size() != 1) throw std::domain_error("Poly: division by a non-monomial");
    const auto& [eb, cb] = *b.terms_.begin();
    Poly r;
    for (const auto& [ea, ca] : a.terms_) {
      Exponents e;
      for (int i = 0; i < kVars; ++i) e[i] = static_cast<std::int8_t>(ea[i] - eb[i]);
      r.terms_[e] = ca / cb;
    }
    return r;
  }
  friend bool operator==(const Poly& a, const Poly& b) { return a.terms_ == b.terms_; }
  friend bool operator!=(const Poly& a, const Poly& b) { return !(a == b); }
  /// Ordering exists only between constants.
  friend bool operator<(const Poly& a, const Poly& b) {
    if (!a.is_constant() || !b.is_constant()) throw std::domain_error("Poly: no order between non-constant polynomials");
    return a.constant() < b.constant();
  }
  friend bool operator>(const Poly& a, const Poly& b) { return b < a; }
  friend bool operator<=(const Poly& a, const Poly& b) { return !(b < a); }
  friend bool operator>=(const Poly& a, const Poly& b) { return !(a < b); }

  /// Partial derivative with respect to symbol i.
  Poly derivative(int i) const {
    Poly r;
    for (const auto& [e, c] : terms_) {
      if (e[static_cast<std::size_t>(i)] == 0) continue;
      Exponents f = e;
      f[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(f[static_cast<std::size_t>(i)] - 1);
      r.add_term(f, c * e[static_cast<std::size_t>(i)]);
    }
    return r;
  }

  /// Value at a point (one Rational per symbol; symbols with negative powers
  /// must be non-zero there).
  Rational evaluate(const std::vector<Rational>& at) const {
    Rational sum(0);
    for (const auto& [e, c] : terms_) {
      Rational t = c;
      for (int i = 0; i < kVars; ++i) {
        for (int k = 0; k < e[i]; ++k) t *= at[static_cast<std::size_t>(i)];
        for (int k = 0; k > e[i]; --k) t /= at[static_cast<std::size_t>(i)];
      }
      sum += t;
    }
    return sum;
  }

  /// Text with the given symbol names, e.g. "2*b2*l_z - w".
  std::string str(const std::vector<std::string>& names) const {
    if (terms_.empty()) return "0";
    std::string out;
    for (auto it = terms_.rbegin(); it != terms_.rend(); ++it) {
      const auto& [e, c] = *it;
      std::string mono;
      for (int i = 0; i < kVars; ++i) {
        if (e[i] == 0) continue;
        if (!mono.empty()) mono += "*";
        mono += names[static_cast<std::size_t>(i)];
        if (e[i] != 1) mono += "^" + std::to_string(e[i]);
      }
      const bool neg = c < 0;
      const Rational a = neg ? Rational(-c) : c;
      std::string coef = (a == 1 && !mono.empty()) ? "" : a.str();
      if (!coef.empty() && !mono.empty()) coef += "*";
      out += (out.empty() ? (neg ? "-" : "") : (neg ? " - " : " + ")) + coef + mono;
    }
    return out;
  }

 private:
  std::map<Exponents, Rational> terms_;

  void add_term(const Exponents& e, const Rational& c) {
    if (c == 0) return;
    auto [it, fresh] = terms_.emplace(e, c);
    if (!fresh) {
      it->second += c;
      if (it->second == 0) terms_.erase(it);
    }
  }
};

}  // namespace qverify

namespace Eigen {
/// The symbolic scalar is exact: epsilon 0.
template <> struct NumTraits<qverify::Poly> : qverify::ExactNumTraits<qverify::Poly, 0, 50, 200> {};
}  // namespace Eigen
