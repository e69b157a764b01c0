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
/// Two's complement in `limbs()` little-endian limbs (the value is them
/// sign-extended; the limbs above are not kept). Sizes are *structural*: a
/// product holds an + bn limbs and a sum max(an, bn), one more only on a signed
/// overflow, whatever the values; so when a matrix's entries are read at one
/// size (wide_from_doubles widens them to the widest) every item runs the same
/// kernels in the same order, and the branches on sizes are predicted (with
/// sign and magnitude and trimmed sizes, random exponents made a third of an
/// item's time mispredicted branches). Products dispatch on the operand sizes
/// to fully unrolled schoolbook kernels of the limb patterns, corrected for the
/// signs (the sizes of this workload are 1 to 10 limbs, where GMP's mpn calls
/// cost more than the arithmetic). A result that would need more than N limbs
/// throws `WideIntOverflow`: nothing is ever truncated silently (callers check a
/// bit bound first and keep the exception as the safety net). One item at a
/// time: `qverify bench`'s exact rows run W items at once on DigitPack
/// (digit_pack.hpp), and fall back to this type where a block does not fit.
///
/// Exact: Eigen::NumTraits epsilon is 0, so every decision of the core is an
/// exact comparison (ScalarOps' primary template).

#include <qverify/core/scalar.hpp>
#include <qverify/exact/prefix_copy.hpp>
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

/// The sign of a two's complement limb pattern whose top limb is x: all ones or zero.
inline Limb sign_of(Limb x) { return static_cast<Limb>(static_cast<std::int64_t>(x) >> 63); }

/// r[0 .. an + bn) = a b for two's complement patterns a (an limbs) and b (bn limbs): the
/// unsigned product of the patterns less the pattern of b at limb an where a < 0 and that of
/// a at limb bn where b < 0 (a = U(a) - [a < 0] 2^(64 an)); modulo 2^(64 (an + bn)) that is
/// a b, which fits in an + bn limbs.
template <int AN, int BN> inline void signed_mul_fixed(Limb* __restrict r, const Limb* __restrict a, const Limb* __restrict b) {
  mul_fixed<AN, BN>(r, a, b);
  const Limb as = sign_of(a[AN - 1]), bs = sign_of(b[BN - 1]);
  unsigned char c = 0;
#pragma GCC unroll 16
  for (int k = 0; k < BN; ++k) c = sub_borrow(c, r[AN + k], b[k] & as, &r[AN + k]);
  c = 0;
#pragma GCC unroll 16
  for (int k = 0; k < AN; ++k) c = sub_borrow(c, r[BN + k], a[k] & bs, &r[BN + k]);
}

inline void signed_mul_any(Limb* r, const Limb* a, int an, const Limb* b, int bn) {
  mul_any(r, a, an, b, bn);
  const Limb as = sign_of(a[an - 1]), bs = sign_of(b[bn - 1]);
  unsigned char c = 0;
  for (int k = 0; k < bn; ++k) c = sub_borrow(c, r[an + k], b[k] & as, &r[an + k]);
  c = 0;
  for (int k = 0; k < an; ++k) c = sub_borrow(c, r[bn + k], a[k] & bs, &r[bn + k]);
}

