#pragma once
/// \file digit_pack.hpp
/// `DigitPack<D>`: the exact integers of W items at once, one per SIMD lane (W the build's
/// width in 64-bit lanes, as DoublePack: 4 with AVX2, 8 with AVX-512), as a scalar of the
/// generic core. The direct formulas run on W items in one instantiation, as they do on
/// DoublePack: `tangent_cone<DigitPack<24>>` is the same template as `tangent_cone<double>`.
///
/// What it is for: exact results from inputs that are doubles or decimal text (as WideInt,
/// wide_int.hpp: each matrix's entries shifted to a common exponent are integers, and the
/// division-free direct formulas need only + - *), without WideInt's cost per operation: a
/// sign, a size and a kernel chosen per operand, an 88-byte result per operation. Here an
/// operation is a fixed sequence of vector instructions for all W items.
///
/// Representation. A lane's value is sum_k d_k 2^(28 k), k < n, with signed 64-bit digits
/// d_k (radix 2^28, one vector of W digits per k). The digits are *lazy*: no carries are
/// propagated by + and -, which add digit by digit (|d| grows by at most a factor 2), and a
/// product is the convolution of the digit vectors, sum_{i+j=k} a_i b_j, each digit product
/// one 32 x 32 -> 64-bit signed multiply (VPMULDQ) of all lanes. The object tracks, the same
/// for all lanes (structural, never per value, so no branch depends on a lane's value):
///   - n, the digits in use;
///   - dig: every |d_k| <= 2^dig;
///   - bits: every lane's |value| < 2^bits.
/// Exactness is a matter of these bounds: a product needs |a_i|, |b_j| < 2^31 (the multiply
/// reads 32 bits) and min(an, bn) 2^(dig_a + dig_b) < 2^63 (the sum of a digit's products
/// fits); + needs 2^(dig + 1) < 2^63. An operand that would break them is first
/// normalized (carries propagated, in place: the value does not change, hence `mutable`),
/// which brings every digit to [0, 2^28) but the top one, signed with |d| <= 2^28, and n
/// to ceil(bits / 28). A result beyond D digits throws DigitPackOverflow: nothing is
/// truncated (callers catch it, and take such items another way). Reading a value that is not
/// normalized rewrites its digits: such a DigitPack shared by threads needs a copy per thread,
/// as an unsynchronized cache would (a normalized one is only read).
///
/// Decisions (ScalarOps: a formula asks whether L_w = 0) are taken when every lane gives the
/// same answer and throw MixedLanes otherwise, as for DoublePack (batch/pack.hpp).

#include <qverify/batch/pack.hpp>
#include <qverify/core/scalar.hpp>
#include <qverify/exact/prefix_copy.hpp>
#include <qverify/exact/scalars.hpp>

#include <gmp.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace qverify {

/// A DigitPack result needed more digits than it has.
struct DigitPackOverflow : std::overflow_error {
  DigitPackOverflow() : std::overflow_error("DigitPack: result beyond its digits") {}
};

