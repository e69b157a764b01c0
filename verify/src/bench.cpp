#include <qverify/core/batch.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/verify/bench.hpp>
#include <qverify/verify/eval.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <random>

namespace qverify {

using json = nlohmann::ordered_json;
using Int = __int128;

namespace {

using Clock = std::chrono::steady_clock;

/// Random small rationals p/q (|p| <= 20, 1 <= q <= 9), one per entry, as
/// numerator and denominator arrays (column-major, like the batches).
struct RationalInputs {
  Eigen::Matrix<std::int32_t, Eigen::Dynamic, Eigen::Dynamic> num, den;
  RationalInputs(Eigen::Index n, int cols, std::uint64_t seed) : num(n, cols), den(n, cols) {
    std::mt19937_64 g(seed);
    for (int c = 0; c < cols; ++c)
      for (Eigen::Index i = 0; i < n; ++i) {
        const std::uint64_t r = g();
        num(i, c) = static_cast<std::int32_t>(r % 41) - 20;
        den(i, c) = static_cast<std::int32_t>((r >> 8) % 9) + 1;
      }
  }
  template <class S, int C> Eigen::Matrix<S, Eigen::Dynamic, C, Eigen::RowMajor> rounded() const {
    Eigen::Matrix<S, Eigen::Dynamic, C, Eigen::RowMajor> out(num.rows(), C);
    for (int c = 0; c < C; ++c)
      for (Eigen::Index i = 0; i < num.rows(); ++i)
        out(i, c) = S(static_cast<double>(num(i, c)) / static_cast<double>(den(i, c)));
    return out;
  }
};

/// Light/plane inputs: point lights (w = 1) and planes with a non-zero normal.
template <class M> void homogenise(M& L, bool light) {
  for (Eigen::Index i = 0; i < L.rows(); ++i) {
    if (light) L(i, 3) = typename M::Scalar(1);
    else if (L(i, 2) == typename M::Scalar(0)) L(i, 2) = typename M::Scalar(1);
  }
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Median of `repeats` timings of f().
template <class F> double median_time(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    f();
    t.push_back(seconds_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// Stream copy of `bytes` bytes moved (bytes/2 read, bytes/2 written) on `threads`
/// threads, best of 3: the machine's sustainable bandwidth in this run. The copy writes
/// with non-temporal stores, as the double batches do (a plain memcpy may read every
/// destination line first and then understates what the machine moves).
double copy_bandwidth(std::size_t bytes, int threads) {
  const std::size_t half = bytes / 2 / sizeof(double) / 2 * 2;
  Eigen::VectorXd src = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(half), 1.0);
  Eigen::VectorXd dst = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(half));
  double best = 1e300;
  for (int r = 0; r < 3; ++r) {
    const auto t0 = Clock::now();
    parallel_for(static_cast<Eigen::Index>(half / 2), threads, [&](Eigen::Index b, Eigen::Index e) {
      const double* s = src.data();
      double* d = dst.data();
      for (Eigen::Index i = 2 * b; i < 2 * e; i += 2) {
#if defined(__SSE2__)
        _mm_stream_pd(d + i, _mm_load_pd(s + i));
#else
        d[i] = s[i], d[i + 1] = s[i + 1];
#endif
      }
      store_fence();
    });
    best = std::min(best, seconds_since(t0));
  }
  volatile double sink = dst[static_cast<Eigen::Index>(half / 2)];
  (void)sink;
  return static_cast<double>(2 * half * sizeof(double)) / best;
}

/// Exact items: each item's denominators are cleared (a positive factor: the
/// results are projective), then the generic formulas run on 128-bit integers,
/// with no gcd and no division. The bit bound of the inputs proves there is no
/// overflow; items beyond it would need GMP (counted per row, none in this benchmark).
long lcm_of(const std::int32_t* d, int k) {
  long l = 1;
  for (int j = 0; j < k; ++j) l = std::lcm(l, static_cast<long>(d[j]));
  return l;
}

int bits(Int x) {
  if (x < 0) x = -x;
  int b = 0;
  while (x > 0) x >>= 1, ++b;
  return b;
}

/// The widest x86 vector extension this build was compiled for.
const char* instruction_set() {
#if defined(__AVX512F__)
  return "AVX-512";
#elif defined(__AVX2__)
  return "AVX2";
#elif defined(__AVX__)
  return "AVX";
#elif defined(__SSE2__)
  return "SSE2";
#else
  return "scalar";
#endif
}

}  // namespace

json run_bench(const BenchOptions& opt) {
  const Eigen::Index n = opt.n;
  const int T = opt.threads;
  json rows = json::array();
  auto say = [&](const std::string& s) {
    if (opt.progress) opt.progress(s);
  };
  // Bandwidth measured in the same run, over as many bytes as the double shadow row moves.
  const std::size_t shadow_bytes = (10 + 4) * 8 + (10 + 4 + 10) * 8;
  // The machine is shared: its bandwidth is measured before and after the double rows (best
  // of 3 each), and the larger reading is the limit, so that a slow moment of the copy does
  // not flatter the rows.
  say("bench: memory bandwidth");
  double bandwidth = copy_bandwidth(static_cast<std::size_t>(n) * shadow_bytes, T);
  auto add_row = [&](const char* op, const char* precision, const char* method, double seconds, std::size_t bytes,
                     json extra = json::object()) {
    const double ips = static_cast<double>(n) / seconds;
    json r{{"op", op},
           {"precision", precision},
           {"method", method},
           {"items_per_s", ips},
           {"ns_per_item", 1e9 / ips},
           {"bytes_per_item", bytes},
           {"roofline_fraction", nullptr}};  // once the bandwidth is final
    for (auto& [k, v] : extra.items()) r[k] = v;
    rows.push_back(r);
  };

  const RationalInputs qa(n, 10, 1), ql(n, 4, 2);
  {  // ---- double
    SymBatch<double> A = qa.rounded<double, 10>();
    Vec4Batch<double> L = ql.rounded<double, 4>(), planes = ql.rounded<double, 4>();
    homogenise(L, true);
    homogenise(planes, false);
    SymBatch<double> P = SymBatch<double>::Zero(n, 10), R = SymBatch<double>::Zero(n, 10), B = SymBatch<double>::Zero(n, 10);
    Vec4Batch<double> pi = Vec4Batch<double>::Zero(n, 4);
    AffineBatch<double> M = AffineBatch<double>::Zero(n, 12);
    for (Method m : {Method::direct, Method::paper}) {
      say(std::string("bench: shadow double ") + method_name(m));
      add_row("shadow", "double", method_name(m),
              median_time(opt.repeats, [&] { shadow_batch<double>(A, L, m, P, pi, R, T); }), shadow_bytes);
      say(std::string("bench: reflection double ") + method_name(m));
      add_row("reflection", "double", method_name(m),
              median_time(opt.repeats, [&] { reflection_batch<double>(A, planes, m, M, B, T); }), (10 + 4) * 8 + (12 + 10) * 8);
    }
  }
  say("bench: memory bandwidth again");
  bandwidth = std::max(bandwidth, copy_bandwidth(static_cast<std::size_t>(n) * shadow_bytes, T));
  {  // ---- certified intervals: Interval_nt<false> with the rounding mode set once per thread;
     //      the batch runs them as IntervalPack, W per instruction (exact/interval_pack.hpp)
    using I = CGAL::Interval_nt<false>;
    auto guard = [] { return CGAL::Protect_FPU_rounding<true>(); };
    SymBatch<I> A(n, 10);
    Vec4Batch<I> L(n, 4), planes(n, 4);
    {
      const SymBatch<double> a = qa.rounded<double, 10>();
      Vec4Batch<double> l = ql.rounded<double, 4>(), p = ql.rounded<double, 4>();
      homogenise(l, true);
      homogenise(p, false);
      A = a.cast<I>();
      L = l.cast<I>();
      planes = p.cast<I>();
    }
    SymBatch<I> P(n, 10), R(n, 10), B(n, 10);
    Vec4Batch<I> pi(n, 4);
    AffineBatch<I> M(n, 12);
    P.setZero(), R.setZero(), B.setZero(), pi.setZero(), M.setZero();
    say("bench: shadow interval");
    add_row("shadow", "interval", "direct",
            median_time(opt.repeats, [&] { shadow_batch<I>(A, L, Method::direct, P, pi, R, T, guard); }), 2 * shadow_bytes);
    say("bench: reflection interval");
    add_row("reflection", "interval", "direct", median_time(opt.repeats, [&] {
              reflection_batch<I>(A, planes, Method::direct, M, B, T, false, guard);
            }),
            2 * ((10 + 4) * 8 + (12 + 10) * 8));
  }
  {  // ---- exact: denominators cleared per item, 128-bit integer arithmetic, no gcd, no division
    SymBatch<Int> P(n, 10), R(n, 10), B(n, 10);
    Vec4Batch<Int> pi(n, 4);
    AffineBatch<Int> M(n, 12);
    P.setZero(), R.setZero(), B.setZero(), pi.setZero(), M.setZero();
    std::atomic<long> beyond_bound{0};  // items of the current row beyond the 128-bit bound
    auto load = [&](Eigen::Index i, Mat4<Int>& a, Vec4<Int>& l, bool light) {
      std::int32_t d[10];
      for (int k = 0; k < 10; ++k) d[k] = qa.den(i, k);
      const long la = lcm_of(d, 10);
      for (int k = 0; k < 10; ++k) {
        const Int v = Int(qa.num(i, k)) * (la / qa.den(i, k));
        a(kSymRow[k], kSymCol[k]) = a(kSymCol[k], kSymRow[k]) = v;
      }
      for (int k = 0; k < 4; ++k) d[k] = ql.den(i, k);
      const long ll = lcm_of(d, light ? 3 : 4);
      for (int k = 0; k < 4; ++k) l(k) = Int(ql.num(i, k)) * (ll / ql.den(i, k));
      if (light) l(3) = Int(ll);  // the point (x, y, z, 1) times its common denominator
      else if (l(2) == 0) l(2) = Int(ll);
    };
    auto shadow_exact = [&](Eigen::Index b, Eigen::Index e) {
      Mat4<Int> a;
      Vec4<Int> l;
      for (Eigen::Index i = b; i < e; ++i) {
        load(i, a, l, true);
        // bit bound: |P| < 2^(3 bits(A) + 2 bits(L) + 5) must fit in 127 bits
        if (3 * bits(max_abs(a)) + 2 * bits(max_abs(l)) + 5 > 126) {
          ++beyond_bound;
          continue;
        }
        const Vec4<Int> p = polar_plane<Int>(a, l);
        scatter_sym(P, i, tangent_cone_from_polar<Int>(a, l, p));
        pi.row(i) = p.transpose();
        scatter_sym(R, i, terminator_quadric_from_polar<Int>(l, p));
      }
    };
    auto reflection_exact = [&](Eigen::Index b, Eigen::Index e) {
      Mat4<Int> a;
      Vec4<Int> pl;
      for (Eigen::Index i = b; i < e; ++i) {
        load(i, a, pl, false);
        if (bits(max_abs(a)) + 6 * bits(max_abs(pl)) + 8 > 126) {
          ++beyond_bound;
          continue;
        }
        const Mat4<Int> m = scaled_mirror_matrix<Int>(pl);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 4; ++c) M(i, 4 * r + c) = m(r, c);
        scatter_sym(B, i, mirror_image<Int>(a, m));
      }
    };
    auto exact_row = [&](const char* op, auto& kernel, std::size_t bytes, const char* arithmetic) {
      say(std::string("bench: ") + op + " exact");
      beyond_bound = 0;
      add_row(op, "exact", "direct", median_time(opt.repeats, [&] { parallel_for(n, T, kernel); }), bytes,
              {{"arithmetic", arithmetic}});
      if (beyond_bound > 0) rows.back()["items_beyond_bit_bound"] = beyond_bound.load() / opt.repeats;
    };
    exact_row("shadow", shadow_exact, (10 + 4) * 8 + (10 + 4 + 10) * 16,
              "128-bit integers after clearing each item's denominators (bit bound checked)");
    exact_row("reflection", reflection_exact, (10 + 4) * 8 + (12 + 10) * 16,
              "128-bit integers, division-free (n.n) M, bit bound checked");
  }
  // roofline fractions and cost ratios against double/direct
  for (auto& r : rows) {
    r["roofline_fraction"] = r["items_per_s"].get<double>() * r["bytes_per_item"].get<double>() / bandwidth;
    for (const auto& d : rows)
      if (d["op"] == r["op"] && d["precision"] == "double" && d["method"] == "direct")
        r["cost_vs_double_direct"] = d["items_per_s"].get<double>() / r["items_per_s"].get<double>();
  }
  return {{"format", "qverify-bench/1"},
          {"threads", T},
          {"n", n},
          {"memory_bandwidth_gbps", bandwidth / 1e9},
          {"bandwidth_method", "parallel stream copy (non-temporal stores, like the double batches) of as many bytes as the double shadow row moves (read + write), best of 3, before and after the double rows; the larger"},
          {"inputs", "random rationals p/q, |p| <= 20, 1 <= q <= 9 (doubles: rounded once; exact: as p and q)"},
          {"timing", "median of " + std::to_string(opt.repeats) + " runs over all n items, outputs pre-allocated"},
          {"simd", {{"lanes", DoublePack::size()},
                    {"instruction_set", instruction_set()},
                    {"note", "double and interval batches run W items per instruction (core/pack.hpp)"}}},
          {"rows", rows}};
}

}  // namespace qverify
