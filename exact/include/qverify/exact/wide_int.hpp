#pragma once
/// \file wide_int.hpp
/// `WideInt<N>`: an exact signed integer of at most N 64-bit limbs, kept in
/// place (no heap, no gcd, no division), as a scalar of the generic core.
///
/// What it is for: exact results from inputs that are *doubles* or *decimal
/// text*. A double is m 2^e (m a 53-bit integer); the ten entries of a matrix
/// share the smallest of their exponents once each is shifted to it, and the
/// direct formulas (polar plane A L, cone (L^T A L) A - (A L)(A L)^T, R, the
/// division-free mirror matrix and M^T A M) use only + - *: they run on the
/// integers, and the results are the exact ones times a known power of two (a
/// positive factor: the results are projective). Decimal text m 10^k clears
/// the same way with a power of ten. `qverify bench` measures this against GMP
/// rationals and CGAL::Mpzf on the same items (README, "bench").
///
/// Sign and magnitude, the magnitude in `limbs()` little-endian limbs; the
/// limbs above are not kept. Products dispatch on the operand sizes to fully
/// unrolled schoolbook kernels (the sizes of this workload are 1 to 9 limbs,
/// where GMP's mpn calls cost more than the arithmetic). A result that would
/// need more than N limbs throws `WideIntOverflow`: nothing is ever truncated
/// silently (callers check a bit bound first and keep the exception as the
/// safety net).
///
/// Exact: Eigen::NumTraits epsilon is 0, so every decision of the core is an
/// exact comparison (ScalarOps' primary template).

#include <qverify/core/scalar.hpp>
#include <qverify/exact/scalars.hpp>

#include <gmp.h>

#if defined(__x86_64__)
#include <immintrin.h>  // _addcarry_u64, _subborrow_u64 (GCC and clang)
#endif

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <algorithm>
#include <utility>

