#pragma once
/// \file pack.hpp
/// A SIMD pack as a scalar type: the batch API (batch.hpp) runs the *same*
/// generic formulas on W items at once by instantiating them with a pack whose
/// arithmetic is lane-wise. No formula is written twice: `tangent_cone<double>`
/// and `tangent_cone<DoublePack>` are one template.
///
/// The pack is the standard library's `std::experimental::native_simd<double>`
/// (Parallelism TS v2, libstdc++ >= 11): W = 2 with the x86-64 baseline (SSE2),
/// 4 with AVX, 8 with AVX-512, whatever the build targets. Its lane-wise +, -,
/// *, / are the IEEE operations of the scalar, so with the fixed summation
/// order of the direct formulas (ordered_dot) every lane is bitwise the
/// single-item double result.
///
/// Decisions. A formula that branches on a scalar (frame_plane asks whether
/// L_w = 0) cannot branch per lane. ScalarOps<DoublePack> answers a question
/// when every lane gives the same answer and throws MixedLanes otherwise; the
/// batch then computes that block item by item. Nothing is ever decided for a
/// lane by another lane's value.

#include <qverify/core/scalar.hpp>

#include <cstdint>
#include <experimental/simd>
#include <limits>

namespace qverify {

namespace stdx = std::experimental;

/// QVERIFY_PACK_BITS (256 or 512) overrides the pack's width for one translation unit: the
/// measured second double kernel for x86-64-v4 compiled by clang++ with 256-bit packs
/// (cmake/ChooseArch.cmake, variant c4n) keeps AVX-512's 32 vector registers and instructions but
/// computes 4 items at once. Without it the pack is the build's native width.
#if defined(QVERIFY_PACK_BITS) && QVERIFY_PACK_BITS != 256 && QVERIFY_PACK_BITS != 512
#error "QVERIFY_PACK_BITS is 256 or 512"
#endif
#if defined(QVERIFY_PACK_BITS) && QVERIFY_PACK_BITS == 512 && !defined(__AVX512F__)
#error "512-bit packs need AVX-512"
#endif
#if defined(QVERIFY_PACK_BITS) && QVERIFY_PACK_BITS == 256 && !defined(__AVX__)
#error "256-bit packs need AVX"
#endif
/// QVERIFY_PACK_512: whether the pack is one 512-bit register (the branches below that use
/// AVX-512 instructions on whole packs).
#if defined(__AVX512F__) && !(defined(QVERIFY_PACK_BITS) && QVERIFY_PACK_BITS == 256)
#define QVERIFY_PACK_512 1
#else
#define QVERIFY_PACK_512 0
#endif

/// W doubles in one register: the native SIMD width of the build, or QVERIFY_PACK_BITS.
#if defined(QVERIFY_PACK_BITS)
using DoublePack = stdx::simd<double, stdx::simd_abi::deduce_t<double, QVERIFY_PACK_BITS / 64>>;
#else
using DoublePack = stdx::native_simd<double>;
#endif
static_assert(sizeof(DoublePack) == DoublePack::size() * sizeof(double), "a pack is one register of doubles");

/// Thrown by a decision whose lanes disagree (see the file comment).
struct MixedLanes {};

/// The one answer of all lanes of a mask, or MixedLanes.
template <class Mask> inline bool uniform(const Mask& m) {
  if (stdx::all_of(m)) return true;
  if (stdx::none_of(m)) return false;
  throw MixedLanes{};
}

/// Hides a value's origin from the optimiser (no instruction is emitted).
/// Interval packs need it: with the rounding mode set upward, (-x) * y and
/// -(x * y) differ, and a compiler assuming round-to-nearest may rewrite one
/// into the other. CGAL's Interval_nt does the same (IA_opacify).
inline DoublePack opaque(DoublePack x) {
  typedef double Vec __attribute__((vector_size(sizeof(DoublePack))));
  Vec v = static_cast<Vec>(x);
  asm("" : "+v"(v));
  return DoublePack(v);
}

/// Lane-wise max by the hardware instruction (MAXPD), which raises the IEEE
/// invalid flag when an operand is NaN. (Not stdx::max: libstdc++ compiles it
/// with finite-math-only, which both leaves NaN behaviour open and, as a
/// function-specific optimisation attribute, stops GCC from inlining its
/// callers.)
inline DoublePack pack_max(const DoublePack& a, const DoublePack& b) {
#if QVERIFY_PACK_512
  // The all-lanes mask form: GCC 12.2's _mm512_max_pd trips -Wuninitialized (GCC PR 105593).
  return DoublePack(_mm512_mask_max_pd(static_cast<__m512d>(b), static_cast<__mmask8>(0xff), static_cast<__m512d>(a),
                                       static_cast<__m512d>(b)));
#elif defined(__AVX__)
  return DoublePack(_mm256_max_pd(static_cast<__m256d>(a), static_cast<__m256d>(b)));
#elif defined(__SSE2__)
  return DoublePack(_mm_max_pd(static_cast<__m128d>(a), static_cast<__m128d>(b)));
#else
  DoublePack r = b;
  stdx::where(a > b, r) = a;  // an ordered signalling comparison: NaN raises invalid
  return r;
#endif
}

#if defined(__SSE2__)
/// Lanes to pairs and back, the transposition of a batch's rows (each row
/// holding two consecutive entries, or one CGAL interval {-lo, hi}):
/// out[j] = (a_j, b_j) for every lane j.
inline void to_lane_pairs(const DoublePack& a, const DoublePack& b, __m128d (&out)[DoublePack::size()]) {
#if QVERIFY_PACK_512
  // Vector shuffles rather than the AVX-512 unpack/extract intrinsics, which GCC 12.2 flags
  // with -Wuninitialized (GCC PR 105593); the same instructions come out.
  typedef double V8 __attribute__((vector_size(64)));
  typedef double V4 __attribute__((vector_size(32)));
  const V8 x = static_cast<V8>(static_cast<__m512d>(a)), y = static_cast<V8>(static_cast<__m512d>(b));
  const V8 lo = __builtin_shufflevector(x, y, 0, 8, 2, 10, 4, 12, 6, 14);  // (a0 b0 a2 b2 ..)
  const V8 hi = __builtin_shufflevector(x, y, 1, 9, 3, 11, 5, 13, 7, 15);  // (a1 b1 a3 b3 ..)
  const V4 quarters[4] = {__builtin_shufflevector(lo, lo, 0, 1, 2, 3), __builtin_shufflevector(hi, hi, 0, 1, 2, 3),
                          __builtin_shufflevector(lo, lo, 4, 5, 6, 7), __builtin_shufflevector(hi, hi, 4, 5, 6, 7)};
  for (int q = 0; q < 2; ++q) {
    out[4 * q + 0] = _mm256_castpd256_pd128(quarters[2 * q]);
    out[4 * q + 1] = _mm256_castpd256_pd128(quarters[2 * q + 1]);
    out[4 * q + 2] = _mm256_extractf128_pd(quarters[2 * q], 1);
    out[4 * q + 3] = _mm256_extractf128_pd(quarters[2 * q + 1], 1);
  }
#elif defined(__AVX__)
  const __m256d x = static_cast<__m256d>(a), y = static_cast<__m256d>(b);
  const __m256d lo = _mm256_unpacklo_pd(x, y), hi = _mm256_unpackhi_pd(x, y);  // (a0 b0 a2 b2), (a1 b1 a3 b3)
  out[0] = _mm256_castpd256_pd128(lo);
  out[1] = _mm256_castpd256_pd128(hi);
  out[2] = _mm256_extractf128_pd(lo, 1);
  out[3] = _mm256_extractf128_pd(hi, 1);
#else
  const __m128d x = static_cast<__m128d>(a), y = static_cast<__m128d>(b);
  out[0] = _mm_unpacklo_pd(x, y);
  out[1] = _mm_unpackhi_pd(x, y);
#endif
}

/// The inverse of to_lane_pairs: a_j, b_j from in[j] = (a_j, b_j).
inline void from_lane_pairs(const __m128d (&in)[DoublePack::size()], DoublePack& a, DoublePack& b) {
#if QVERIFY_PACK_512
  typedef double V8 __attribute__((vector_size(64)));
  typedef double V4 __attribute__((vector_size(32)));
  const V4 x0 = _mm256_set_m128d(in[2], in[0]), x1 = _mm256_set_m128d(in[6], in[4]);  // (a0 b0 a2 b2), (a4 b4 a6 b6)
  const V4 y0 = _mm256_set_m128d(in[3], in[1]), y1 = _mm256_set_m128d(in[7], in[5]);  // (a1 b1 a3 b3), (a5 b5 a7 b7)
  const V8 x = __builtin_shufflevector(x0, x1, 0, 1, 2, 3, 4, 5, 6, 7);
  const V8 y = __builtin_shufflevector(y0, y1, 0, 1, 2, 3, 4, 5, 6, 7);
  a = DoublePack(static_cast<__m512d>(__builtin_shufflevector(x, y, 0, 8, 2, 10, 4, 12, 6, 14)));
  b = DoublePack(static_cast<__m512d>(__builtin_shufflevector(x, y, 1, 9, 3, 11, 5, 13, 7, 15)));
#elif defined(__AVX__)
  const __m256d x = _mm256_set_m128d(in[2], in[0]), y = _mm256_set_m128d(in[3], in[1]);
  a = DoublePack(_mm256_unpacklo_pd(x, y));
  b = DoublePack(_mm256_unpackhi_pd(x, y));
#else
  a = DoublePack(_mm_unpacklo_pd(in[0], in[1]));
  b = DoublePack(_mm_unpackhi_pd(in[0], in[1]));
#endif
}
#endif

#if defined(__SSE2__)
#if QVERIFY_PACK_512
/// Streams one 512-bit vector to p: a whole line where p is 64-byte aligned, else two 32-byte halves
/// (p 32-byte aligned only, as pack_aligned allows).
/// (Vector shuffles for the halves, not _mm512_extractf64x4_pd: GCC PR 105593, as to_lane_pairs.)
inline void stream_vector(double* p, __m512d v) {
  if ((reinterpret_cast<std::uintptr_t>(p) & 63) == 0) {
    _mm512_stream_pd(p, v);
  } else {
    typedef double V8 __attribute__((vector_size(64)));
    const V8 x = static_cast<V8>(v);
    _mm256_stream_pd(p, static_cast<__m256d>(__builtin_shufflevector(x, x, 0, 1, 2, 3)));
    _mm256_stream_pd(p + 4, static_cast<__m256d>(__builtin_shufflevector(x, x, 4, 5, 6, 7)));
  }
}
#endif

/// Streams `Count` 16-byte pieces, given in memory order, to dst as whole
/// vectors of the pack's width (W / 2 pieces each: one 64-byte line with
/// AVX-512, or its two halves where dst is 32-byte aligned only; half a line
/// with AVX2), non-temporally. dst as pack_aligned requires. A block of W contiguous rows is a whole number of such
/// vectors; stored this way it takes a quarter of the store instructions of
/// 16-byte pieces, and no line is ever partly written by one store and
/// completed by another far away. (The double shadow batch on one thread of
/// AMD Zen 5, out of the caches: 16-17 ns per item with 16-byte stores, 13-14
/// with whole lines; README, "bench".)
template <int Count> inline void stream_pieces(double* dst, const __m128d (&seq)[Count]) {
  constexpr int per = static_cast<int>(DoublePack::size()) / 2;
  static_assert(Count % per == 0, "a whole number of vectors");
  for (int q = 0; q < Count; q += per) {
#if QVERIFY_PACK_512
    static_assert(per == 4, "a 512-bit pack");
    typedef double V8 __attribute__((vector_size(64)));
    typedef double V4 __attribute__((vector_size(32)));
    const V4 lo = _mm256_set_m128d(seq[q + 1], seq[q]), hi = _mm256_set_m128d(seq[q + 3], seq[q + 2]);
    const V8 line = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
    stream_vector(dst + 2 * q, static_cast<__m512d>(line));
#elif defined(__AVX__)
    static_assert(per == 2, "a 256-bit pack");
    _mm256_stream_pd(dst + 2 * q, _mm256_set_m128d(seq[q + 1], seq[q]));
#else
    static_assert(per == 1, "a 128-bit pack");
    _mm_stream_pd(dst + 2 * q, seq[q]);
#endif
  }
}

#if QVERIFY_PACK_512 || defined(__AVX__)
/// W contiguous rows of N pairs, row j holding (a_k[j], b_k[j]) for k < N (a block of CGAL
/// intervals {-lo, hi}; or of doubles, entries 2k and 2k + 1 of a row), to and from the lanes, by
/// whole vectors of the pack's width, 2 N a multiple of the pairs a vector holds (any N with
/// 256-bit packs, N even with 512-bit ones):
/// stream_pair_rows streams them non-temporally (dst as pack_aligned requires),
/// load_pair_rows reads them from anywhere. For 8 lanes and one entry, to/from_lane_pairs with
/// 16-byte loads and stores took about 22 instructions, mostly moves between registers and
/// extractions of 16-byte parts; these take about 7. (The interval shadow kernel for AVX-512, one
/// thread, data in the caches: 21 ns per item before, 15.8 after, 2026-12-03.)
///
/// How. Interleaving a_k and b_k (unpack) gives u_0[k], the pairs of the even lanes, and u_1[k],
/// those of the odd lanes: chunk c of u_p[k] (one pair, 16 bytes) is row 2c + p, entry k. Rows 2c
/// and 2c + 1 are 2N consecutive pairs in memory, v = 0..2N-1 being u_{v / N}[v % N]'s chunk c:
/// every V consecutive v (V = W / 2 pairs a vector), V g .. V g + V - 1, are, chunk c of each, the
/// block's vector 2 c N / V + g: a V x V transposition of chunks across those V registers gives
/// the V vectors (c = 0..V-1). Both steps are their own inverses, so loading runs them on the
/// vectors read.
namespace pair_rows {
#if QVERIFY_PACK_512
typedef double Vec __attribute__((vector_size(64)));
typedef __m512d Native;
constexpr int kChunks = 4;  // pairs per vector
/// x[i] <- (chunk i of x[0], ..., chunk i of x[3]): a 4 x 4 transposition of 16-byte chunks.
inline void transpose(Vec (&x)[4]) {
  const Vec t0 = __builtin_shufflevector(x[0], x[1], 0, 1, 2, 3, 8, 9, 10, 11);
  const Vec t1 = __builtin_shufflevector(x[0], x[1], 4, 5, 6, 7, 12, 13, 14, 15);
  const Vec t2 = __builtin_shufflevector(x[2], x[3], 0, 1, 2, 3, 8, 9, 10, 11);
  const Vec t3 = __builtin_shufflevector(x[2], x[3], 4, 5, 6, 7, 12, 13, 14, 15);
  x[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5, 8, 9, 12, 13);
  x[1] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7, 10, 11, 14, 15);
  x[2] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5, 8, 9, 12, 13);
  x[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7, 10, 11, 14, 15);
}
/// (x, y) <- their even lanes interleaved, their odd lanes interleaved.
inline void interleave(Vec& x, Vec& y) {
  const Vec e = __builtin_shufflevector(x, y, 0, 8, 2, 10, 4, 12, 6, 14);
  y = __builtin_shufflevector(x, y, 1, 9, 3, 11, 5, 13, 7, 15);
  x = e;
}
inline Vec load(const double* p) { return static_cast<Vec>(_mm512_loadu_pd(p)); }
inline void stream(double* p, const Vec& v) { stream_vector(p, static_cast<__m512d>(v)); }
#else
typedef double Vec __attribute__((vector_size(32)));
typedef __m256d Native;
constexpr int kChunks = 2;
inline void transpose(Vec (&x)[2]) {
  const Vec t = __builtin_shufflevector(x[0], x[1], 0, 1, 4, 5);
  x[1] = __builtin_shufflevector(x[0], x[1], 2, 3, 6, 7);
  x[0] = t;
}
inline void interleave(Vec& x, Vec& y) {
  const Vec e = __builtin_shufflevector(x, y, 0, 4, 2, 6);
  y = __builtin_shufflevector(x, y, 1, 5, 3, 7);
  x = e;
}
inline Vec load(const double* p) { return static_cast<Vec>(_mm256_loadu_pd(p)); }
inline void stream(double* p, const Vec& v) { _mm256_stream_pd(p, static_cast<__m256d>(v)); }
#endif
static_assert(sizeof(Vec) == sizeof(DoublePack), "one vector a pack");
}  // namespace pair_rows

