#pragma once
/// \file batch.hpp
/// Batch API: many (quadric, light) or (quadric, mirror) items at once, in a
/// structure-of-arrays layout, threads over items.
///
/// A batch of symmetric matrices is an `n x 10` row-major Eigen matrix: item
/// i's ten entries (A00 A01 A02 A03 A11 A12 A13 A22 A23 A33) are contiguous; a
/// batch of 4-vectors is `n x 4`. (Row-major rather than one array per entry:
/// a column layout streams 38 arrays at once, more than the hardware
/// prefetchers and write-combining buffers track; measured by `qverify bench`.)
///
/// One implementation of every formula: the items are computed by the *same*
/// generic functions as a single item (polar_plane, tangent_cone_entries,
/// terminator_entries, mirror_matrix_entries, mirror_image_entries, the
/// paper's route), instantiated either with the scalar itself, one item at a
/// time, or with a SIMD pack of W items ("lanes", pack.hpp): the direct route
/// in double runs W = 2 items per instruction on SSE2 (4 with AVX, 8 with
/// AVX-512), the certified intervals likewise (exact/interval_pack.hpp).
/// Entry k of W consecutive rows is gathered into one pack and the results are
/// transposed back into rows on the way out. The packed results are bitwise
/// the single-item results (tests/batch/test_batch.cpp). The paper route runs one
/// item at a time (it is the reference route, not the fast one).
///
/// Matrices only: the status words are per-item decisions (shadow_flags),
/// computed when wanted.

#include <qverify/core/mirror.hpp>
#include <qverify/batch/pack.hpp>
#include <qverify/batch/pages.hpp>
#include <qverify/batch/rows.hpp>
#include <qverify/core/shadow.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace qverify {

// SymBatch, Vec4Batch, AffineBatch and the entry order kSymRow/kSymCol: rows.hpp.

/// Plain (cached) stores of item i's symmetric matrix; gather_sym, its reverse,
/// is load_sym_lanes with ScalarLanes (below).
template <class S> void scatter_sym(SymBatch<S>& X, Eigen::Index i, const Mat4<S>& m) {
  for (int k = 0; k < 10; ++k) X(i, k) = m(kSymRow[k], kSymCol[k]);
}

/// Writes n contiguous values to a batch row. For double with SSE2 the stores
/// are non-temporal (the results are not read again soon, and a write-allocate
/// would read every output line first); rows of 4, 10 and 12 doubles start
/// 16-byte aligned in Eigen's aligned storage.
template <class S, int N> inline void store_row(S* dst, const S (&v)[N]) {
#if defined(__SSE2__)
  if constexpr (std::is_same_v<S, double> && N % 2 == 0) {
    if ((reinterpret_cast<std::uintptr_t>(dst) & 15) == 0) {
      for (int k = 0; k < N; k += 2) _mm_stream_pd(dst + k, _mm_set_pd(v[k + 1], v[k]));
      return;
    }
  }
#endif
  for (int k = 0; k < N; ++k) dst[k] = v[k];
}

/// Software prefetch of the input rows a pack will load `kPrefetchBlocks` blocks
/// later: the span of `Rows` rows from row0 (rows `stride` scalars apart, N
/// entries read from each; the batches' rows are contiguous, stride == N, and
/// the span is then exactly the block). The hardware prefetchers stop at every
/// 4 KiB page, and a block of interval packs does enough arithmetic between
/// loads that their latency showed: the interval rows of `qverify bench` went
/// from 20-23 to 13-15 ns per item (2 threads, AVX-512, runs interleaved with
/// the commit before). The double rows are at the bandwidth limit either way.
/// Addresses past the end are harmless: a prefetch does not fault, and the
/// address is formed as an integer (no out-of-range pointer arithmetic). On x86
/// the prefetch is an asm statement: GCC deletes loops of __builtin_prefetch
/// whose trip count it does not fold (a loop without side effects).
inline void prefetch_line(std::uintptr_t address) {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  asm volatile("prefetcht0 (%0)" : : "r"(address));
#elif defined(__GNUC__)
  __builtin_prefetch(reinterpret_cast<const void*>(address), 0, 3);
#else
  (void)address;
#endif
}
constexpr int kPrefetchBlocks = 8;
template <int N, int Rows, class S> inline void prefetch_rows(const S* row0, Eigen::Index stride) {
  constexpr std::uintptr_t line = 64;
  const std::uintptr_t ahead = reinterpret_cast<std::uintptr_t>(row0) + sizeof(S) * stride * Rows * kPrefetchBlocks;
  const std::uintptr_t end = ahead + sizeof(S) * (stride * (Rows - 1) + N);
  for (std::uintptr_t a = ahead & ~(line - 1); a < end; a += line) prefetch_line(a);
}