namespace qverify {

/// A WideInt result needed more limbs than it has.
struct WideIntOverflow : std::overflow_error {
  WideIntOverflow() : std::overflow_error("WideInt: result beyond its limbs") {}
};

namespace wide_detail {

using Limb = std::uint64_t;
using Limb2 = unsigned __int128;

/// x + y + carry into *out; the carry out (add / adc on x86, 128-bit arithmetic elsewhere).
inline unsigned char add_carry(unsigned char carry, Limb x, Limb y, Limb* out) {
#if defined(__x86_64__)
  unsigned long long s;
  carry = _addcarry_u64(carry, x, y, &s);
  *out = s;
  return carry;
#else
  const Limb2 t = static_cast<Limb2>(x) + y + carry;
  *out = static_cast<Limb>(t);
  return static_cast<unsigned char>(t >> 64);
#endif
}
/// x - y - borrow into *out; the borrow out (sub / sbb on x86).
inline unsigned char sub_borrow(unsigned char borrow, Limb x, Limb y, Limb* out) {
#if defined(__x86_64__)
  unsigned long long s;
  borrow = _subborrow_u64(borrow, x, y, &s);
  *out = s;
  return borrow;
#else
  const Limb2 t = static_cast<Limb2>(x) - y - borrow;
  *out = static_cast<Limb>(t);
  return static_cast<unsigned char>((t >> 64) & 1);
#endif
}

/// r[0 .. AN+BN) = a[0 .. AN) * b[0 .. BN), unrolled.
template <int AN, int BN> inline void mul_fixed(Limb* __restrict r, const Limb* __restrict a, const Limb* __restrict b) {
  Limb c = 0;
#pragma GCC unroll 16
  for (int j = 0; j < BN; ++j) {
    const Limb2 t = static_cast<Limb2>(a[0]) * b[j] + c;
    r[j] = static_cast<Limb>(t);
    c = static_cast<Limb>(t >> 64);
  }
  r[BN] = c;
#pragma GCC unroll 16
  for (int i = 1; i < AN; ++i) {
    c = 0;
#pragma GCC unroll 16
    for (int j = 0; j < BN; ++j) {
      const Limb2 t = static_cast<Limb2>(a[i]) * b[j] + r[i + j] + c;  // < 2^128: no overflow
      r[i + j] = static_cast<Limb>(t);
      c = static_cast<Limb>(t >> 64);
    }
    r[i + BN] = c;
  }
}

inline void mul_any(Limb* r, const Limb* a, int an, const Limb* b, int bn) {
  Limb c = 0;
  for (int j = 0; j < bn; ++j) {
    const Limb2 t = static_cast<Limb2>(a[0]) * b[j] + c;
    r[j] = static_cast<Limb>(t);
    c = static_cast<Limb>(t >> 64);
  }
  r[bn] = c;
  for (int i = 1; i < an; ++i) {
    c = 0;
    for (int j = 0; j < bn; ++j) {
      const Limb2 t = static_cast<Limb2>(a[i]) * b[j] + r[i + j] + c;
      r[i + j] = static_cast<Limb>(t);
      c = static_cast<Limb>(t >> 64);
    }
    r[i + bn] = c;
  }
}

/// r = a * b for an >= bn >= 1 (r has an + bn limbs).
inline void mul(Limb* r, const Limb* a, int an, const Limb* b, int bn) {
  switch (an * 16 + bn) {
#define QVERIFY_WIDE_MUL(x, y) \
  case (x) * 16 + (y): mul_fixed<x, y>(r, a, b); return;
    QVERIFY_WIDE_MUL(1, 1) QVERIFY_WIDE_MUL(2, 1) QVERIFY_WIDE_MUL(2, 2) QVERIFY_WIDE_MUL(3, 1)
    QVERIFY_WIDE_MUL(3, 2) QVERIFY_WIDE_MUL(3, 3) QVERIFY_WIDE_MUL(4, 1) QVERIFY_WIDE_MUL(4, 2)
    QVERIFY_WIDE_MUL(4, 3) QVERIFY_WIDE_MUL(4, 4) QVERIFY_WIDE_MUL(5, 1) QVERIFY_WIDE_MUL(5, 2)
    QVERIFY_WIDE_MUL(5, 3) QVERIFY_WIDE_MUL(5, 4) QVERIFY_WIDE_MUL(5, 5) QVERIFY_WIDE_MUL(6, 1)
    QVERIFY_WIDE_MUL(6, 2) QVERIFY_WIDE_MUL(6, 3) QVERIFY_WIDE_MUL(6, 4) QVERIFY_WIDE_MUL(7, 1)
    QVERIFY_WIDE_MUL(7, 2) QVERIFY_WIDE_MUL(7, 3) QVERIFY_WIDE_MUL(8, 1) QVERIFY_WIDE_MUL(8, 2)
    QVERIFY_WIDE_MUL(9, 1)
#undef QVERIFY_WIDE_MUL
    default: mul_any(r, a, an, b, bn);
  }
}

}  // namespace wide_detail

template <int N> class WideInt {
  static_assert(N >= 2, "WideInt needs at least two limbs");

 public:
  using Limb = wide_detail::Limb;
  static constexpr int max_limbs = N;

  /// Zero. User-provided, so that a value-initialization (`WideInt()`, `S()`) does not fill
  /// all N limbs with zeros first (a `rep stos` of N + 1 words and a stalled reload, measured).
  WideInt() {}
  WideInt(int v) : WideInt(static_cast<long long>(v)) {}
  WideInt(long v) : WideInt(static_cast<long long>(v)) {}
  WideInt(long long v) {
    if (v == 0) return;
    d_[0] = v < 0 ? Limb(0) - static_cast<Limb>(v) : static_cast<Limb>(v);
    size_ = v < 0 ? -1 : 1;
  }

  /// (-1)^negative * m * 2^shift, exactly (throws WideIntOverflow beyond N limbs).
  static WideInt from_magnitude(unsigned __int128 m, bool negative, int shift = 0) {
    WideInt r;
    if (m == 0) return r;
    if (shift < 0) throw std::invalid_argument("WideInt: negative shift");
    const int q = shift / 64, b = shift % 64;
    const Limb lo = static_cast<Limb>(m), hi = static_cast<Limb>(m >> 64);
    Limb w[3] = {lo << b, b ? (hi << b) | (lo >> (64 - b)) : hi, b ? hi >> (64 - b) : Limb(0)};
    int n = w[2] ? 3 : w[1] ? 2 : 1;
    if (q + n > N) throw WideIntOverflow();
    for (int k = 0; k < q; ++k) r.d_[k] = 0;
    for (int k = 0; k < n; ++k) r.d_[q + k] = w[k];
    n += q;
    r.size_ = negative ? -n : n;
    return r;
  }

  int sign() const { return (size_ > 0) - (size_ < 0); }
  /// Limbs of the magnitude.
  int limbs() const { return std::abs(size_); }
  const Limb* limb_data() const { return d_; }
  /// Bits of the magnitude (0 for zero).
  int bits() const {
    const int n = limbs();
    return n ? (n - 1) * 64 + 64 - __builtin_clzll(d_[n - 1]) : 0;
  }

  /// The value as a GMP rational (exactly).
  Rational to_rational() const {
    boost::multiprecision::mpz_int z;
    if (size_ != 0) mpz_import(z.backend().data(), static_cast<std::size_t>(limbs()), -1, sizeof(Limb), 0, 0, d_);
    if (size_ < 0) z = -z;
    return Rational(z);
  }
  /// The value as a GMP integer.
  void to_mpz(mpz_t out) const {
    if (size_ == 0) {
      mpz_set_ui(out, 0);
      return;
    }
    mpz_import(out, static_cast<std::size_t>(limbs()), -1, sizeof(Limb), 0, 0, d_);
    if (size_ < 0) mpz_neg(out, out);
  }

  friend WideInt operator*(const WideInt& a, const WideInt& b) {
    WideInt r;
    const int an = a.limbs(), bn = b.limbs();
    if (!an || !bn) return r;
    int n = an + bn;
    if (n > N + 1) throw WideIntOverflow();
    if (n > N) {  // may still fit: compute into a scratch one limb wider
      Limb t[N + 1];
      if (an >= bn) wide_detail::mul(t, a.d_, an, b.d_, bn);
      else wide_detail::mul(t, b.d_, bn, a.d_, an);
      if (t[N] != 0) throw WideIntOverflow();
      for (int k = 0; k < N; ++k) r.d_[k] = t[k];
      n = N;
    } else if (an >= bn) {
      wide_detail::mul(r.d_, a.d_, an, b.d_, bn);
    } else {
      wide_detail::mul(r.d_, b.d_, bn, a.d_, an);
    }
    while (n > 0 && r.d_[n - 1] == 0) --n;
    r.size_ = (a.size_ ^ b.size_) < 0 ? -n : n;
    return r;
  }
  friend WideInt operator+(const WideInt& a, const WideInt& b) { return add(a, b, b.size_); }
  friend WideInt operator-(const WideInt& a, const WideInt& b) { return add(a, b, -b.size_); }
  WideInt operator-() const {
    WideInt r;
    assign(r, *this, -size_);
    return r;
  }
  WideInt operator+() const {
    WideInt r;
    assign(r, *this, size_);
    return r;
  }
  WideInt& operator+=(const WideInt& b) { return *this = *this + b; }
  WideInt& operator-=(const WideInt& b) { return *this = *this - b; }
  WideInt& operator*=(const WideInt& b) { return *this = *this * b; }

  friend bool operator==(const WideInt& a, const WideInt& b) {
    if (a.size_ != b.size_) return false;
    for (int k = 0; k < a.limbs(); ++k)
      if (a.d_[k] != b.d_[k]) return false;
    return true;
  }
  friend bool operator!=(const WideInt& a, const WideInt& b) { return !(a == b); }
  friend bool operator<(const WideInt& a, const WideInt& b) { return compare(a, b) < 0; }
  friend bool operator>(const WideInt& a, const WideInt& b) { return compare(a, b) > 0; }
  friend bool operator<=(const WideInt& a, const WideInt& b) { return compare(a, b) <= 0; }
  friend bool operator>=(const WideInt& a, const WideInt& b) { return compare(a, b) >= 0; }

 private:
  /// |a| against |b|: -1, 0, 1.
  static int compare_magnitude(const WideInt& a, const WideInt& b) {
    const int an = a.limbs(), bn = b.limbs();
    if (an != bn) return an < bn ? -1 : 1;
    for (int k = an - 1; k >= 0; --k)
      if (a.d_[k] != b.d_[k]) return a.d_[k] < b.d_[k] ? -1 : 1;
    return 0;
  }
  static int compare(const WideInt& a, const WideInt& b) {
    if (a.sign() != b.sign()) return a.sign() < b.sign() ? -1 : 1;
    const int m = compare_magnitude(a, b);
    return a.size_ < 0 ? -m : m;
  }
  /// r = (sign) x, limb by limb (8-byte moves: the limbs were just written that way,
  /// and a wide copy of narrow stores stalls store forwarding).
  static void assign(WideInt& r, const WideInt& x, int signed_size) {
    const int n = x.limbs();
    for (int k = 0; k < n; ++k) {
      r.d_[k] = x.d_[k];
      asm("" : "+r"(k));  // keep it a loop of moves, not a call to memmove
    }
    r.size_ = signed_size;
  }
  /// a + (b with signed size bs). One named result (constructed in place).
  static WideInt add(const WideInt& a, const WideInt& b, int bs) {
    WideInt r;
    if (bs == 0) {
      assign(r, a, a.size_);
    } else if (a.size_ == 0) {
      assign(r, b, bs);
    } else if ((a.size_ ^ bs) >= 0) {  // same signs: magnitudes add
      const Limb *x = a.d_, *y = b.d_;
      int xn = a.limbs(), yn = std::abs(bs);
      if (xn < yn) std::swap(x, y), std::swap(xn, yn);
      unsigned char c = 0;
      int k = 0;
      for (; k < yn; ++k) c = wide_detail::add_carry(c, x[k], y[k], &r.d_[k]);
      for (; k < xn; ++k) c = wide_detail::add_carry(c, x[k], 0, &r.d_[k]);
      int n = xn;
      if (c) {
        if (n >= N) throw WideIntOverflow();
        r.d_[n++] = 1;
      }
      r.size_ = a.size_ < 0 ? -n : n;
    } else {  // opposite signs: the smaller magnitude from the larger
      const int cmp = compare_magnitude(a, b);
      if (cmp != 0) {
        const Limb *x = a.d_, *y = b.d_;
        int xn = a.limbs(), yn = std::abs(bs);
        bool negative = a.size_ < 0;
        if (cmp < 0) {
          std::swap(x, y), std::swap(xn, yn);
          negative = bs < 0;
        }
        unsigned char c = 0;
        int k = 0;
        for (; k < yn; ++k) c = wide_detail::sub_borrow(c, x[k], y[k], &r.d_[k]);
        for (; k < xn; ++k) c = wide_detail::sub_borrow(c, x[k], 0, &r.d_[k]);
        int n = xn;
        while (n > 0 && r.d_[n - 1] == 0) --n;
        r.size_ = negative ? -n : n;
      }
    }
    return r;
  }

  int size_ = 0;  ///< signed: the sign of the value, |size_| limbs of magnitude
  Limb d_[N];
};

/// A finite double x as m 2^e with m an integer below 2^53 (the significand with
/// its hidden bit; a subnormal's own bits, e = -1074), read from the bits (a
/// libm frexp and ldexp per entry were a tenth of an exact bench item): e, or
/// a very large value for 0 (so that it never is the smallest exponent).
inline int binary_exponent(double x) {
  if (x == 0) return 1 << 20;
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  const int biased = static_cast<int>((b >> 52) & 0x7ff);
  if (biased == 0x7ff) throw std::invalid_argument("WideInt: not a finite double");
  return biased == 0 ? -1074 : biased - 1075;
}

/// x * 2^-e0 as a WideInt, exactly; requires e0 <= binary_exponent(x).
template <int N> WideInt<N> wide_from_double(double x, int e0) {
  if (x == 0) return WideInt<N>();
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  const int e = binary_exponent(x);  // throws for inf and NaN
  std::uint64_t m = b & ((std::uint64_t(1) << 52) - 1);
  if (((b >> 52) & 0x7ff) != 0) m |= std::uint64_t(1) << 52;
  return WideInt<N>::from_magnitude(m, (b >> 63) != 0, e - e0);
}

/// The doubles x[0 .. n) as integers: out[k] = x[k] 2^-e with e the smallest
/// binary exponent among them (one matrix's entries share one scale: a
/// positive factor, the results of the division-free formulas are
/// projective). Returns e; throws WideIntOverflow when an entry does not fit
/// in N limbs (a spread of exponents beyond them), std::invalid_argument for
/// inf or NaN. All zero: 0.
template <int N> int wide_from_doubles(const double* x, int n, WideInt<N>* out) {
  int e = binary_exponent(x[0]);
  for (int k = 1; k < n; ++k) e = std::min(e, binary_exponent(x[k]));
  if (e == binary_exponent(0.0)) e = 0;
  for (int k = 0; k < n; ++k) out[k] = wide_from_double<N>(x[k], e);
  return e;
}

namespace wide_detail {
/// 10^k for k = 0..38, as 128-bit integers.
struct Pow10Table {
  unsigned __int128 p[39];
  constexpr Pow10Table() : p() {
    p[0] = 1;
    for (int k = 1; k < 39; ++k) p[k] = p[k - 1] * 10;
  }
};
inline constexpr Pow10Table kPow10{};
}  // namespace wide_detail

/// m 10^shift as a WideInt, exactly (shift >= 0; throws WideIntOverflow beyond
/// N limbs). Decimal text m 10^e, scaled to the smallest exponent e0 of a
/// matrix, is wide_from_decimal(m, e - e0) times 10^e0.
template <int N> WideInt<N> wide_from_decimal(std::int64_t m, int shift) {
  if (shift < 0) throw std::invalid_argument("WideInt: negative decimal shift");
  const bool negative = m < 0;
  const auto mag = static_cast<unsigned __int128>(negative ? -static_cast<__int128>(m) : static_cast<__int128>(m));
  if (mag == 0) return WideInt<N>();
  if (shift <= 38) {
    const unsigned __int128 p = wide_detail::kPow10.p[shift];
    if (mag <= ~static_cast<unsigned __int128>(0) / p) return WideInt<N>::from_magnitude(mag * p, negative);
  }
  WideInt<N> r = WideInt<N>::from_magnitude(mag, negative);
  for (; shift > 0; shift -= std::min(shift, 38))
    r = r * WideInt<N>::from_magnitude(wide_detail::kPow10.p[std::min(shift, 38)], false);
  return r;
}

}  // namespace qverify

namespace Eigen {

/// WideInt is exact: epsilon 0 (every tolerance of the core is an equality).
template <int N> struct NumTraits<qverify::WideInt<N>> : GenericNumTraits<qverify::WideInt<N>> {
  using Self = qverify::WideInt<N>;
  using Real = Self;
  using NonInteger = Self;
  using Literal = Self;
  using Nested = Self;
  enum {
    IsComplex = 0,
    IsInteger = 1,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 4,
    MulCost = 8
  };
  static Real epsilon() { return Real(0); }
  static Real dummy_precision() { return Real(0); }
  static Real highest() { return Real(0); }
  static Real lowest() { return Real(0); }
  static int digits10() { return 0; }
};

}  // namespace Eigen