namespace digit_detail {

constexpr int kRadixBits = 28;
constexpr std::int64_t kRadixMask = (std::int64_t(1) << kRadixBits) - 1;
/// Lanes: as many 64-bit integers as the build's double pack holds doubles.
constexpr int kLanes = static_cast<int>(DoublePack::size());
typedef std::int64_t Lanes __attribute__((vector_size(kLanes * 8)));
typedef std::uint64_t ULanes __attribute__((vector_size(kLanes * 8)));

inline Lanes splat(std::int64_t v) { return Lanes{} + v; }

/// Lane-wise (low 32 bits of a, signed) * (low 32 bits of b, signed), 64-bit products.
/// (A template, so that the branches for other widths are discarded.)
template <class V = Lanes> inline V mul32(V a, V b) {
#if defined(__AVX512F__)
  // (the zero-masking form: GCC 12.2's _mm512_mul_epi32 trips -Wmaybe-uninitialized, GCC PR 105593)
  if constexpr (sizeof(V) == 64)
    return reinterpret_cast<V>(_mm512_maskz_mul_epi32(static_cast<__mmask8>(0xff), reinterpret_cast<__m512i>(a), reinterpret_cast<__m512i>(b)));
#endif
#if defined(__AVX2__)
  if constexpr (sizeof(V) == 32) return reinterpret_cast<V>(_mm256_mul_epi32(reinterpret_cast<__m256i>(a), reinterpret_cast<__m256i>(b)));
#endif
#if defined(__SSE4_1__)
  if constexpr (sizeof(V) == 16) return reinterpret_cast<V>(_mm_mul_epi32(reinterpret_cast<__m128i>(a), reinterpret_cast<__m128i>(b)));
#endif
  V r;
  for (int l = 0; l < kLanes; ++l)
    r[l] = static_cast<std::int64_t>(static_cast<std::int32_t>(a[l])) * static_cast<std::int32_t>(b[l]);
  return r;
}

/// Lane-wise logical shifts by per-lane counts; a count of 64 or more (a negative count read
/// as unsigned included) gives 0, as the AVX2 and AVX-512 instructions do.
template <class V = ULanes> inline V shift_right(V a, V count) {
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64)  // (zero-masking: GCC PR 105593, as in mul32)
    return reinterpret_cast<V>(_mm512_maskz_srlv_epi64(static_cast<__mmask8>(0xff), reinterpret_cast<__m512i>(a), reinterpret_cast<__m512i>(count)));
#endif
#if defined(__AVX2__)
  if constexpr (sizeof(V) == 32) return reinterpret_cast<V>(_mm256_srlv_epi64(reinterpret_cast<__m256i>(a), reinterpret_cast<__m256i>(count)));
#endif
  V r;
  for (int l = 0; l < kLanes; ++l) r[l] = count[l] < 64 ? a[l] >> count[l] : 0;
  return r;
}
template <class V = ULanes> inline V shift_left(V a, V count) {
#if defined(__AVX512F__)
  if constexpr (sizeof(V) == 64)  // (zero-masking: GCC PR 105593, as in mul32)
    return reinterpret_cast<V>(_mm512_maskz_sllv_epi64(static_cast<__mmask8>(0xff), reinterpret_cast<__m512i>(a), reinterpret_cast<__m512i>(count)));
#endif
#if defined(__AVX2__)
  if constexpr (sizeof(V) == 32) return reinterpret_cast<V>(_mm256_sllv_epi64(reinterpret_cast<__m256i>(a), reinterpret_cast<__m256i>(count)));
#endif
  V r;
  for (int l = 0; l < kLanes; ++l) r[l] = count[l] < 64 ? a[l] << count[l] : 0;
  return r;
}

/// floor(t / 2^28) lane-wise, for every t: the logical shift of t + 2^63 (AVX2 has no 64-bit
/// arithmetic shift; t + 2^63 never wraps as unsigned), less 2^35.
inline Lanes carry_of(Lanes t) {
  const ULanes biased = reinterpret_cast<ULanes>(t) + (ULanes{} + (std::uint64_t(1) << 63));
  return reinterpret_cast<Lanes>(biased >> kRadixBits) - splat(std::int64_t(1) << (63 - kRadixBits));
}

/// r[0 .. an + bn - 1) = the convolution of a[0 .. an) and b[0 .. bn): r_k = sum_{i+j=k} a_i b_j,
/// one 32 x 32 -> 64-bit product per term, each r_k summed in a register. Unrolled for fixed sizes
/// (every item of a block and every block of a batch run the same ones: the sizes are structural).
template <int AN, int BN> inline void conv_fixed(Lanes* __restrict r, const Lanes* __restrict a, const Lanes* __restrict b) {
#pragma GCC unroll 64
  for (int k = 0; k < AN + BN - 1; ++k) {
    Lanes acc{};
#pragma GCC unroll 16
    for (int j = 0; j < BN; ++j)
      if (k - j >= 0 && k - j < AN) acc += mul32(a[k - j], b[j]);
    r[k] = acc;
  }
}

inline void conv_any(Lanes* r, const Lanes* a, int an, const Lanes* b, int bn) {
  for (int k = 0; k < an + bn - 1; ++k) {
    const int lo = std::max(0, k - bn + 1), hi = std::min(k, an - 1);
    Lanes acc = mul32(a[lo], b[k - lo]);
    for (int i = lo + 1; i <= hi; ++i) acc += mul32(a[i], b[k - i]);
    r[k] = acc;
  }
}