/// r = a * b, signed, for an >= bn >= 1 (r has an + bn limbs).
inline void signed_mul(Limb* r, const Limb* a, int an, const Limb* b, int bn) {
  switch (an * 16 + bn) {
#define QVERIFY_WIDE_MUL(x, y) \
  case (x) * 16 + (y): signed_mul_fixed<x, y>(r, a, b); return;
    QVERIFY_WIDE_MUL(1, 1) QVERIFY_WIDE_MUL(2, 1) QVERIFY_WIDE_MUL(2, 2) QVERIFY_WIDE_MUL(3, 1)
    QVERIFY_WIDE_MUL(3, 2) QVERIFY_WIDE_MUL(3, 3) QVERIFY_WIDE_MUL(4, 1) QVERIFY_WIDE_MUL(4, 2)
    QVERIFY_WIDE_MUL(4, 3) QVERIFY_WIDE_MUL(4, 4) QVERIFY_WIDE_MUL(5, 1) QVERIFY_WIDE_MUL(5, 2)
    QVERIFY_WIDE_MUL(5, 3) QVERIFY_WIDE_MUL(5, 4) QVERIFY_WIDE_MUL(5, 5) QVERIFY_WIDE_MUL(6, 1)
    QVERIFY_WIDE_MUL(6, 2) QVERIFY_WIDE_MUL(6, 3) QVERIFY_WIDE_MUL(6, 4) QVERIFY_WIDE_MUL(7, 1)
    QVERIFY_WIDE_MUL(7, 2) QVERIFY_WIDE_MUL(7, 3) QVERIFY_WIDE_MUL(8, 1) QVERIFY_WIDE_MUL(8, 2)
    QVERIFY_WIDE_MUL(9, 1)
#undef QVERIFY_WIDE_MUL
    default: signed_mul_any(r, a, an, b, bn);
  }
}

}  // namespace wide_detail