/// Orders the non-temporal stores of this thread before its results are read.
inline void store_fence() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

/// Runs f(begin, end) over [0, n) on `threads` threads (contiguous chunks).
/// Chunks start at multiples of 64 items (a multiple of every pack width W),
/// so that every block of W rows starts on a whole vector of the pack where
/// the batch's storage does (W rows of N doubles are N vectors), and streams
/// whole (stream_pieces, pack.hpp). With fewer than 64 items per thread some
/// threads get none.
template <class F> void parallel_for(Eigen::Index n, int threads, F&& f) {
  threads = std::max(1, threads);
  if (threads == 1 || n < 1024) {
    f(Eigen::Index(0), n);
    return;
  }
  std::vector<std::thread> pool;
  const Eigen::Index chunk = ((n + threads - 1) / threads + 63) / 64 * 64;
  for (int t = 0; t < threads; ++t) {
    const Eigen::Index b = t * chunk, e = std::min(n, b + chunk);
    if (b < e) pool.emplace_back([&f, b, e] { f(b, e); });
  }
  for (auto& th : pool) th.join();
}

// ----------------------------------------------------------------------- lanes

/// Inline everything an item calls: GCC otherwise keeps the formulas of a pack
/// out of line, and the per-item call overhead doubles the time (measured).
#if defined(__GNUC__)
#define QVERIFY_FLATTEN __attribute__((flatten))
#else
#define QVERIFY_FLATTEN
#endif

/// Lanes of width 1: an item is computed with the scalar itself.
template <class S> struct ScalarLanes {
  using Scalar = S;
  using Pack = S;
  static constexpr int width = 1;
  /// Entries 0..N-1 of the rows starting at row0 (rows `stride` scalars apart).
  template <int N> static void load(const S* row0, Eigen::Index, S (&v)[N]) {
    for (int k = 0; k < N; ++k) v[k] = row0[k];
  }
  /// Writes v[0..N) to the row(s) starting at row0.
  template <int N> static void store(S* row0, Eigen::Index, const S (&v)[N]) { store_row<S, N>(row0, v); }
  /// Set for the duration of a run of packs (e.g. the rounding mode).
  struct Guard {};
  /// Faults: a pack computation that cannot be trusted (e.g. a NaN in an
  /// interval pack) makes the batch recompute its span item by item.
  static void clear_faults() {}
  static bool faulted() { return false; }
};

/// The lanes a batch of S runs on: ScalarLanes unless a pack exists for S
/// (double here, CGAL intervals in exact/interval_pack.hpp).
template <class S, class Enable = void> struct BatchLanes : ScalarLanes<S> {};