/// The convolution for an >= bn >= 1: a jump to the unrolled kernel of these sizes, those the
/// direct formulas take on doubles and decimal text (counted on 4096 items of each: a factor of
/// 3 to 5 digits beside one of up to 17, or two of 6 to 9), the loop for the rest. Every kernel
/// listed is compiled: a table of every pair to 21 x 5 took a sanitizer build half a minute per
/// file that multiplies DigitPacks.
inline void conv(Lanes* r, const Lanes* a, int an, const Lanes* b, int bn) {
  switch (an * 64 + bn) {
#define QVERIFY_DIGIT_CONV(x, y) \
  case (x) * 64 + (y): conv_fixed<x, y>(r, a, b); return;
    QVERIFY_DIGIT_CONV(3, 3) QVERIFY_DIGIT_CONV(4, 3) QVERIFY_DIGIT_CONV(5, 3) QVERIFY_DIGIT_CONV(6, 3)
    QVERIFY_DIGIT_CONV(7, 3) QVERIFY_DIGIT_CONV(8, 3) QVERIFY_DIGIT_CONV(9, 3)
    QVERIFY_DIGIT_CONV(10, 3) QVERIFY_DIGIT_CONV(11, 3) QVERIFY_DIGIT_CONV(12, 3)
    QVERIFY_DIGIT_CONV(13, 3) QVERIFY_DIGIT_CONV(14, 3) QVERIFY_DIGIT_CONV(4, 4)
    QVERIFY_DIGIT_CONV(5, 4) QVERIFY_DIGIT_CONV(6, 4) QVERIFY_DIGIT_CONV(7, 4) QVERIFY_DIGIT_CONV(8, 4)
    QVERIFY_DIGIT_CONV(9, 4) QVERIFY_DIGIT_CONV(10, 4) QVERIFY_DIGIT_CONV(11, 4)
    QVERIFY_DIGIT_CONV(12, 4) QVERIFY_DIGIT_CONV(13, 4) QVERIFY_DIGIT_CONV(14, 4)
    QVERIFY_DIGIT_CONV(15, 4) QVERIFY_DIGIT_CONV(16, 4) QVERIFY_DIGIT_CONV(17, 4)
    QVERIFY_DIGIT_CONV(5, 5) QVERIFY_DIGIT_CONV(6, 5) QVERIFY_DIGIT_CONV(7, 5) QVERIFY_DIGIT_CONV(8, 5)
    QVERIFY_DIGIT_CONV(9, 5) QVERIFY_DIGIT_CONV(10, 5) QVERIFY_DIGIT_CONV(11, 5)
    QVERIFY_DIGIT_CONV(12, 5) QVERIFY_DIGIT_CONV(13, 5) QVERIFY_DIGIT_CONV(14, 5)
    QVERIFY_DIGIT_CONV(15, 5) QVERIFY_DIGIT_CONV(16, 5) QVERIFY_DIGIT_CONV(17, 5)
    QVERIFY_DIGIT_CONV(6, 6) QVERIFY_DIGIT_CONV(7, 6) QVERIFY_DIGIT_CONV(7, 7) QVERIFY_DIGIT_CONV(8, 6)
    QVERIFY_DIGIT_CONV(8, 7) QVERIFY_DIGIT_CONV(8, 8) QVERIFY_DIGIT_CONV(9, 8) QVERIFY_DIGIT_CONV(9, 9)
#undef QVERIFY_DIGIT_CONV
    default: conv_any(r, a, an, b, bn);
  }
}

/// ceil(log2(m)) for m >= 1.
constexpr int ceil_log2(int m) {
  int r = 0;
  while ((1 << r) < m) ++r;
  return r;
}

}  // namespace digit_detail