template <int N> class WideInt {
  static_assert(N >= 2 && N <= 32, "WideInt: 2 to 32 limbs");

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
    d_[0] = static_cast<Limb>(v);
    n_ = 1;
  }
  /// Copies the limbs in use only, 8 bytes at a time (they were just written that way, and a
  /// wide reload of narrow stores stalls store forwarding).
  WideInt(const WideInt& x) { copy_from(x); }
  WideInt& operator=(const WideInt& x) {
    copy_from(x);
    return *this;
  }

  /// (-1)^negative * m * 2^shift, exactly (throws WideIntOverflow beyond N limbs).
  static WideInt from_magnitude(unsigned __int128 m, bool negative, int shift = 0) {
    WideInt r;
    if (m == 0) return r;
    if (shift < 0) throw std::invalid_argument("WideInt: negative shift");
    const int q = shift / 64, b = shift % 64;
    const Limb lo = static_cast<Limb>(m), hi = static_cast<Limb>(m >> 64);
    Limb w[4] = {lo << b, b ? (hi << b) | (lo >> (64 - b)) : hi, b ? hi >> (64 - b) : Limb(0), 0};
    int n = w[2] ? 3 : w[1] ? 2 : 1;
    if (w[n - 1] >> 63) w[n++] = 0;  // room for the sign bit
    if (q >= N || q + n > N) throw WideIntOverflow();
    for (int k = 0; k < q; ++k) r.d_[k] = 0;
    for (int k = 0; k < n; ++k) r.d_[q + k] = w[k];
    r.n_ = q + n;
    if (negative) r.negate_in_place();
    return r;
  }

  /// The 128-bit two's complement pattern v in `limbs` limbs (1 or 2; with 1, v must fit in a
  /// signed 64-bit limb), zero included (the entries of a matrix, zeros too, get one size).
  static WideInt from_signed(unsigned __int128 v, int limbs) {
    WideInt r;
    r.d_[0] = static_cast<Limb>(v);
    r.d_[1] = static_cast<Limb>(v >> 64);
    r.n_ = limbs;
    return r;
  }

  /// This value held in `limbs` limbs (sign-extended; `limbs` at least limbs()). The operations
  /// take their sizes from their operands' limbs, not from the values, so an item whose entries
  /// are all widened to one size runs the same kernels at every entry (predicted branches).
  WideInt widened(int limbs) const {
    if (limbs > N) throw WideIntOverflow();
    WideInt r(*this);
    const Limb s = sign_mask();
    for (int k = n_; k < limbs; ++k) r.d_[k] = s;
    r.n_ = std::max(n_, limbs);
    return r;
  }

  int sign() const {
    if (n_ == 0) return 0;
    if (d_[n_ - 1] >> 63) return -1;
    for (int k = 0; k < n_; ++k)
      if (d_[k]) return 1;
    return 0;
  }
  /// Limbs held: two's complement, the value is d[0 .. limbs()) sign-extended. An upper bound
  /// of the limbs the value needs (an operation's result holds what its operands' sizes allow).
  int limbs() const { return n_; }
  /// Bits of the magnitude (0 for zero).
  int bits() const {
    Limb m[N];
    const int n = magnitude(m);
    return n ? (n - 1) * 64 + 64 - __builtin_clzll(m[n - 1]) : 0;
  }

  /// The value as a GMP rational (exactly).
  Rational to_rational() const {
    boost::multiprecision::mpz_int z;
    to_mpz(z.backend().data());
    return Rational(z);
  }
  /// The value as a GMP integer.
  void to_mpz(mpz_t out) const {
    Limb m[N];
    const int n = magnitude(m);
    if (n == 0) {
      mpz_set_ui(out, 0);
      return;
    }
    mpz_import(out, static_cast<std::size_t>(n), -1, sizeof(Limb), 0, 0, m);
    if (d_[n_ - 1] >> 63) mpz_neg(out, out);
  }

  /// The product in an + bn limbs: the unsigned product of the two limb patterns, less the
  /// pattern of b at limb an where a < 0 and that of a at limb bn where b < 0 (two's complement:
  /// a = U(a) - [a < 0] 2^(64 an)); modulo 2^(64 (an + bn)) that is a b, which fits.
  friend WideInt operator*(const WideInt& a, const WideInt& b) {
    WideInt r;
    if (!a.n_ || !b.n_) return r;
    const WideInt& x = a.n_ >= b.n_ ? a : b;
    const WideInt& y = a.n_ >= b.n_ ? b : a;
    const int xn = x.n_, yn = y.n_, n = xn + yn;
    if (n <= N) {
      wide_detail::signed_mul(r.d_, x.d_, xn, y.d_, yn);
      r.n_ = n;
      return r;
    }
    Limb t[2 * N];  // may still fit: the whole product, then the limbs that are only sign
    wide_detail::signed_mul(t, x.d_, xn, y.d_, yn);
    const int m = significant_limbs(t, n);
    if (m > N) throw WideIntOverflow();
    for (int k = 0; k < m; ++k) r.d_[k] = t[k];
    r.n_ = m;
    return r;
  }
  friend WideInt operator+(const WideInt& a, const WideInt& b) { return add<false>(a, b); }
  friend WideInt operator-(const WideInt& a, const WideInt& b) { return add<true>(a, b); }
  WideInt operator-() const { return add<true>(WideInt(), *this); }
  WideInt operator+() const { return *this; }
  WideInt& operator+=(const WideInt& b) { return *this = *this + b; }
  WideInt& operator-=(const WideInt& b) { return *this = *this - b; }
  WideInt& operator*=(const WideInt& b) { return *this = *this * b; }

  friend bool operator==(const WideInt& a, const WideInt& b) { return compare(a, b) == 0; }
  friend bool operator!=(const WideInt& a, const WideInt& b) { return compare(a, b) != 0; }
  friend bool operator<(const WideInt& a, const WideInt& b) { return compare(a, b) < 0; }
  friend bool operator>(const WideInt& a, const WideInt& b) { return compare(a, b) > 0; }
  friend bool operator<=(const WideInt& a, const WideInt& b) { return compare(a, b) <= 0; }
  friend bool operator>=(const WideInt& a, const WideInt& b) { return compare(a, b) >= 0; }

 private:
  /// All ones for a negative value, else zero (the limbs above limbs()).
  Limb sign_mask() const { return n_ ? static_cast<Limb>(static_cast<std::int64_t>(d_[n_ - 1]) >> 63) : 0; }
  /// The limbs in use (8-byte moves: they were just written that way).
  void copy_from(const WideInt& x) {
    detail::copy_prefix(d_, x.d_, x.n_);
    n_ = x.n_;
  }
  /// The fewest limbs that hold t[0 .. n) sign-extended.
  static int significant_limbs(const Limb* t, int n) {
    const Limb s = n ? static_cast<Limb>(static_cast<std::int64_t>(t[n - 1]) >> 63) : 0;
    while (n > 0 && t[n - 1] == s && (n == 1 ? s == 0 : (t[n - 2] >> 63) == (s & 1))) --n;
    return n;
  }
  /// |this| into m; its limbs (trimmed).
  int magnitude(Limb* m) const {
    const Limb s = sign_mask();
    unsigned char c = static_cast<unsigned char>(s & 1);
    for (int k = 0; k < n_; ++k) c = wide_detail::add_carry(c, d_[k] ^ s, 0, &m[k]);
    int n = n_;
    while (n > 0 && m[n - 1] == 0) --n;
    return n;
  }
  void negate_in_place() {
    unsigned char c = 1;
    for (int k = 0; k < n_; ++k) c = wide_detail::add_carry(c, ~d_[k], 0, &d_[k]);
  }
  /// a + b or a - b in max(an, bn) limbs, one more on a signed overflow.
  template <bool Sub> static WideInt add(const WideInt& a, const WideInt& b) {
    WideInt r;
    const int an = a.n_, bn = b.n_, n = std::max(an, bn);
    if (n == 0) return r;
    const Limb as = a.sign_mask(), bs0 = b.sign_mask();
    const Limb flip = Sub ? ~Limb(0) : 0;  // a - b = a + ~b + 1
    unsigned char c = Sub ? 1 : 0;
    const int m = std::min(an, bn);
    int k = 0;
    for (; k < m; ++k) c = wide_detail::add_carry(c, a.d_[k], b.d_[k] ^ flip, &r.d_[k]);
    for (; k < an; ++k) c = wide_detail::add_carry(c, a.d_[k], bs0 ^ flip, &r.d_[k]);
    for (; k < bn; ++k) c = wide_detail::add_carry(c, as, b.d_[k] ^ flip, &r.d_[k]);
    // overflow: the operands' signs agree and the result's differs; the true sum then has
    // the operands' sign in one more limb
    const Limb bs = bs0 ^ flip, rs = static_cast<Limb>(static_cast<std::int64_t>(r.d_[n - 1]) >> 63);
    r.n_ = n;
    if (as == bs && rs != as) {
      if (n >= N) throw WideIntOverflow();
      r.d_[n] = as;
      r.n_ = n + 1;
    }
    return r;
  }
  /// The sign of a - b (no overflow: computed one limb wider).
  static int compare(const WideInt& a, const WideInt& b) {
    const int n = std::max(a.n_, b.n_);
    const Limb as = a.sign_mask(), bs = b.sign_mask();
    // top limb first, as signed, then the lower limbs as unsigned
    if (as != bs) return as ? -1 : 1;
    for (int k = n - 1; k >= 0; --k) {
      const Limb x = k < a.n_ ? a.d_[k] : as, y = k < b.n_ ? b.d_[k] : bs;
      if (x != y) return x < y ? -1 : 1;
    }
    return 0;
  }

  int n_ = 0;  ///< limbs held: the value is d_[0 .. n_) in two's complement (0 limbs: zero)
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

