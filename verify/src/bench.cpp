#include <qverify/core/batch.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/verify/bench.hpp>
#include <qverify/verify/eval.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <numeric>
#include <random>
#include <tuple>
#include <vector>

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

/// The lights, which are also the mirror planes: points (x, y, z, 1) with z != 0
/// (a zero z becomes 1), so that the plane x X + y Y + z Z + 1 = 0 has a normal.
template <class M> void homogenise(M& L) {
  for (Eigen::Index i = 0; i < L.rows(); ++i) {
    L(i, 3) = typename M::Scalar(1);
    if (L(i, 2) == typename M::Scalar(0)) L(i, 2) = typename M::Scalar(1);
  }
}

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Runs every job once per round, `rounds` rounds, always in the same order, and
/// returns each job's times (job-major). Interleaving makes every row, and the
/// bandwidth copy, sample the same moments of a shared machine: a ratio of two
/// rows (interval against double) or of a row to the bandwidth then measures the
/// code, not which minute each was timed in.
std::vector<std::vector<double>> interleaved_times(int rounds, const std::vector<std::function<void()>>& jobs,
                                                   const std::function<void(int)>& before_round) {
  std::vector<std::vector<double>> t(jobs.size());
  for (int r = 0; r < rounds; ++r) {
    before_round(r);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      const auto t0 = Clock::now();
      jobs[j]();
      t[j].push_back(seconds_since(t0));
    }
  }
  return t;
}