template <int D> class DigitPack {
  static_assert(D >= 2 && D <= 32, "DigitPack: 2 to 32 digits");

 public:
  using Lanes = digit_detail::Lanes;
  static constexpr int lanes = digit_detail::kLanes;
  static constexpr int radix_bits = digit_detail::kRadixBits;
  static constexpr int max_digits = D;
  /// Every lane's value below 2^max_bits fits (D normalized digits hold 28 D bits; a bound, not
  /// what an operation's intermediate digits may need).
  static constexpr int max_bits = radix_bits * D;

  /// Zero in every lane. User-provided, so that a value-initialization does not fill the digits.
  DigitPack() {}
  /// v in every lane.
  DigitPack(int v) : DigitPack(static_cast<long long>(v)) {}
  DigitPack(long v) : DigitPack(static_cast<long long>(v)) {}
  DigitPack(long long v) {
    __int128 w[lanes];
    for (int l = 0; l < lanes; ++l) w[l] = v;
    *this = from_lanes(w);
  }
  /// Copies the digits in use only.
  DigitPack(const DigitPack& x) { copy_from(x); }
  DigitPack& operator=(const DigitPack& x) {
    if (this != &x) copy_from(x);
    return *this;
  }

  /// The bits of the largest magnitude among v[0 .. count).
  static int bits_of(const __int128* v, int count) {
    int bits = 0;
    for (int l = 0; l < count; ++l) {
      const unsigned __int128 m = v[l] < 0 ? -static_cast<unsigned __int128>(v[l]) : static_cast<unsigned __int128>(v[l]);
      const auto hi = static_cast<std::uint64_t>(m >> 64), lo = static_cast<std::uint64_t>(m);
      bits = std::max(bits, hi ? 128 - __builtin_clzll(hi) : lo ? 64 - __builtin_clzll(lo) : 0);
    }
    return bits;
  }

  /// Lane l holds v[l], exactly, in normalized digits for the bound |v| < 2^bits (at least
  /// the values' own; entries of one matrix given one bound get one size, so that every item
  /// of a block runs the same kernels).
  static DigitPack from_lanes(const __int128 (&v)[lanes], int bits) {
    DigitPack r;
    if (bits < 0 || bits > 127 || bits_of(v, lanes) > bits) throw std::invalid_argument("DigitPack: a value beyond its bound");
    if (bits == 0) return r;
    const int n = digits_for(bits);
    if (n > D) throw DigitPackOverflow();
    Lanes lo, hi;  // the two's complement halves of every lane
    for (int l = 0; l < lanes; ++l) lo[l] = static_cast<std::int64_t>(v[l]), hi[l] = static_cast<std::int64_t>(v[l] >> 64);
    const auto ulo = reinterpret_cast<digit_detail::ULanes>(lo), uhi = reinterpret_cast<digit_detail::ULanes>(hi);
    for (int k = 0; k < n; ++k) {
      const int at = radix_bits * k;  // bits [at, at + 28) of the 128-bit pattern
      Lanes digit;
      if (k + 1 == n) {  // the top digit: everything above, signed (an arithmetic shift)
        digit = at >= 64 ? hi >> (at - 64) : at == 0 ? lo : reinterpret_cast<Lanes>((ulo >> at) | (uhi << (64 - at)));
      } else {
        const digit_detail::ULanes u = at >= 64 ? uhi >> (at - 64) : at + radix_bits <= 64 ? ulo >> at : (ulo >> at) | (uhi << (64 - at));
        digit = reinterpret_cast<Lanes>(u) & digit_detail::kRadixMask;
      }
      r.d_[k] = digit;
    }
    r.n_ = n;
    r.dig_ = radix_bits;
    r.bits_ = bits;
    r.canonical_ = true;
    return r;
  }
  /// Lane l holds v[l], exactly (normalized digits for the values' own bound).
  static DigitPack from_lanes(const __int128 (&v)[lanes]) { return from_lanes(v, bits_of(v, lanes)); }

  /// Entries of W items read from doubles: lane l of out[k] is items[l][k] 2^-e[l], exactly, with
  /// e[l] the smallest binary exponent among item l's `count` entries (a positive factor per
  /// item: the division-free formulas are projective). All lanes' entries get one digit count,
  /// from the largest spread of exponents. False (out unspecified) when an item's spread needs
  /// more than 126 bits or the digits; std::invalid_argument for inf or NaN. Vectorized: the
  /// significand's digits are variable shifts of it, one per digit.
  static bool from_doubles(const double* const (&items)[lanes], int count, DigitPack* out, int (&e)[lanes]) {
    using U = digit_detail::ULanes;
    constexpr int kMax = 16;
    if (count > kMax) throw std::invalid_argument("DigitPack::from_doubles: at most 16 entries");
    U m[kMax];
    Lanes ex[kMax], negative[kMax];
    const Lanes none = digit_detail::splat(std::int64_t(1) << 20);  // a zero's exponent: never the smallest
    Lanes e0 = none;
    for (int k = 0; k < count; ++k) {
      U b;
      for (int l = 0; l < lanes; ++l) {
        std::uint64_t bits_of_x;  // (clang takes no address of a vector element)
        std::memcpy(&bits_of_x, &items[l][k], sizeof(double));
        b[l] = bits_of_x;
      }
      const Lanes biased = reinterpret_cast<Lanes>((b >> 52) & (U{} + 0x7ff));
      for (int l = 0; l < lanes; ++l)
        if (biased[l] == 0x7ff) throw std::invalid_argument("DigitPack: not a finite double");
      const U fraction = b & (U{} + ((std::uint64_t(1) << 52) - 1));
      m[k] = fraction | reinterpret_cast<U>((biased != 0) & (Lanes{} + (std::int64_t(1) << 52)));
      ex[k] = biased == 0 ? Lanes{} - 1074 : biased - 1075;
      ex[k] = m[k] == 0 ? none : ex[k];
      negative[k] = reinterpret_cast<Lanes>(b) < 0;  // all ones where the sign bit is set
      e0 = ex[k] < e0 ? ex[k] : e0;
    }
    e0 = e0 == none ? Lanes{} : e0;
    int bits = 0;
    for (int l = 0; l < lanes; ++l) {
      e[l] = static_cast<int>(e0[l]);
      for (int k = 0; k < count; ++k)
        if (m[k][l] != 0) bits = std::max(bits, 53 + static_cast<int>(ex[k][l] - e0[l]));
    }
    if (bits > 126) return false;
    const int n = digits_for(bits);
    if (n > D) return false;
    for (int k = 0; k < count; ++k) {
      DigitPack& r = out[k];
      const U shift = reinterpret_cast<U>(ex[k] - e0);
      for (int j = 0; j < n; ++j) {
        // bits [28 j, 28 j + 28) of m << shift: m >> (28 j - shift) or m << (shift - 28 j),
        // whichever count is not negative (the other, read as unsigned, gives 0)
        const U at = U{} + static_cast<std::uint64_t>(radix_bits * j);
        const U u = digit_detail::shift_right(m[k], at - shift) | digit_detail::shift_left(m[k], shift - at);
        const Lanes digit = reinterpret_cast<Lanes>(u) & digit_detail::kRadixMask;
        r.d_[j] = (digit ^ negative[k]) - negative[k];  // negated where the entry is negative
      }
      r.n_ = n;
      r.dig_ = radix_bits;
      r.bits_ = bits;
    }
    return true;
  }

  /// Normalized digits for a bound of `bits` bits: the top digit t = floor(v / 2^(28 (n - 1)))
  /// then has |t| <= 2^(bits - 28 (n - 1)) <= 2^28.
  static constexpr int digits_for(int bits) { return bits <= 0 ? 0 : (bits + radix_bits - 1) / radix_bits; }

  /// Digits in use (the same for every lane).
  int digits() const { return n_; }
  /// The digits in use, lane-major: out[k W + l] = digit k of lane l (digits() W numbers).
  void copy_digits(std::int64_t* out) const { std::memcpy(out, d_, sizeof(Lanes) * static_cast<std::size_t>(n_)); }
  /// Digit k of lane l (k < digits()): lazy unless normalized.
  std::int64_t digit(int k, int lane) const { return d_[k][lane]; }
  /// A bound on every lane's magnitude: |value| < 2^bound_bits().
  int bound_bits() const { return bits_; }

  /// Carries propagated: the canonical form, digits in [0, 2^28) but the top one (signed, |d|
  /// <= 2^28), digits_for(bits) of them (no operation holds more: a product's an + bn - 1 digits
  /// are at most ceil((x + y) / 28) for bounds of x and y bits). The value does not change. A
  /// canonical value is left as it is, nothing written: reading it is safe from several threads.
  /// A top digit beyond 2^28 would mean a bit bound below the value, a bug of this class:
  /// std::logic_error, never a wrong digit.
  void normalize() const {
    if (canonical_ || n_ == 0) return;
    const int target = std::max(n_, digits_for(bits_));
    if (target > D) throw DigitPackOverflow();
    Lanes c{};
    for (int k = 0; k + 1 < target; ++k) {
      const Lanes t = (k < n_ ? d_[k] : Lanes{}) + c;
      c = digit_detail::carry_of(t);
      d_[k] = t & digit_detail::kRadixMask;
    }
    const Lanes top = (target - 1 < n_ ? d_[target - 1] : Lanes{}) + c;
    const std::int64_t limit = std::int64_t(1) << radix_bits;
    for (int l = 0; l < lanes; ++l)
      if (top[l] > limit || top[l] < -limit) throw std::logic_error("DigitPack: a value beyond its bit bound");
    d_[target - 1] = top;
    n_ = target;
    dig_ = radix_bits;
    canonical_ = true;
  }

  /// Lane l's value as a GMP rational (exactly).
  Rational to_rational(int lane) const {
    boost::multiprecision::mpz_int z;
    to_mpz(lane, z.backend().data());
    return Rational(z);
  }
  /// Lane l's value as a GMP integer.
  void to_mpz(int lane, mpz_t out) const {
    mpz_set_ui(out, 0);
    if (n_ == 0) return;
    normalize();
    mpz_set_si(out, static_cast<long>(d_[n_ - 1][lane]));
    for (int k = n_ - 2; k >= 0; --k) {
      mpz_mul_2exp(out, out, radix_bits);
      mpz_add_ui(out, out, static_cast<unsigned long>(d_[k][lane]));
    }
  }
  /// The sign of every lane's value: -1, 0 or 1.
  void signs(int (&s)[lanes]) const {
    normalize();
    for (int l = 0; l < lanes; ++l) {
      s[l] = 0;
      if (n_ == 0) continue;
      const std::int64_t top = d_[n_ - 1][l];
      if (top != 0) {
        s[l] = top < 0 ? -1 : 1;
        continue;
      }
      for (int k = 0; k + 1 < n_; ++k)
        if (d_[k][l] != 0) s[l] = 1;  // the lower digits are non-negative
    }
  }

  friend DigitPack operator+(const DigitPack& a, const DigitPack& b) { return add<false>(a, b); }
  friend DigitPack operator-(const DigitPack& a, const DigitPack& b) { return add<true>(a, b); }
  DigitPack operator-() const {
    DigitPack r;
    for (int k = 0; k < n_; ++k) r.d_[k] = -d_[k];
    r.n_ = n_, r.dig_ = dig_, r.bits_ = bits_;
    return r;
  }
  DigitPack operator+() const { return *this; }
  /// In place: no result to copy (ordered_dot sums with +=).
  DigitPack& operator+=(const DigitPack& b) { return add_in_place<false>(b); }
  DigitPack& operator-=(const DigitPack& b) { return add_in_place<true>(b); }
  DigitPack& operator*=(const DigitPack& b) { return *this = *this * b; }

  /// The convolution of the digit vectors, each output digit summed in a register.
  friend DigitPack operator*(const DigitPack& a, const DigitPack& b) {
    DigitPack r;
    if (a.n_ == 0 || b.n_ == 0) return r;
    // the multiply reads 32 bits of each digit, and a digit's m products must sum below 2^63
    if (a.dig_ > 30) a.normalize();
    if (b.dig_ > 30) b.normalize();
    while (a.dig_ + b.dig_ + digit_detail::ceil_log2(std::min(a.n_, b.n_)) > 62)
      (a.dig_ >= b.dig_ ? a : b).normalize();
    const int an = a.n_, bn = b.n_, n = an + bn - 1;
    if (n > D) throw DigitPackOverflow();
    if (an >= bn) digit_detail::conv(r.d_, a.d_, an, b.d_, bn);
    else digit_detail::conv(r.d_, b.d_, bn, a.d_, an);
    r.n_ = n;
    r.dig_ = a.dig_ + b.dig_ + digit_detail::ceil_log2(std::min(an, bn));
    r.bits_ = a.bits_ + b.bits_;
    return r;
  }

 private:
  /// The digits in use (a loop of a variable count became a call to memmove).
  void copy_from(const DigitPack& x) {
    detail::copy_prefix(d_, x.d_, x.n_);
    n_ = x.n_, dig_ = x.dig_, bits_ = x.bits_, canonical_ = x.canonical_;
  }
  template <bool Sub> DigitPack& add_in_place(const DigitPack& b) {
    if (b.n_ == 0) return *this;
    if (n_ == 0) return *this = Sub ? -b : b;
    while (std::max(dig_, b.dig_) + 1 > 62) (dig_ >= b.dig_ ? *this : b).normalize();
    const int m = std::min(n_, b.n_);
    int k = 0;
    for (; k < m; ++k) d_[k] = Sub ? d_[k] - b.d_[k] : d_[k] + b.d_[k];
    for (; k < b.n_; ++k) d_[k] = Sub ? -b.d_[k] : b.d_[k];
    n_ = std::max(n_, b.n_);
    canonical_ = false;
    dig_ = std::max(dig_, b.dig_) + 1;
    bits_ = std::max(bits_, b.bits_) + 1;
    return *this;
  }
  /// a + b or a - b digit by digit (no carries).
  template <bool Sub> static DigitPack add(const DigitPack& a, const DigitPack& b) {
    if (a.n_ == 0) return Sub ? -b : b;
    if (b.n_ == 0) return a;
    while (std::max(a.dig_, b.dig_) + 1 > 62) (a.dig_ >= b.dig_ ? a : b).normalize();
    DigitPack r;
    const int m = std::min(a.n_, b.n_);
    int k = 0;
    for (; k < m; ++k) r.d_[k] = Sub ? a.d_[k] - b.d_[k] : a.d_[k] + b.d_[k];
    for (; k < a.n_; ++k) r.d_[k] = a.d_[k];
    for (; k < b.n_; ++k) r.d_[k] = Sub ? -b.d_[k] : b.d_[k];
    r.n_ = std::max(a.n_, b.n_);
    r.dig_ = std::max(a.dig_, b.dig_) + 1;
    r.bits_ = std::max(a.bits_, b.bits_) + 1;
    return r;
  }

  // Bounds the same for every lane; normalize() changes the form, never the value.
  mutable int n_ = 0;     ///< digits in use (none: zero)
  mutable int dig_ = 0;   ///< every |digit| <= 2^dig_
  mutable bool canonical_ = false;  ///< the digits are normalize()'s (lower ones in [0, 2^28))
  int bits_ = 0;          ///< every |value| < 2^bits_
  mutable Lanes d_[D];
};

/// Decisions on a DigitPack: the one answer of all lanes, or MixedLanes (batch/pack.hpp).
template <int D> struct ScalarOps<DigitPack<D>> {
  using P = DigitPack<D>;
  static constexpr bool interval = false;
  static bool exact() { return true; }
  static bool less(const P& a, const P& b) {
    int s[P::lanes];
    (a - b).signs(s);
    int below = 0;
    for (int l = 0; l < P::lanes; ++l) below += s[l] < 0;
    if (below == 0 || below == P::lanes) return below != 0;
    throw MixedLanes{};
  }
  static bool is_zero(const P& a) {
    int s[P::lanes];
    a.signs(s);
    int zeros = 0;
    for (int l = 0; l < P::lanes; ++l) zeros += s[l] == 0;
    if (zeros == 0 || zeros == P::lanes) return zeros != 0;
    throw MixedLanes{};
  }
  static bool finite(const P&) { return true; }
};

}  // namespace qverify

namespace Eigen {

/// DigitPack is exact: epsilon 0.
template <int D> struct NumTraits<qverify::DigitPack<D>> : qverify::ExactNumTraits<qverify::DigitPack<D>, 1, 4, 16> {};

}  // namespace Eigen