template <int N> inline void stream_pair_rows(double* dst, const DoublePack (&a)[N], const DoublePack (&b)[N]) {
  using namespace pair_rows;
  static_assert(2 * N % kChunks == 0, "whole vectors: W rows of N pairs");
  constexpr int V = kChunks, G = 2 * N / V;  // G vectors for each chunk index c
  Vec u[2][N];
  for (int k = 0; k < N; ++k) {
    u[0][k] = static_cast<Vec>(static_cast<Native>(a[k])), u[1][k] = static_cast<Vec>(static_cast<Native>(b[k]));
    interleave(u[0][k], u[1][k]);
  }
  // By groups, not in memory order: with whole lines (dst 64-byte aligned) each store fills its line
  // and the order does not matter to the write-combining buffers, and memory order (all the block's
  // vectors formed first, then streamed) measured slower: 36 against 30 ns per item (AVX-512, one
  // thread, 2026-12-03). With 32-byte halves (dst 32-byte aligned only, as the library's batches)
  // a line is completed by the next group's store, so up to V - 1 lines of each output are half
  // written at a time; the two orders could not be told apart on this machine's noise that day, and
  // `qverify bench` times this path (README, "bench").
  for (int g = 0; g < G; ++g) {
    Vec x[V];
    for (int i = 0; i < V; ++i) x[i] = u[(V * g + i) / N][(V * g + i) % N];
    transpose(x);
    for (int c = 0; c < V; ++c) stream(dst + 2 * V * (c * G + g), x[c]);
  }
}