/// x[k] 2^-e as 128-bit integers, e <= the binary exponent of every x[k] (wide_from_doubles
/// takes the smallest): false, and out unspecified, when one needs more than 126 bits (a spread
/// of exponents beyond 73). `bits`: the most bits of a magnitude. Throws std::invalid_argument
/// for inf or NaN.
inline bool doubles_to_int128(const double* x, int n, int e, __int128* out, int& bits) {
  bits = 0;
  for (int k = 0; k < n; ++k) {
    std::uint64_t b;
    std::memcpy(&b, &x[k], sizeof b);
    std::uint64_t m = b & ((std::uint64_t(1) << 52) - 1);
    if (((b >> 52) & 0x7ff) != 0) m |= std::uint64_t(1) << 52;
    if (m == 0) {
      out[k] = 0;
      continue;
    }
    const int shift = binary_exponent(x[k]) - e, mb = 64 - __builtin_clzll(m) + shift;
    if (shift < 0) throw std::invalid_argument("WideInt: exponent above the double's");
    if (mb > 126) return false;
    bits = std::max(bits, mb);
    const auto mag = static_cast<__int128>(static_cast<unsigned __int128>(m) << shift);
    out[k] = (b >> 63) ? -mag : mag;
  }
  return true;
}

/// The smallest binary exponent of x[0 .. n) (0 when all are zero).
inline int smallest_binary_exponent(const double* x, int n) {
  int e = binary_exponent(x[0]);
  for (int k = 1; k < n; ++k) e = std::min(e, binary_exponent(x[k]));
  return e == binary_exponent(0.0) ? 0 : e;
}