/// Doubles, W rows at a time. Rows of 4, 10 and 12 doubles start 16-byte
/// aligned in Eigen's storage, so entries (k, k+1) of a row are one aligned
/// pair: W pairs are transposed into two packs (to/from_lane_pairs) and the
/// results are streamed back (non-temporal: they are not read again soon): the
/// block as whole vectors of the pack where its rows are contiguous and aligned
/// to it (stream_pieces; every block of a batch), else one row after the other.
template <> struct BatchLanes<double> : ScalarLanes<double> {
  using Pack = DoublePack;
  static constexpr int width = static_cast<int>(DoublePack::size());
  template <int N> static void load(const double* row0, Eigen::Index stride, Pack (&v)[N]) {
    prefetch_rows<N, width>(row0, stride);
#if QVERIFY_PACK_512 || defined(__AVX__)
    if constexpr (whole_pairs<N>()) {
      if (stride == N) {  // the W rows are one contiguous block: whole vectors
        Pack a[N / 2], b[N / 2];
        load_pair_rows<N / 2>(row0, a, b);
        for (int k = 0; k < N / 2; ++k) v[2 * k] = a[k], v[2 * k + 1] = b[k];
        return;
      }
    }
#endif
#if defined(__SSE2__)
    if constexpr (N % 2 == 0) {
      if (aligned_rows(row0, stride)) {
        for (int k = 0; k < N; k += 2) {
          __m128d in[width];
          for (int j = 0; j < width; ++j) in[j] = _mm_load_pd(row0 + j * stride + k);
          from_lane_pairs(in, v[k], v[k + 1]);
        }
        return;
      }
    }
#endif
    for (int k = 0; k < N; ++k) v[k] = Pack([&](auto j) { return row0[j * stride + k]; });
  }
  template <int N> static void store(double* row0, Eigen::Index stride, const Pack (&v)[N]) {
#if QVERIFY_PACK_512 || defined(__AVX__)
    if constexpr (whole_pairs<N>()) {
      if (stride == N && pack_aligned(row0)) {  // the W rows are one contiguous block: whole vectors
        Pack a[N / 2], b[N / 2];
        for (int k = 0; k < N / 2; ++k) a[k] = v[2 * k], b[k] = v[2 * k + 1];
        stream_pair_rows<N / 2>(row0, a, b);
        return;
      }
    }
#endif
#if defined(__SSE2__)
    if constexpr (N % 2 == 0) {
      if (aligned_rows(row0, stride)) {
        // Transposed whole first, then streamed in memory order: the block as whole vectors where
        // it is one (its rows contiguous and aligned), else row by row, each row's stores
        // consecutive: at most two lines of each output batch are partly written at a time. Streamed
        // entry pair by entry pair across the rows instead, all the block's lines fill at once
        // (8 rows of 10 doubles: 10 lines with AVX-512), more than the write-combining buffers
        // hold: on AMD Zen 4 the AVX-512 build then took 2-3x the AVX2 one's time (README,
        // "bench"). The values stored are the same either way.
        __m128d out[N / 2][width];
        for (int k = 0; k < N; k += 2) to_lane_pairs(v[k], v[k + 1], out[k / 2]);
        if (stride == N && pack_aligned(row0)) {  // the W rows are one contiguous block: whole vectors
          __m128d seq[N / 2 * width];
          for (int j = 0; j < width; ++j)
            for (int k = 0; k < N; k += 2) seq[j * (N / 2) + k / 2] = out[k / 2][j];
          stream_pieces(row0, seq);
          return;
        }
        for (int j = 0; j < width; ++j)
          for (int k = 0; k < N; k += 2) _mm_stream_pd(row0 + j * stride + k, out[k / 2][j]);
        return;
      }
    }
#endif
    for (int j = 0; j < width; ++j) {
      double r[N];
      for (int k = 0; k < N; ++k) r[k] = v[k][j];
      store_row<double, N>(row0 + j * stride, r);
    }
  }

 private:
  /// Whether a block of W rows of N doubles is read and written as whole vectors by their pairs
  /// (entries 2k and 2k + 1: load_pair_rows and stream_pair_rows, pack.hpp): the block's 16-byte
  /// pairs are moved within whole registers by shuffles, and every store is a whole vector. (The
  /// pieces of to_lane_pairs and stream_pieces, below, let clang 14 split each 32-byte store of
  /// two pieces into two 16-byte ones; README, "Whole-vector rows with clang's kernel".) Rows of 10 with 512-bit packs are 5
  /// pairs, which do not fill whole vectors of 4 pairs: the pieces take them.
  template <int N> static constexpr bool whole_pairs() {
#if QVERIFY_PACK_512 || defined(__AVX__)
    return N % 2 == 0 && (N / 2 * 2) % pair_rows::kChunks == 0;
#else
    return false;
#endif
  }
  static bool aligned_rows(const double* row0, Eigen::Index stride) {
    return (reinterpret_cast<std::uintptr_t>(row0) & 15) == 0 && stride % 2 == 0;
  }
};