template <int N> inline void load_pair_rows(const double* src, DoublePack (&a)[N], DoublePack (&b)[N]) {
  using namespace pair_rows;
  static_assert(2 * N % kChunks == 0, "whole vectors: W rows of N pairs");
  constexpr int V = kChunks, G = 2 * N / V;
  Vec u[2][N];
  for (int g = 0; g < G; ++g) {
    Vec x[V];
    for (int c = 0; c < V; ++c) x[c] = load(src + 2 * V * (c * G + g));
    transpose(x);
    for (int i = 0; i < V; ++i) u[(V * g + i) / N][(V * g + i) % N] = x[i];
  }
  for (int k = 0; k < N; ++k) {
    interleave(u[0][k], u[1][k]);
    a[k] = DoublePack(static_cast<Native>(u[0][k]));
    b[k] = DoublePack(static_cast<Native>(u[1][k]));
  }
}
#endif

/// Whether dst is aligned for stream_pieces and stream_pair_rows: to the pack's size, or to 32 bytes
/// for a 512-bit pack, whose vectors then go as two 32-byte halves. The library is built for
/// x86-64-v3 (cmake/ChooseArch.cmake), for which Eigen aligns a batch's storage to 32 bytes only,
/// and its AVX-512 kernels write into it: with 64 required, they fell back to 16-byte pieces.
inline bool pack_aligned(const void* dst) {
  return (reinterpret_cast<std::uintptr_t>(dst) % (QVERIFY_PACK_512 ? 32 : sizeof(DoublePack))) == 0;
}
#endif