/// The doubles x[0 .. n) as integers: out[k] = x[k] 2^-e with e the smallest
/// binary exponent among them (one matrix's entries share one scale: a
/// positive factor, the results of the division-free formulas are
/// projective). Returns e; throws WideIntOverflow when an entry does not fit
/// in N limbs (a spread of exponents beyond them), std::invalid_argument for
/// inf or NaN. All zero: 0.
template <int N> int wide_from_doubles(const double* x, int n, WideInt<N>* out) {
  const int e = smallest_binary_exponent(x, n);
  // Every entry within 126 bits (a spread of exponents up to 73, as in every benchmark item):
  // shifted and signed in 128-bit integers, written as one or two limbs.
  constexpr int kFast = 16;
  __int128 v[kFast];
  int bits = 0;
  if (n <= kFast && doubles_to_int128(x, n, e, v, bits)) {
    const int limbs = bits + 1 > 64 ? 2 : 1;  // the magnitude and a sign bit
    for (int k = 0; k < n; ++k) out[k] = WideInt<N>::from_signed(static_cast<unsigned __int128>(v[k]), limbs);
    return e;
  }
  int limbs = 0;
  for (int k = 0; k < n; ++k) out[k] = wide_from_double<N>(x[k], e), limbs = std::max(limbs, out[k].limbs());
  for (int k = 0; k < n; ++k) out[k] = out[k].widened(limbs);
  return e;
}

namespace wide_detail {
/// 10^k for k = 0..38, as 128-bit integers, and the largest m with m 10^k < 2^126.
struct Pow10Table {
  unsigned __int128 p[39], below_126_bits[39];
  constexpr Pow10Table() : p(), below_126_bits() {
    p[0] = 1;
    for (int k = 1; k < 39; ++k) p[k] = p[k - 1] * 10;
    for (int k = 0; k < 39; ++k) below_126_bits[k] = ((static_cast<unsigned __int128>(1) << 126) - 1) / p[k];
  }
};
inline constexpr Pow10Table kPow10{};
}  // namespace wide_detail

/// m 10^shift as a 128-bit integer when it fits in 126 bits (shift >= 0): false otherwise.
inline bool decimal_to_int128(std::int64_t m, int shift, __int128& out) {
  if (shift < 0) throw std::invalid_argument("WideInt: negative decimal shift");
  const auto mag = static_cast<unsigned __int128>(m < 0 ? -static_cast<__int128>(m) : static_cast<__int128>(m));
  if (mag == 0) {
    out = 0;
    return true;
  }
  if (shift > 38 || mag > wide_detail::kPow10.below_126_bits[shift]) return false;
  const auto v = static_cast<__int128>(mag * wide_detail::kPow10.p[shift]);
  out = m < 0 ? -v : v;
  return true;
}

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
template <int N> struct NumTraits<qverify::WideInt<N>> : qverify::ExactNumTraits<qverify::WideInt<N>, 1, 4, 8> {};

}  // namespace Eigen