/// The symmetric matrices of the lanes starting at row `row0` of a SymBatch.
template <class Ln> Mat4<typename Ln::Pack> load_sym_lanes(const typename Ln::Scalar* row0) {
  typename Ln::Pack v[10];
  Ln::template load<10>(row0, 10, v);
  Mat4<typename Ln::Pack> m;
  for (int k = 0; k < 10; ++k) {
    m(kSymRow[k], kSymCol[k]) = v[k];
    if (kSymRow[k] != kSymCol[k]) m(kSymCol[k], kSymRow[k]) = v[k];
  }
  return m;
}
template <class Ln> Vec4<typename Ln::Pack> load_vec4_lanes(const typename Ln::Scalar* row0) {
  typename Ln::Pack v[4];
  Ln::template load<4>(row0, 4, v);
  return Vec4<typename Ln::Pack>(v[0], v[1], v[2], v[3]);
}
template <class Ln> void store_sym_lanes(typename Ln::Scalar* row0, const Mat4<typename Ln::Pack>& m) {
  typename Ln::Pack v[10];
  for (int k = 0; k < 10; ++k) v[k] = m(kSymRow[k], kSymCol[k]);
  Ln::template store<10>(row0, 10, v);
}
/// The ten entries f(i, j) (i <= j, in the row order kSymRow/kSymCol) of a symmetric result,
/// stored straight from the formula's entry function (tangent_cone_entries, terminator_entries,
/// mirror_image_entries): without the 4x4 matrix of packs that store_sym_lanes takes, which GCC
/// keeps on the stack and copies (with the data in the caches, one thread, the interval shadow
/// kernel went from 25.9 to 22.8 ns per item, GCC's double one from 8.1 to 6.6; README, "bench").
/// The entries are formed in a pack expansion, not a loop: each call then has constant indices,
/// and the entry function's branches on them (terminator_entries) fold away; GCC kept a loop over
/// k, with the branches, the table lookups and the products inside.
template <class Ln, class F, std::size_t... K>
void store_sym_entries(typename Ln::Scalar* row0, const F& f, std::index_sequence<K...>) {
  const typename Ln::Pack v[10] = {f(kSymRow[K], kSymCol[K])...};
  Ln::template store<10>(row0, 10, v);
}
template <class Ln, class F> void store_sym_entries(typename Ln::Scalar* row0, const F& f) {
  store_sym_entries<Ln>(row0, f, std::make_index_sequence<10>{});
}
/// The same for rows 1-3 of an affine matrix, f(i, j) for i < 3, j < 4 (mirror_matrix_entries).
template <class Ln, class F, std::size_t... K>
void store_affine_entries(typename Ln::Scalar* row0, const F& f, std::index_sequence<K...>) {
  const typename Ln::Pack v[12] = {f(static_cast<int>(K / 4), static_cast<int>(K % 4))...};
  Ln::template store<12>(row0, 12, v);
}
template <class Ln, class F> void store_affine_entries(typename Ln::Scalar* row0, const F& f) {
  store_affine_entries<Ln>(row0, f, std::make_index_sequence<12>{});
}
template <class Ln> void store_vec4_lanes(typename Ln::Scalar* row0, const Vec4<typename Ln::Pack>& p) {
  const typename Ln::Pack v[4] = {p(0), p(1), p(2), p(3)};
  Ln::template store<4>(row0, 4, v);
}