template <> struct ScalarOps<DoublePack> {
  using P = DoublePack;
  static constexpr bool interval = false;
  static bool exact() { return false; }
  static bool less(const P& a, const P& b) { return uniform(a < b); }
  static bool is_zero(const P& a) { return uniform(a == P(0)); }
  static P abs(const P& x) { return stdx::abs(x); }
  static bool finite(const P& x) { return stdx::all_of(stdx::isfinite(x)); }
};

}  // namespace qverify

namespace qverify {
/// Eigen's traits of a pack of doubles P (DoublePack, IntervalPack): Eigen's
/// scalar (non-vectorised) code paths, whose every operation is one SIMD
/// operation on the pack; constants are broadcast.
template <class P, int MulCostOfPack> struct PackNumTraits : Eigen::GenericNumTraits<double> {
  typedef P Real;
  typedef P NonInteger;
  typedef P Nested;
  typedef P Literal;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 0,
    ReadCost = 1,
    AddCost = 1,
    MulCost = MulCostOfPack
  };
  static P epsilon() { return P(std::numeric_limits<double>::epsilon()); }
  static P dummy_precision() { return P(Eigen::NumTraits<double>::dummy_precision()); }
  static P highest() { return P(std::numeric_limits<double>::max()); }
  static P lowest() { return P(std::numeric_limits<double>::lowest()); }
};
}  // namespace qverify

namespace Eigen {
template <> struct NumTraits<qverify::DoublePack> : qverify::PackNumTraits<qverify::DoublePack, 1> {};
}  // namespace Eigen
