#pragma once
/// \file interval_pack.hpp
/// Certified intervals W items at a time: the batch API (batch/batch.hpp) runs
/// the generic direct formulas on IntervalPack, W = DoublePack::size()
/// intervals per operation, for batches of CGAL::Interval_nt.
///
/// Representation and rounding. An interval [lo, hi] is stored, like CGAL's
/// Interval_nt, as (-lo, hi): with the rounding mode upward (the batch sets it
/// for the run of packs) every bound is one upward-rounded operation, with no
/// mode switch:
///   a + b = (a.nlo + b.nlo, a.hi + b.hi)
///   a - b = (a.nlo + b.hi,  a.hi + b.nlo)
///   a * b: hi  = max(lo_a lo_b, lo_a hi_b, hi_a lo_b, hi_a hi_b)   (four corners,
///          nlo = max(-(the same four products))                     each rounded up;
///     with AVX or AVX-512 only the two corners that can be extreme are formed, chosen
///     by the signs of lo_a and hi_a: the same bounds in 4 products instead of 8)
///     where every negated corner is formed as a product of exactly negated
///     operands (nlo_a * lo_b = -(lo_a lo_b)), the negations hidden from the
///     optimiser (`opaque`): under round-to-nearest (-x) y = -(x y), upward it
///     is not, and a compiler may not be trusted to know which mode is set;
///   a / b for b > 0: hi = max(hi_a / lo_b, hi_a / hi_b), nlo = max(nlo_a / lo_b,
///     nlo_a / hi_b) (a / b is monotone in each argument, so these corners are
///     the extremes); b < 0 via a / b = (-a) / (-b). A divisor that may contain
///     0 gives up (MixedLanes): the batch computes that block item by item with
///     CGAL's Interval_nt, which returns the whole line.
/// These are CGAL's own corner formulas ("brutal" multiplication), lane-wise.
///
/// Why the result is certified. With finite inputs (checked at load) a NaN can
/// only arise from inf - inf, 0 * inf, 0 / 0 or inf / inf, each of which
/// raises the IEEE invalid flag; max() of a NaN raises it too. The batch clears
/// the flag before a span of packs and recomputes the span item by item (CGAL)
/// when it is raised. Without NaN every bound above is a correctly directed
/// rounding of an exact corner value, hence an enclosure; infinite bounds are
/// valid enclosures. tests/core/test_batch.cpp (the "[pack]" cases) checks packs
/// against CGAL bound for bound and against exact results.

#include <qverify/batch/batch.hpp>
#include <qverify/exact/interval.hpp>

#include <cfenv>
#include <type_traits>

namespace qverify {

/// W intervals (-lo, hi); arithmetic requires the rounding mode upward.
///
/// Every constant and every negation that enters a product passes through
/// `opaque`: the optimiser then cannot apply a rewrite that holds only under
/// round-to-nearest, e.g. fold (-2) / x into -(2 / x) (found by the tests:
/// folding the constant of k = 2 / (n.n) narrowed a bound by an ulp). The
/// operations themselves are sums, products, quotients and max of such
/// values, which no compiler rewrites without -ffast-math; the tests compare
/// every operation and whole batches with CGAL bound for bound.
struct IntervalPack {
  DoublePack nlo, hi;  ///< -lower bounds, upper bounds

  IntervalPack() = default;
  IntervalPack(const DoublePack& minus_lo, const DoublePack& up) : nlo(minus_lo), hi(up) {}
  /// A small integer constant (the generic code's S(0), S(2)), exact in double.
  template <class I, std::enable_if_t<std::is_integral_v<I>, int> = 0>
  IntervalPack(I v) : IntervalPack(static_cast<double>(v)) {}
  /// The point interval [v, v] in every lane (hidden from constant folding).
  explicit IntervalPack(double v) : nlo(opaque(DoublePack(-v))), hi(opaque(DoublePack(v))) {}

  DoublePack lower() const { return -nlo; }