/// Item i's symmetric matrix.
template <class S> Mat4<S> gather_sym(const SymBatch<S>& X, Eigen::Index i) {
  return load_sym_lanes<ScalarLanes<S>>(&X(i, 0));
}

/// item(lanes, i) over [0, n) on `threads` threads: blocks of Ln::width items
/// at a time, the rest (and every block whose pack computation gave up) with
/// ScalarLanes. A block gives up by a MixedLanes decision (pack.hpp) or by a
/// fault of its span (Ln::faulted). Each thread runs `setup()` first (its
/// result lives for the thread's chunk) and fences its non-temporal stores at
/// the end.
template <class Ln, class Setup, class Item> void for_each_block(Eigen::Index n, int threads, Setup& setup, Item&& item) {
  using S = typename Ln::Scalar;
  constexpr int W = Ln::width;
  parallel_for(n, threads, [&](Eigen::Index b, Eigen::Index e) {
    auto guard = setup();
    (void)guard;
    Eigen::Index i = b;
    if constexpr (W > 1) {
      constexpr Eigen::Index span = 64 * W;  // items between two fault checks
      while (e - i >= W) {
        const Eigen::Index stop = i + std::min<Eigen::Index>(span, (e - i) / W * W);
        bool redo = false;
        {
          typename Ln::Guard lanes_guard;
          (void)lanes_guard;
          Ln::clear_faults();
          for (Eigen::Index j = i; j < stop; j += W) {
            try {
              item(Ln{}, j);
            } catch (const MixedLanes&) {
              redo = true;
            }
          }
          redo = redo || Ln::faulted();
        }
        if (redo)
          for (Eigen::Index j = i; j < stop; ++j) item(ScalarLanes<S>{}, j);
        i = stop;
      }
    }
    for (; i < e; ++i) item(ScalarLanes<S>{}, i);
    store_fence();
  });
}

/// The number of items of a batch: A's rows, which the other input (lights or planes) must have
/// too; else std::invalid_argument, before anything is read (a shorter one would be read beyond
/// its end).
inline Eigen::Index batch_items(const char* function, Eigen::Index quadrics, Eigen::Index others) {
  if (others != quadrics)
    throw std::invalid_argument(std::string(function) + ": " + std::to_string(quadrics) + " quadrics but " +
                                std::to_string(others) + " rows of the second input (one per quadric)");
  return quadrics;
}

/// Sizes an output batch to n rows; storage of the right size is reused as it is. Storage it
/// allocates anew is advised huge pages before anything is written to it (pages.hpp says why),
/// for scalars that Eigen leaves uninitialised (double, CGAL intervals): Eigen constructs the others
/// (GMP rationals, MPFR numbers) in resize, which touches every page first. Returns the bytes
/// advised.
template <class Derived> std::size_t sized_output(Eigen::PlainObjectBase<Derived>& X, Eigen::Index n) {
  if (X.rows() == n) return 0;
  X.resize(n, Eigen::NoChange);
  if constexpr (Eigen::NumTraits<typename Derived::Scalar>::RequireInitialization) return 0;
  else return advise_huge_pages(X);
}

