#pragma once
/// \file batch.hpp
/// Batch API: many (quadric, light) or (quadric, mirror) items at once, in a
/// structure-of-arrays layout, threads over items.
///
/// A batch of symmetric matrices is an `n x 10` row-major Eigen matrix: item
/// i's ten entries (A00 A01 A02 A03 A11 A12 A13 A22 A23 A33) are contiguous; a
/// batch of 4-vectors is `n x 4`. (Row-major rather than one array per entry:
/// a column layout streams 38 arrays at once, more than the hardware
/// prefetchers and write-combining buffers track; measured by `qverify bench`.) Item i is gathered into fixed-size Eigen
/// matrices, computed by the *same* generic functions as a single item
/// (tangent_cone, polar_plane, terminator_quadric, the paper's route,
/// mirror_matrix, mirror_image) and scattered back: one implementation of
/// every formula. Matrices only: the status words are per-item decisions
/// (shadow_flags), computed when wanted.

#include <qverify/core/mirror.hpp>
#include <qverify/core/shadow.hpp>

#include <algorithm>
#include <cstdint>
#include <thread>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace qverify {

template <class S> using SymBatch = Eigen::Matrix<S, Eigen::Dynamic, 10, Eigen::RowMajor>;
template <class S> using Vec4Batch = Eigen::Matrix<S, Eigen::Dynamic, 4, Eigen::RowMajor>;
/// The three non-trivial rows of mirror matrices (row 4 is 0 0 0 1).
template <class S> using AffineBatch = Eigen::Matrix<S, Eigen::Dynamic, 12, Eigen::RowMajor>;

/// Entry order of a symmetric matrix in a SymBatch row.
constexpr int kSymRow[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
constexpr int kSymCol[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

template <class S> Mat4<S> gather_sym(const SymBatch<S>& X, Eigen::Index i) {
  Mat4<S> m;
  for (int k = 0; k < 10; ++k) m(kSymRow[k], kSymCol[k]) = m(kSymCol[k], kSymRow[k]) = X(i, k);
  return m;
}
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

/// Orders the non-temporal stores of this thread before its results are read.
inline void store_fence() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

template <class S> void store_sym(SymBatch<S>& X, Eigen::Index i, const Mat4<S>& m) {
  S v[10];
  for (int k = 0; k < 10; ++k) v[k] = m(kSymRow[k], kSymCol[k]);
  store_row<S, 10>(&X(i, 0), v);
}
template <class S> void store_vec4(Vec4Batch<S>& X, Eigen::Index i, const Vec4<S>& p) {
  const S v[4] = {p(0), p(1), p(2), p(3)};
  store_row<S, 4>(&X(i, 0), v);
}

/// Runs f(begin, end) over [0, n) on `threads` threads (contiguous chunks).
template <class F> void parallel_for(Eigen::Index n, int threads, F&& f) {
  threads = std::max(1, threads);
  if (threads == 1 || n < 1024) {
    f(Eigen::Index(0), n);
    return;
  }
  std::vector<std::thread> pool;
  const Eigen::Index chunk = (n + threads - 1) / threads;
  for (int t = 0; t < threads; ++t) {
    const Eigen::Index b = t * chunk, e = std::min(n, b + chunk);
    if (b < e) pool.emplace_back([&f, b, e] { f(b, e); });
  }
  for (auto& th : pool) th.join();
}

/// item(i) for every i in [0, n) on `threads` threads; each thread runs
/// `setup()` first (its result lives for the thread's chunk) and fences its
/// non-temporal stores at the end.
template <class Setup, class Item> void for_each_item(Eigen::Index n, int threads, Setup& setup, Item&& item) {
  parallel_for(n, threads, [&](Eigen::Index b, Eigen::Index e) {
    auto guard = setup();
    (void)guard;
    for (Eigen::Index i = b; i < e; ++i) item(i);
    store_fence();
  });
}

/// P, pi and R of every item (quadric A.row(i), light L.row(i)) by `method`.
/// Method paper on an item whose frame does not exist uses the direct formulas.
/// `setup` runs once per thread before its chunk (e.g. to set a rounding mode).
template <class S, class Setup>
void shadow_batch(const SymBatch<S>& A, const Vec4Batch<S>& L, Method method, SymBatch<S>& P, Vec4Batch<S>& pi,
                  SymBatch<S>& R, int threads, Setup&& setup) {
  const Eigen::Index n = A.rows();
  P.resize(n, 10);
  pi.resize(n, 4);
  R.resize(n, 10);
  for_each_item(n, threads, setup, [&](Eigen::Index i) {
    const Mat4<S> a = gather_sym(A, i);
    const Vec4<S> l = L.row(i).transpose();
    if (method == Method::paper) {
      const PaperFrame<S> f = paper_frame<S>(l);
      if (!f.singular) {
        const Mat4<S> C = paper_C<S>(a, f);
        const Vec4<S> s = paper_S<S>(C);
        store_sym(P, i, paper_P<S>(paper_D<S>(C), f));
        store_vec4(pi, i, paper_polar_plane<S>(s, f));
        store_sym(R, i, paper_R<S>(s, f));
        return;
      }
    }
    const Vec4<S> p = polar_plane<S>(a, l);
    store_sym(P, i, tangent_cone_from_polar<S>(a, l, p));
    store_vec4(pi, i, p);
    store_sym(R, i, terminator_quadric_from_polar<S>(l, p));
  });
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
  const Eigen::Index n = A.rows();
  M.resize(n, 12);
  B.resize(n, 10);
  for_each_item(n, threads, setup, [&](Eigen::Index i) {
    const Mat4<S> a = gather_sym(A, i);
    const Vec4<S> pl = planes.row(i).transpose();
    const Mat4<S> m = scaled ? scaled_mirror_matrix<S>(pl) : mirror_matrix<S>(pl);
    S rows[12];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) rows[4 * r + c] = m(r, c);
    store_row<S, 12>(&M(i, 0), rows);
    store_sym(B, i, scaled ? mirror_image<S>(a, m)
                           : method == Method::paper ? mirror_image_paper<S>(a, m) : mirror_image_of_plane<S>(a, pl));
  });
}

template <class S>
void reflection_batch(const SymBatch<S>& A, const Vec4Batch<S>& planes, Method method, AffineBatch<S>& M,
                      SymBatch<S>& B, int threads) {
  reflection_batch(A, planes, method, M, B, threads, false, [] { return 0; });
}

}  // namespace qverify