  friend IntervalPack operator-(const IntervalPack& a) { return {a.hi, a.nlo}; }
  friend IntervalPack operator+(const IntervalPack& a, const IntervalPack& b) { return {a.nlo + b.nlo, a.hi + b.hi}; }
  friend IntervalPack operator-(const IntervalPack& a, const IntervalPack& b) { return {a.nlo + b.hi, a.hi + b.nlo}; }
  friend IntervalPack operator*(const IntervalPack& a, const IntervalPack& b) {
    const DoublePack la = opaque(-a.nlo), lb = opaque(-b.nlo);
#if defined(__AVX__)
    // Sign-selected corners (two products per bound): for a fixed x the largest x y is
    // x hi_b when x >= 0 and x lo_b when x < 0, the largest -x y is (-x) lo_b when
    // x >= 0 and (-x) hi_b when x < 0; the extremes over a lie at x = lo_a or hi_a.
    // BLENDVPD (AVX) or a mask blend on the sign bits (AVX-512) selects by the sign bit
    // of x (-0 counts as negative: the product is 0 either way).
    const DoublePack nha = opaque(-a.hi);
    auto pick = [](const DoublePack& x, const DoublePack& if_nonneg, const DoublePack& if_neg) {
#if QVERIFY_PACK_512  // (one 512-bit register: pack.hpp)
      const __mmask8 negative = _mm512_cmplt_epi64_mask(_mm512_castpd_si512(static_cast<__m512d>(x)), _mm512_setzero_si512());
      return DoublePack(_mm512_mask_blend_pd(negative, static_cast<__m512d>(if_nonneg), static_cast<__m512d>(if_neg)));
#else
      return DoublePack(_mm256_blendv_pd(static_cast<__m256d>(if_nonneg), static_cast<__m256d>(if_neg),
                                         static_cast<__m256d>(x)));
#endif
    };
    const DoublePack up = pack_max(a.hi * pick(a.hi, b.hi, lb), la * pick(la, b.hi, lb));
    const DoublePack down = pack_max(nha * pick(a.hi, lb, b.hi), a.nlo * pick(la, lb, b.hi));
#else
    // All four corners each way (CGAL's "brutal" product).
    const DoublePack nhb = opaque(-b.hi);
    const DoublePack up = pack_max(pack_max(a.nlo * b.nlo, la * b.hi), pack_max(a.hi * lb, a.hi * b.hi));
    const DoublePack down = pack_max(pack_max(a.nlo * lb, a.nlo * b.hi), pack_max(a.hi * b.nlo, a.hi * nhb));
#endif
    return {down, up};
  }
  friend IntervalPack operator/(const IntervalPack& a, const IntervalPack& b) {
    if (stdx::all_of(b.nlo < DoublePack(0))) {  // b > 0 in every lane
      const DoublePack lb = opaque(-b.nlo);
      return {pack_max(a.nlo / lb, a.nlo / b.hi), pack_max(a.hi / lb, a.hi / b.hi)};
    }
    if (stdx::all_of(b.hi < DoublePack(0))) return (-a) / (-b);
    throw MixedLanes{};  // 0 may lie in a divisor: item by item
  }
  IntervalPack& operator+=(const IntervalPack& b) { return *this = *this + b; }
  IntervalPack& operator-=(const IntervalPack& b) { return *this = *this - b; }
  IntervalPack& operator*=(const IntervalPack& b) { return *this = *this * b; }
  IntervalPack& operator/=(const IntervalPack& b) { return *this = *this / b; }
};

/// Interval semantics, as for Interval_nt (interval.hpp): a comparison holds
/// when it is certain; the lanes must agree (MixedLanes otherwise).
template <> struct ScalarOps<IntervalPack> {
  using P = IntervalPack;
  static constexpr bool interval = true;
  static bool exact() { return false; }
  static bool less(const P& a, const P& b) { return uniform(a.hi < b.lower()); }
  static bool is_zero(const P& a) { return uniform(a.nlo == DoublePack(0) && a.hi == DoublePack(0)); }
  /// |[lo, hi]| = [max(lo, -hi, 0), max(-lo, hi)]: one formula for the three cases (0 inside,
  /// nonnegative, nonpositive), by lane-wise max and exact negations. Not by masked assignment
  /// (stdx::where): clang 14 with libstdc++ 12's <experimental/simd> compiles where() on
  /// AVX-512 masks to nothing (measured: the assignment is dropped at -O0 and -O2).
  static P abs(const P& x) {
    const DoublePack lower = pack_max(pack_max(opaque(-x.nlo), opaque(-x.hi)), DoublePack(0));
    return P{opaque(-lower), pack_max(x.nlo, x.hi)};
  }
  static bool finite(const P& x) { return stdx::all_of(stdx::isfinite(x.nlo) && stdx::isfinite(x.hi)); }
};

/// Batches of CGAL intervals run on IntervalPack.
template <bool Protected> struct BatchLanes<CGAL::Interval_nt<Protected>> : ScalarLanes<CGAL::Interval_nt<Protected>> {
  using Scalar = CGAL::Interval_nt<Protected>;
  using Pack = IntervalPack;
  static constexpr int width = static_cast<int>(DoublePack::size());

  /// Entries 0..N-1 of `width` rows; a non-finite bound gives up (item by item).
  /// With SSE2 an Interval_nt is one register {-lo, hi}: W of them transpose
  /// into the packs (-lo, hi). A block of contiguous rows (every block of a
  /// batch) is read by whole vectors (load_pair_rows, pack.hpp) and written so
  /// where it is aligned as pack_aligned requires (stream_pair_rows); other
  /// rows go pair by pair (from/to_lane_pairs).
  template <int N> static void load(const Scalar* row0, Eigen::Index stride, Pack (&v)[N]) {
    prefetch_rows<N, width>(row0, stride);
#if defined(CGAL_USE_SSE2) && (QVERIFY_PACK_512 || defined(__AVX__))
    if constexpr (N % 2 == 0) {
      if (stride == N) {  // the W rows are one contiguous block: whole vectors
        DoublePack nlo[N], hi[N];
        load_pair_rows<N>(reinterpret_cast<const double*>(row0), nlo, hi);
        for (int k = 0; k < N; ++k) {
          v[k] = Pack(nlo[k], hi[k]);
          if (!ScalarOps<Pack>::finite(v[k])) throw MixedLanes{};
        }
        return;
      }
    }
#endif
    for (int k = 0; k < N; ++k) {
      DoublePack nlo, hi;
#if defined(CGAL_USE_SSE2) && defined(__SSE2__)
      __m128d in[width];
      for (int j = 0; j < width; ++j) in[j] = row0[j * stride + k].simd();
      from_lane_pairs(in, nlo, hi);
#else
      nlo = DoublePack([&](auto j) { return -row0[j * stride + k].inf(); });
      hi = DoublePack([&](auto j) { return row0[j * stride + k].sup(); });
#endif
      v[k] = Pack(nlo, hi);
      if (!ScalarOps<Pack>::finite(v[k])) throw MixedLanes{};
    }
  }
  template <int N> static void store(Scalar* row0, Eigen::Index stride, const Pack (&v)[N]) {
#if defined(CGAL_USE_SSE2) && (QVERIFY_PACK_512 || defined(__AVX__))
    if constexpr (N % 2 == 0) {
      if (stride == N && pack_aligned(row0)) {  // non-temporal whole vectors, as the double batches
        DoublePack nlo[N], hi[N];
        for (int k = 0; k < N; ++k) nlo[k] = v[k].nlo, hi[k] = v[k].hi;
        stream_pair_rows<N>(reinterpret_cast<double*>(row0), nlo, hi);
        return;
      }
    }
#endif
    for (int k = 0; k < N; ++k) {
#if defined(CGAL_USE_SSE2) && defined(__SSE2__)
      __m128d out[width];
      to_lane_pairs(v[k].nlo, v[k].hi, out);
      // Non-temporal, as the double batches: the output lines are not read first.
      for (int j = 0; j < width; ++j) _mm_stream_pd(reinterpret_cast<double*>(row0 + j * stride + k), out[j]);
#else
      for (int j = 0; j < width; ++j) row0[j * stride + k] = Scalar(-v[k].nlo[j], v[k].hi[j]);
#endif
    }
  }
  /// The rounding mode upward for the run of packs (restored after).
  struct Guard {
    CGAL::Protect_FPU_rounding<true> upward{CGAL_FE_UPWARD};
  };
  static void clear_faults() { std::feclearexcept(FE_INVALID); }
  static bool faulted() { return std::fetestexcept(FE_INVALID) != 0; }
};

}  // namespace qverify

namespace Eigen {
template <> struct NumTraits<qverify::IntervalPack> : qverify::PackNumTraits<qverify::IntervalPack, 4> {};
}  // namespace Eigen