/// P, pi and R of every item (quadric A.row(i), light L.row(i)) by `method`.
/// Method paper on an item whose frame does not exist uses the direct formulas.
/// `setup` runs once per thread before its chunk (e.g. to set a rounding mode).
template <class S, class Setup>
void shadow_batch(const SymBatch<S>& A, const Vec4Batch<S>& L, Method method, SymBatch<S>& P, Vec4Batch<S>& pi,
                  SymBatch<S>& R, int threads, Setup&& setup) {
  const Eigen::Index n = batch_items("shadow_batch", A.rows(), L.rows());
  sized_output(P, n), sized_output(pi, n), sized_output(R, n);
  auto item = [&](auto lanes, Eigen::Index i) QVERIFY_FLATTEN {
    using Ln = decltype(lanes);
    using T = typename Ln::Pack;
    const Mat4<T> a = load_sym_lanes<Ln>(&A(i, 0));
    const Vec4<T> l = load_vec4_lanes<Ln>(&L(i, 0));
    if constexpr (Ln::width == 1) {
      if (method == Method::paper) {
        const PaperFrame<T> f = paper_frame<T>(l);
        if (!f.singular) {
          const Mat4<T> C = paper_C<T>(a, f);
          const Vec4<T> s = paper_S<T>(C);
          store_sym_lanes<Ln>(&P(i, 0), paper_P<T>(paper_D<T>(C), f));
          store_vec4_lanes<Ln>(&pi(i, 0), paper_polar_plane<T>(s, f));
          store_sym_lanes<Ln>(&R(i, 0), paper_R<T>(s, f));
          return;
        }
      }
    }
    const Vec4<T> p = polar_plane<T>(a, l);
    store_sym_entries<Ln>(&P(i, 0), tangent_cone_entries<T>(a, l, p));
    store_vec4_lanes<Ln>(&pi(i, 0), p);
    store_sym_entries<Ln>(&R(i, 0), terminator_entries<T>(l, p));
  };
  if (method == Method::paper) for_each_block<ScalarLanes<S>>(n, threads, setup, item);
  else for_each_block<BatchLanes<S>>(n, threads, setup, item);
}

template <class S>
void shadow_batch(const SymBatch<S>& A, const Vec4Batch<S>& L, Method method, SymBatch<S>& P, Vec4Batch<S>& pi,
                  SymBatch<S>& R, int threads) {
  shadow_batch(A, L, method, P, pi, R, threads, [] { return 0; });
}

/// M (rows 1-3) and B of every item (quadric A.row(i), mirror plane planes.row(i)).
/// With `scaled` the division-free (n.n) M is used (exact integer types): M and
/// B then carry the positive factors n.n and (n.n)^2.
template <class S, class Setup>
void reflection_batch(const SymBatch<S>& A, const Vec4Batch<S>& planes, Method method, AffineBatch<S>& M,
                      SymBatch<S>& B, int threads, bool scaled, Setup&& setup) {
  const Eigen::Index n = batch_items("reflection_batch", A.rows(), planes.rows());
  sized_output(M, n), sized_output(B, n);
  auto item = [&](auto lanes, Eigen::Index i) QVERIFY_FLATTEN {
    using Ln = decltype(lanes);
    using T = typename Ln::Pack;
    const Mat4<T> a = load_sym_lanes<Ln>(&A(i, 0));
    const Vec4<T> pl = load_vec4_lanes<Ln>(&planes(i, 0));
    if constexpr (Ln::width == 1) {
      if (scaled || method == Method::paper) {
        const Mat4<T> m = scaled ? scaled_mirror_matrix<T>(pl) : mirror_matrix<T>(pl);
        store_affine_entries<Ln>(&M(i, 0), [&m](int r, int c) { return m(r, c); });
        if (scaled) return store_sym_lanes<Ln>(&B(i, 0), mirror_image<T>(a, m));
        return store_sym_lanes<Ln>(&B(i, 0), mirror_image_paper<T>(a, m));
      }
    }
    const Vec4<T> h = mirror_half_direction<T>(pl);  // the one division
    store_affine_entries<Ln>(&M(i, 0), mirror_matrix_entries<T>(h, pl));
    store_sym_entries<Ln>(&B(i, 0), mirror_image_entries<T>(a, h, pl));
  };
  if (method == Method::paper || scaled) for_each_block<ScalarLanes<S>>(n, threads, setup, item);
  else for_each_block<BatchLanes<S>>(n, threads, setup, item);
}

template <class S>
void reflection_batch(const SymBatch<S>& A, const Vec4Batch<S>& planes, Method method, AffineBatch<S>& M,
                      SymBatch<S>& B, int threads) {
  reflection_batch(A, planes, method, M, B, threads, false, [] { return 0; });
}

}  // namespace qverify