double best_of(const std::vector<double>& t) { return *std::min_element(t.begin(), t.end()); }
double median_of(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// Stream copy of as many bytes as `bytes` (half read, half written) on `threads`
/// threads: one sample of the machine's sustainable bandwidth. The copy writes with
/// non-temporal stores, as the double batches do (a plain memcpy may read every
/// destination line first and then understates what the machine moves).
struct StreamCopy {
  Eigen::VectorXd src, dst;
  explicit StreamCopy(std::size_t bytes) {
    const auto half = static_cast<Eigen::Index>(bytes / 2 / sizeof(double) / 2 * 2);
    src = Eigen::VectorXd::Constant(half, 1.0);
    dst = Eigen::VectorXd::Zero(half);
  }
  double bytes() const { return static_cast<double>(2 * src.size() * sizeof(double)); }
  void operator()(int threads) {
    parallel_for(src.size() / 2, threads, [&](Eigen::Index b, Eigen::Index e) {
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
  }
};

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

constexpr std::size_t kShadowBytes = (10 + 4) * 8 + (10 + 4 + 10) * 8;  ///< double A, L in; P, pi, R out
constexpr std::size_t kReflectionBytes = (10 + 4) * 8 + (12 + 10) * 8;  ///< double A, plane in; M, B out

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

std::size_t bench_bytes_per_item() {
  // double and interval inputs (A, L), outputs of both ops, and the copy's two halves
  return (10 + 4) * 8 * 3 + ((10 + 4 + 10) + (12 + 10)) * 8 * 3 + kShadowBytes;
}

json run_bench(const BenchOptions& opt) {
  const Eigen::Index n = opt.n;
  const int T = opt.threads;
  const int rounds = opt.repeats;
  json rows = json::array();
  auto say = [&](const std::string& s) {
    if (opt.progress) opt.progress(s);
  };
  auto per_item_ns = [&](const std::vector<double>& times) {
    json a = json::array();
    for (double t : times) a.push_back(1e9 * t / static_cast<double>(n));
    return a;
  };
  auto add_row = [&](const char* op, const char* precision, const char* method, const std::vector<double>& times,
                     std::size_t bytes, json extra = json::object()) {
    const double ips = static_cast<double>(n) / best_of(times);
    json r{{"op", op},
           {"precision", precision},
           {"method", method},
           {"items_per_s", ips},
           {"ns_per_item", 1e9 / ips},
           {"ns_per_item_median", 1e9 * median_of(times) / static_cast<double>(n)},
           {"ns_per_item_runs", per_item_ns(times)},
           {"bytes_per_item", bytes},
           {"roofline_fraction", nullptr}};  // once the bandwidth is final
    for (auto& [k, v] : extra.items()) r[k] = v;
    rows.push_back(r);
  };
  auto progress = [&](const char* what) {
    return [&, what](int r) {
      say("bench: " + std::string(what) + ", round " + std::to_string(r + 1) + "/" + std::to_string(rounds));
    };
  };
  // Certified intervals: Interval_nt<false> with the rounding mode set once per thread; the
  // batch runs them as IntervalPack, W per instruction (exact/interval_pack.hpp).
  using I = CGAL::Interval_nt<false>;
  auto guard = [] { return CGAL::Protect_FPU_rounding<true>(); };

  // The bandwidth: a stream copy of as many bytes as the double shadow row moves.
  StreamCopy copy(static_cast<std::size_t>(n) * kShadowBytes);
  std::vector<double> copy_times;
  {  // ---- double and interval, both ops: every round runs the copy, the four direct rows, the copy
    SymBatch<double> A;
    Vec4Batch<double> L;
    {
      const RationalInputs qa(n, 10, 1), ql(n, 4, 2);
      A = qa.rounded<double, 10>();
      L = ql.rounded<double, 4>();
    }
    homogenise(L);
    const SymBatch<I> AI = A.cast<I>();
    const Vec4Batch<I> LI = L.cast<I>();
    SymBatch<double> P = SymBatch<double>::Zero(n, 10), R = SymBatch<double>::Zero(n, 10),
                     B = SymBatch<double>::Zero(n, 10);
    Vec4Batch<double> pi = Vec4Batch<double>::Zero(n, 4);
    AffineBatch<double> M = AffineBatch<double>::Zero(n, 12);
    SymBatch<I> PI(n, 10), RI(n, 10), BI(n, 10);
    Vec4Batch<I> piI(n, 4);
    AffineBatch<I> MI(n, 12);
    PI.setZero(), RI.setZero(), BI.setZero(), piI.setZero(), MI.setZero();
    auto t = interleaved_times(
        rounds,
        {[&] { copy(T); }, [&] { shadow_batch<double>(A, L, Method::direct, P, pi, R, T); },
         [&] { reflection_batch<double>(A, L, Method::direct, M, B, T); },
         [&] { shadow_batch<I>(AI, LI, Method::direct, PI, piI, RI, T, guard); },
         [&] { reflection_batch<I>(AI, LI, Method::direct, MI, BI, T, false, guard); }, [&] { copy(T); }},
        progress("stream copy, double and interval direct rows"));
    copy_times = t[0];
    copy_times.insert(copy_times.end(), t[5].begin(), t[5].end());
    add_row("shadow", "double", "direct", t[1], kShadowBytes);
    add_row("reflection", "double", "direct", t[2], kReflectionBytes);
    add_row("shadow", "interval", "direct", t[3], 2 * kShadowBytes);
    add_row("reflection", "interval", "direct", t[4], 2 * kReflectionBytes);
    // the paper route (one item at a time) against the direct one, on the same items
    t = interleaved_times(rounds,
                          {[&] { shadow_batch<double>(A, L, Method::paper, P, pi, R, T); },
                           [&] { reflection_batch<double>(A, L, Method::paper, M, B, T); }},
                          progress("double paper rows"));
    add_row("shadow", "double", "paper", t[0], kShadowBytes);
    add_row("reflection", "double", "paper", t[1], kReflectionBytes);
  }
  {  // ---- exact: denominators cleared per item, 128-bit integer arithmetic, no gcd, no division
    SymBatch<Int> P(n, 10), R(n, 10), B(n, 10);
    Vec4Batch<Int> pi(n, 4);
    AffineBatch<Int> M(n, 12);
    P.setZero(), R.setZero(), B.setZero(), pi.setZero(), M.setZero();
    // The same items as above, drawn again from the same seeds rather than kept through the
    // double and interval rows (112 bytes per item less at the memory peak).
    const RationalInputs qa(n, 10, 1), ql(n, 4, 2);
    std::atomic<long> beyond_bound{0};  // items of the current row beyond the 128-bit bound
    auto load = [&](Eigen::Index i, Mat4<Int>& a, Vec4<Int>& l) {
      std::int32_t d[10];
      for (int k = 0; k < 10; ++k) d[k] = qa.den(i, k);
      const long la = lcm_of(d, 10);
      for (int k = 0; k < 10; ++k) {
        const Int v = Int(qa.num(i, k)) * (la / qa.den(i, k));
        a(kSymRow[k], kSymCol[k]) = a(kSymCol[k], kSymRow[k]) = v;
      }
      for (int k = 0; k < 4; ++k) d[k] = ql.den(i, k);
      const long ll = lcm_of(d, 3);
      for (int k = 0; k < 3; ++k) l(k) = Int(ql.num(i, k)) * (ll / ql.den(i, k));
      l(3) = Int(ll);  // the point (x, y, z, 1) times its common denominator (as homogenise)
      if (l(2) == 0) l(2) = Int(ll);
    };
    auto shadow_exact = [&](Eigen::Index b, Eigen::Index e) {
      Mat4<Int> a;
      Vec4<Int> l;
      for (Eigen::Index i = b; i < e; ++i) {
        load(i, a, l);
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
        load(i, a, pl);
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
      beyond_bound = 0;
      const auto t = interleaved_times(rounds, {[&] { parallel_for(n, T, kernel); }}, [&](int r) {
        say("bench: " + std::string(op) + " exact, run " + std::to_string(r + 1) + "/" + std::to_string(rounds));
      });
      add_row(op, "exact", "direct", t[0], bytes, {{"arithmetic", arithmetic}});
      if (beyond_bound > 0) rows.back()["items_beyond_bit_bound"] = beyond_bound.load() / rounds;
    };
    exact_row("shadow", shadow_exact, (10 + 4) * 8 + (10 + 4 + 10) * 16,
              "128-bit integers after clearing each item's denominators (bit bound checked)");
    exact_row("reflection", reflection_exact, (10 + 4) * 8 + (12 + 10) * 16,
              "128-bit integers, division-free (n.n) M, bit bound checked");
  }
  // The bandwidth limit: the best copy of all rounds (a shared machine's noise only adds
  // time, to the copy as to the rows, so best against best).
  const double bandwidth = copy.bytes() / best_of(copy_times);
  // roofline fractions and cost ratios against double/direct
  for (auto& r : rows) {
    r["roofline_fraction"] = r["items_per_s"].get<double>() * r["bytes_per_item"].get<double>() / bandwidth;
    for (const auto& d : rows)
      if (d["op"] == r["op"] && d["precision"] == "double" && d["method"] == "direct")
        r["cost_vs_double_direct"] = d["items_per_s"].get<double>() / r["items_per_s"].get<double>();
  }
  // rows by precision, method, op
  auto rank = [](const json& r) {
    const std::string p = r["precision"], m = r["method"];
    return std::make_tuple(p == "double" ? 0 : p == "interval" ? 1 : 2, m == "direct" ? 0 : 1, r["op"] == "shadow" ? 0 : 1);
  };
  std::stable_sort(rows.begin(), rows.end(), [&](const json& x, const json& y) { return rank(x) < rank(y); });
  const std::string R = std::to_string(rounds);
  return {{"format", "qverify-bench/1"},
          {"threads", T},
          {"n", n},
          {"memory_bandwidth_gbps", bandwidth / 1e9},
          {"memory_bandwidth_gbps_runs", [&] {
             json a = json::array();
             for (double t : copy_times) a.push_back(copy.bytes() / t / 1e9);
             return a;
           }()},
          {"bandwidth_method", "parallel stream copy (non-temporal stores, like the double batches) of as many bytes "
                               "as the double shadow row moves (read + write), run at the start and at the end of each of the " + R +
                               " rounds, around the rows; the best copy"},
          {"inputs", "random rationals p/q, |p| <= 20, 1 <= q <= 9 (doubles: rounded once; exact: as p and q): "
                     "quadrics A, and lights (x, y, z, 1) with z != 0 that are also the mirror planes "
                     "x X + y Y + z Z + 1 = 0"},
          {"timing", "best of " + R + " rounds; each round runs the copy, the four double and interval "
                     "direct rows once and the copy again (so that rows and bandwidth sample the same moments of a shared machine, whose "
                     "noise only adds time); then the paper rows, best of " + R + " rounds; then the exact rows, best "
                     "of " + R + " runs; all n items per run, outputs pre-allocated; ns_per_item_runs lists every run, "
                     "ns_per_item_median is the median"},
          {"simd", {{"lanes", DoublePack::size()},
                    {"instruction_set", instruction_set()},
                    {"note", "double and interval batches run W items per instruction (core/pack.hpp)"}}},
          {"rows", rows}};
}

}  // namespace qverify
