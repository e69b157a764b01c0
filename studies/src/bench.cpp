#include <qverify/batch/batch.hpp>
#include <qverify/batch/pages.hpp>
#include <qverify/core/mirror_division_free.hpp>
#include <qverify/exact/digit_batch.hpp>
#include <qverify/exact/double_batch.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/interval_batch.hpp>
#include <qverify/exact/rounding.hpp>
#include <qverify/exact/wide_int.hpp>
#include <qverify/eval/accuracy.hpp>
#include <qverify/studies/bench.hpp>
#include <qverify/eval/eval.hpp>
#include <qverify/verify/point_filter.hpp>

#include <CGAL/Mpzf.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

namespace qverify {

using Int = __int128;

namespace {

using Clock = std::chrono::steady_clock;

// ------------------------------------------------------------------------------ inputs

/// The three kinds of inputs, each with double, interval and exact rows.
enum class Kind { small_rational, double_valued, decimal17 };
constexpr Kind kKinds[] = {Kind::small_rational, Kind::double_valued, Kind::decimal17};
const char* kind_name(Kind k) {
  switch (k) {
    case Kind::small_rational: return "small-rational";
    case Kind::double_valued: return "double-valued";
    case Kind::decimal17: return "decimal-17";
  }
  return "";
}

/// Counter-based random numbers (splitmix64 of the index): value k of a stream
/// is the same whatever thread draws it and in which order.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
std::uint64_t draw(std::uint64_t seed, std::uint64_t k) { return mix(mix(seed) ^ k); }

/// Entry k of item i: A's ten entries are 0..9, the light's x, y, z are 10..12.
std::uint64_t entry_index(Eigen::Index i, int k) { return static_cast<std::uint64_t>(i) * 16 + static_cast<std::uint64_t>(k); }

constexpr std::uint64_t kSeedSmall = 1, kSeedDouble = 18, kSeedDecimal = 1817;

/// A random small rational p/q (|p| <= 20, 1 <= q <= 9): entry k of item i.
struct SmallRational {
  std::int32_t p, q;
};
SmallRational small_rational(Eigen::Index i, int k) {
  const std::uint64_t r = draw(kSeedSmall, entry_index(i, k));
  return {static_cast<std::int32_t>(r % 41) - 20, static_cast<std::int32_t>((r >> 8) % 9) + 1};
}

/// Small rationals of n items as numerator and denominator arrays (14 columns: A's ten
/// entries, the light's x, y, z and w = 1/1), for the exact rows.
struct RationalInputs {
  Eigen::Matrix<std::int32_t, Eigen::Dynamic, 14, Eigen::RowMajor> num, den;
  RationalInputs(Eigen::Index n, int threads) : num(n, 14), den(n, 14) {
    parallel_for(n, threads, [&](Eigen::Index b, Eigen::Index e) {
      for (Eigen::Index i = b; i < e; ++i) {
        for (int k = 0; k < 13; ++k) {
          const SmallRational x = small_rational(i, k);
          num(i, k) = x.p, den(i, k) = x.q;
        }
        num(i, 13) = den(i, 13) = 1;
      }
    });
  }
};

/// A double with a full 53-bit mantissa (top bit set, 52 random bits), |x| in
/// [2^e, 2^(e+1)) with e uniform in -30..30, random sign.
double random_double(std::uint64_t seed, std::uint64_t k) {
  const std::uint64_t r = draw(seed, 2 * k), s = draw(seed, 2 * k + 1);
  const std::uint64_t m = (r >> 11) | (std::uint64_t(1) << 52);
  const int e = static_cast<int>(s % 61) - 30;
  const double x = std::ldexp(static_cast<double>(m), e - 52);
  return (s >> 63) ? -x : x;
}

/// Decimal text with 17 significant digits: m 10^e, 10^16 <= |m| < 10^17,
/// |x| in [10^k, 10^(k+1)) with k uniform in -9..8 (about 2^-30 .. 2^30).
struct Decimal {
  std::int64_t m = 0;
  int e = 0;
};
Decimal random_decimal(std::uint64_t seed, std::uint64_t k) {
  const std::uint64_t r = draw(seed, 2 * k), s = draw(seed, 2 * k + 1);
  const auto m = static_cast<std::int64_t>(10000000000000000ull + r % 90000000000000000ull);
  const int k10 = static_cast<int>(s % 18) - 9;
  return {(s >> 63) ? -m : m, k10 - 16};
}
/// The text of a decimal ("-12345678901234567e-20") into buf (48 bytes); returns its end.
char* decimal_text(const Decimal& d, char* buf) {
  char* p = std::to_chars(buf, buf + 24, d.m).ptr;  // at most 20 characters
  *p++ = 'e';
  return std::to_chars(p, buf + 40, d.e).ptr;
}
/// The double nearest to the decimal text (std::from_chars rounds correctly).
double nearest_double(const Decimal& d) {
  char buf[48];
  const char* end = decimal_text(d, buf);
  double x = 0;
  std::from_chars(buf, end, x);
  return x;
}
Rational pow10_rational(int e) {
  boost::multiprecision::mpz_int p = 1;
  for (int k = 0; k < std::abs(e); ++k) p *= 10;
  return e >= 0 ? Rational(p) : Rational(1) / Rational(p);
}
Rational decimal_value(const Decimal& d) { return Rational(d.m) * pow10_rational(d.e); }

/// Exact inputs of one item of a kind, as rationals (light (x, y, z, 1)).
void exact_item(Kind kind, Eigen::Index i, Mat4<Rational>& A, Vec4<Rational>& L) {
  auto value = [&](int k) {
    if (kind == Kind::double_valued) return Rational(random_double(kSeedDouble, entry_index(i, k)));
    return decimal_value(random_decimal(kSeedDecimal, entry_index(i, k)));
  };
  for (int k = 0; k < 10; ++k) A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = value(k);
  for (int k = 0; k < 3; ++k) L(k) = value(10 + k);
  L(3) = 1;
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

/// The buffers of the double and interval rows and of the bandwidth copy: where each lies, and the bytes
/// advised huge pages (for BenchPages).
struct BufferPages {
  std::vector<std::pair<std::uintptr_t, std::size_t>> spans;  ///< start and bytes of each buffer
  std::size_t advised = 0;

  /// Sizes a buffer to n rows, advised huge pages when `huge` (batch/pages.hpp) before it is first written.
  template <class Derived> void size(Eigen::PlainObjectBase<Derived>& x, Eigen::Index n, bool huge) {
    x.resize(n, Eigen::NoChange);
    if (huge) advised += advise_huge_pages(x);
    spans.emplace_back(reinterpret_cast<std::uintptr_t>(x.data()),
                       sizeof(typename Derived::Scalar) * static_cast<std::size_t>(x.size()));
  }
  std::size_t bytes() const {
    std::size_t b = 0;
    for (const auto& s : spans) b += s.second;
    return b;
  }
};

/// The first line of a text file, or "" when it cannot be read.
std::string first_line(const char* path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

/// The pages the buffers got (BenchPages), taken once they are written: the system's transparent huge page
/// mode, and the huge pages of the mappings that hold them (/proc/self/smaps: each large buffer is a mapping
/// of its own, malloc's mmap; a mapping shared with other data counts at most its bytes of the buffers, so
/// the figure is an upper bound there).
BenchPages bench_pages(const std::vector<const BufferPages*>& buffers) {
  BenchPages p;
  for (const BufferPages* b : buffers) p.advised_bytes += b->advised, p.buffer_bytes += b->bytes();
  p.huge_pages_advised = p.advised_bytes > 0;  // bytes are advised only when asked (BufferPages::size)
  const std::string mode = first_line("/sys/kernel/mm/transparent_hugepage/enabled");  // "always [madvise] never"
  const auto open = mode.find('['), close = mode.find(']');
  if (open != std::string::npos && close != std::string::npos && close > open)
    p.transparent_huge_pages = mode.substr(open + 1, close - open - 1);
  auto buffer_bytes_in = [&](std::uintptr_t lo, std::uintptr_t hi) {  // of the buffers, inside [lo, hi)
    std::size_t inside = 0;
    for (const BufferPages* b : buffers)
      for (const auto& [start, bytes] : b->spans) {
        const std::uintptr_t from = std::max(lo, start), to = std::min(hi, start + bytes);
        if (from < to) inside += to - from;
      }
    return inside;
  };
  std::ifstream in("/proc/self/smaps");
  std::size_t inside = 0;  // the current mapping's bytes of the buffers
  for (std::string line; std::getline(in, line);) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream fields(line);
    if (line.find("AnonHugePages:") == 0) {
      std::string key;
      std::size_t kib = 0;
      // a mapping that holds other data too (the heap) counts no more than its bytes of the buffers
      if (inside > 0 && (fields >> key >> kib)) p.buffer_huge_page_bytes += std::min(kib * 1024, inside);
    } else if (fields >> std::hex >> lo >> dash >> hi && dash == '-') {  // a mapping's first line: "lo-hi perms ..."
      inside = buffer_bytes_in(lo, hi);
    }
  }
  return p;
}

/// Stream copy of as many bytes as `bytes` (half read, half written) on `threads`
/// threads: one sample of the machine's sustainable bandwidth. The copy writes with
/// non-temporal stores of whole vectors of the pack, as the double batches do
/// (stream_pieces: a plain memcpy may read every destination line first and
/// then understates what the machine moves; 16-byte stores, which the batches
/// no longer make, moved less here).
struct StreamCopy {
  static constexpr Eigen::Index W = static_cast<Eigen::Index>(DoublePack::size());
  Eigen::VectorXd src, dst;
  BufferPages pages;
  /// Pages as the rows' buffers get them (`huge`: advised huge pages, FloatBuffers), so that the rows and
  /// their yardstick run on the same kind of pages.
  StreamCopy(std::size_t bytes, bool huge) {
    const auto half = static_cast<Eigen::Index>(bytes / 2 / sizeof(double) / W * W);
    pages.size(src, half, huge), pages.size(dst, half, huge);
    src.setConstant(1.0), dst.setZero();
  }
  double bytes() const { return static_cast<double>(2 * src.size() * sizeof(double)); }
  void operator()(int threads) {
    parallel_for(src.size() / W, threads, [&](Eigen::Index b, Eigen::Index e) {
      const double* s = src.data();
      double* d = dst.data();
      for (Eigen::Index i = W * b; i < W * e; i += W) {
#if defined(__SSE2__)
        if (pack_aligned(d) && pack_aligned(s)) {  // Eigen's storage is aligned to the pack
          __m128d seq[W / 2];
          for (Eigen::Index k = 0; k < W / 2; ++k) seq[k] = _mm_load_pd(s + i + 2 * k);
          stream_pieces(d + i, seq);
          continue;
        }
#endif
        for (Eigen::Index k = 0; k < W; ++k) d[i + k] = s[i + k];
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

// ------------------------------------------------------- exact arithmetic for doubles

/// Exact rows on double-valued and decimal-17 inputs: WideInt<10> (640-bit
/// integers in place, exact/wide_int.hpp) after aligning each matrix's exponents.
using W = WideInt<10>;
constexpr int kWideBits = 64 * W::max_limbs - 1;  ///< two's complement: the top bit is the sign

/// Bit bounds of the results from the bits of the integer inputs (bA for A,
/// bL for the light or plane): |pi_i| < 2^(bA+bL+2), |L.pi| < 2^(bA+2bL+4),
/// |P_ij| < 2^(2bA+2bL+5); the division-free mirror matrix < 2^(2bL+3) and
/// (n.n)^2 B < 2^(bA+4bL+8) (mirror_division_free.hpp). Every intermediate is below
/// its result's bound.
bool shadow_fits(int bA, int bL) { return 2 * bA + 2 * bL + 5 <= kWideBits; }
bool reflection_fits(int bA, int bL) { return bA + 4 * bL + 10 <= kWideBits; }

template <int R, int C> int max_bits(const Eigen::Matrix<W, R, C>& m) {
  int b = 0;
  for (Eigen::Index i = 0; i < m.size(); ++i) b = std::max(b, m(i).bits());
  return b;
}

/// A double-valued item as integers: A = A_int 2^eA, L = L_int 2^eL (each
/// matrix shifted to the smallest binary exponent of its entries). False when
/// an entry does not fit (WideIntOverflow).
bool wide_item(const double* a, const double* l, Mat4<W>& A, Vec4<W>& L, int& eA, int& eL) {
  W ai[10], li[4];
  try {
    eA = wide_from_doubles<10>(a, 10, ai);
    eL = wide_from_doubles<10>(l, 4, li);
  } catch (const WideIntOverflow&) {
    return false;
  }
  for (int k = 0; k < 10; ++k) A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = ai[k];
  for (int k = 0; k < 4; ++k) L(k) = li[k];
  return true;
}

/// A decimal-17 item as integers: A = A_int 10^kA (each matrix scaled to the
/// smallest decimal exponent of its entries). False when an entry does not fit.
bool wide_item(const Decimal* a, const Decimal* l, Mat4<W>& A, Vec4<W>& L, int& kA, int& kL) {
  kA = a[0].e, kL = l[0].e;
  for (int k = 1; k < 10; ++k) kA = std::min(kA, a[k].e);
  for (int k = 1; k < 4; ++k) kL = std::min(kL, l[k].e);
  try {
    for (int k = 0; k < 10; ++k) A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = wide_from_decimal<10>(a[k].m, a[k].e - kA);
    for (int k = 0; k < 4; ++k) L(k) = wide_from_decimal<10>(l[k].m, l[k].e - kL);
  } catch (const WideIntOverflow&) {
    return false;
  }
  return true;
}

/// Exact results of one item, kept in a per-thread ring (the rows time the
/// computation and its stores, not memory for n results of varying size).
struct WideShadowOut {
  W P[10], pi[4], R[10];
  int scale = 0;  ///< the results are these integers times base^scale
};
struct WideReflectionOut {
  W M[12], B[10];
  int scale = 0;
};
constexpr std::size_t kRing = 1024;
constexpr Eigen::Index kCandidateItems = 4000;  ///< items for the exact arithmetic candidates

void wide_shadow(const Mat4<W>& A, const Vec4<W>& L, WideShadowOut& o) {
  const Vec4<W> p = polar_plane<W>(A, L);
  const Mat4<W> P = tangent_cone_from_polar<W>(A, L, p);
  const Mat4<W> R = terminator_quadric_from_polar<W>(L, p);
  for (int k = 0; k < 10; ++k) o.P[k] = P(kSymRow[k], kSymCol[k]), o.R[k] = R(kSymRow[k], kSymCol[k]);
  for (int k = 0; k < 4; ++k) o.pi[k] = p(k);
}
void wide_reflection(const Mat4<W>& A, const Vec4<W>& plane, WideReflectionOut& o) {
  const Mat4<W> M = scaled_mirror_matrix<W>(plane);
  const Mat4<W> B = mirror_image_division_free<W>(A, plane);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) o.M[4 * r + c] = M(r, c);
  for (int k = 0; k < 10; ++k) o.B[k] = B(kSymRow[k], kSymCol[k]);
}

/// The exact rows' arithmetic: W items at once in digit blocks (exact/digit_batch.hpp, on
/// DigitPack<24>), in chunks of kDigitChunk items whose results stay in a per-thread buffer until
/// the next chunk's.
constexpr Eigen::Index kDigitChunk = 256;

/// Items beyond the WideInt bound run on GMP rationals (counted; none in this benchmark).
template <class S> void generic_shadow(const Mat4<S>& A, const Vec4<S>& L, Mat4<S>& P, Mat4<S>& R) {
  const Vec4<S> p = polar_plane<S>(A, L);
  P = tangent_cone_from_polar<S>(A, L, p);
  R = terminator_quadric_from_polar<S>(L, p);
}
template <class S> void generic_reflection(const Mat4<S>& A, const Vec4<S>& plane, Mat4<S>& M, Mat4<S>& B) {
  M = scaled_mirror_matrix<S>(plane);
  B = mirror_image_division_free<S>(A, plane);
}

// ------------------------------------------------------------------------- threads

/// Runs f(t, b, e) on `threads` threads over contiguous ranges of [0, n) of about
/// equal weight (weights[i] per element).
template <class F> void weighted_threads(const std::vector<std::size_t>& weights, int threads, F&& f) {
  const std::size_t n = weights.size();
  threads = std::max(1, std::min<int>(threads, static_cast<int>(std::max<std::size_t>(n, 1))));
  const std::size_t total = std::accumulate(weights.begin(), weights.end(), std::size_t(0));
  std::vector<std::size_t> cut{0};
  std::size_t acc = 0;
  for (std::size_t i = 0; i < n && static_cast<int>(cut.size()) < threads; ++i) {
    acc += weights[i];
    if (acc * static_cast<std::size_t>(threads) >= total * cut.size()) cut.push_back(i + 1);
  }
  while (static_cast<int>(cut.size()) <= threads) cut.push_back(n);
  cut.back() = n;
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
    if (cut[t] < cut[t + 1]) pool.emplace_back([&f, t, &cut] { f(t, cut[t], cut[t + 1]); });
  if (cut[0] < cut[1]) f(0, cut[0], cut[1]);
  for (auto& th : pool) th.join();
}

// -------------------------------------------------------------------- verification

constexpr int kVerifySamples = kDefaultSamples;  ///< exact points per item, as `verify`
constexpr double kVerifyAccuracy = kDefaultAccuracy;

Mat4<double> rounded(const Mat4<Rational>& m) {
  Mat4<double> out;
  RoundingReport rep;
  for (Eigen::Index i = 0; i < m.size(); ++i) out(i) = round_rational<double>(m(i), rep);
  return out;
}
Vec4<double> rounded(const Vec4<Rational>& v) {
  Vec4<double> out;
  RoundingReport rep;
  for (int i = 0; i < 4; ++i) out(i) = round_rational<double>(v(i), rep);
  return out;
}

/// One verified shadow item: its exact terminator points (enclosed, and cleared
/// for proof mode), the correctly rounded double results and the exact ones.
struct VerifyShadow {
  FilterPoints pts;    ///< terminator points: P, the polar plane and R
  FilterPoints gen;    ///< points of the cone's generator lines: P
  FilterPoints plane;  ///< rational points of the polar plane inside the object: R
  Mat4<double> P, R;
  Vec4<double> pi;
  IntegerQuadric Pe, Re;
  IntegerPlane pie;
  std::size_t pairs() const { return 3 * pts.exact.size() + gen.exact.size() + plane.exact.size(); }
  std::size_t points() const { return pts.exact.size() + gen.exact.size() + plane.exact.size(); }
};
struct VerifyReflection {
  FilterPoints pts;
  Mat4<double> B;
  IntegerQuadric Be;
};

}  // namespace

long bench_exact_items(long n) { return std::max(1000L, n / 10); }
int bench_verify_items(long n) { return static_cast<int>(std::clamp(n / 50000, 8L, 200L)); }

std::size_t bench_bytes_per_item() {
  // double and interval inputs (A, L), outputs of both ops, and the copy's two halves
  return (10 + 4) * 8 * 3 + ((10 + 4 + 10) + (12 + 10)) * 8 * 3 + kShadowBytes;
}

ProcessorInfo processor_info() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, flags;
  ProcessorInfo p;
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (p.vendor) break;  // the first processor's block
      continue;
    }
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim(line.substr(0, colon)), value = trim(line.substr(colon + 1));
    if (key == "vendor_id" && !value.empty()) p.vendor = value;
    else if (key == "model name" && !value.empty()) p.model_name = value;
    else if (key == "cpu family") p.family = std::atoi(value.c_str());
    else if (key == "model") p.model = std::atoi(value.c_str());
    else if (key == "flags") flags = " " + value + " ";
  }
  for (const auto& [flag, name] : {std::pair{"sse2", "SSE2"}, {"avx2", "AVX2"}, {"avx512f", "AVX-512"}, {"avx512ifma", "AVX-512 IFMA"}})
    if (flags.find(std::string(" ") + flag + " ") != std::string::npos) p.supports.push_back(name);
  p.instruction_set = build_instruction_set();
  p.double_kernel = double_batch_kernel();
  p.interval_kernel = interval_batch_kernel();
  p.exact_kernel = digit_blocks_kernel();
  p.exact_lanes = digit_blocks_lanes();
  p.lanes = double_batch_lanes();
  p.logical_cpus = std::thread::hardware_concurrency();
  return p;
}

namespace {

// ------------------------------------------------------------------------------ rows

/// Each run's time per item, in ns (a row's ns_per_item_runs).
std::vector<double> per_item_ns(const std::vector<double>& times, double items) {
  std::vector<double> out;
  for (double t : times) out.push_back(1e9 * t / items);
  return out;
}

/// A batch row: `items` items per run, `times` the runs (best of them: items_per_s).
BenchRow batch_row(Kind kind, const char* op, const char* precision, const char* method, const std::vector<double>& times,
                   std::size_t bytes, Eigen::Index items) {
  BenchRow r;
  r.op = op, r.precision = precision, r.method = method, r.inputs = kind_name(kind);
  r.n = items;
  r.items_per_s = static_cast<double>(items) / best_of(times);
  r.ns_per_item = 1e9 / r.items_per_s;
  r.ns_per_item_median = 1e9 * median_of(times) / static_cast<double>(items);
  r.ns_per_item_runs = per_item_ns(times, static_cast<double>(items));
  r.bytes_per_item = bytes;
  return r;
}

/// A verification row on double-valued items: a point check counts as an item (items_per_s = points per s).
BenchRow verify_row(const char* op, const char* precision, const char* method, const std::vector<double>& times,
                    const FilterCounts& c, int threads, std::size_t distinct, int passes, std::size_t bytes,
                    std::size_t items) {
  const double checks = static_cast<double>(c.checked);
  BenchRow r;
  r.op = op, r.precision = precision, r.method = method, r.inputs = kind_name(Kind::double_valued);
  r.n = static_cast<long>(items);
  r.items_per_s = checks / best_of(times);
  r.ns_per_item = 1e9 / r.items_per_s;
  r.ns_per_item_median = 1e9 * median_of(times) / checks;
  r.ns_per_item_runs = per_item_ns(times, checks);
  r.bytes_per_item = bytes;
  r.verify = VerifyRowFacts{c, threads, distinct, passes};
  return r;
}

/// Roofline fractions (items/s x bytes/item against the bandwidth), cost ratios against double/direct of the
/// same op and inputs (the verification rows: against their double, filtered row), then the rows in the
/// report's order: op group (batch, then verification), inputs, precision, method, op.
void finish_rows(std::vector<BenchRow>& rows, double bandwidth) {
  for (auto& r : rows) {
    r.roofline_fraction = r.items_per_s * static_cast<double>(r.bytes_per_item) / bandwidth;
    for (const auto& d : rows)
      if (d.op == r.op && d.inputs == r.inputs && d.precision == "double" && (d.method == "direct" || d.method == "filtered"))
        r.cost_vs_double_direct = d.items_per_s / r.items_per_s;
  }
  auto rank = [](const BenchRow& r) {
    const std::string &p = r.precision, &m = r.method, &in = r.inputs, &op = r.op;
    const bool verify = op.rfind("verify", 0) == 0;
    return std::make_tuple(verify, in == "small-rational" ? 0 : in == "double-valued" ? 1 : 2,
                           p == "double" ? 0 : p == "interval" ? 1 : 2, m == "paper" ? 1 : 0,
                           op == "shadow" || op == "verify-shadow" ? 0 : 1);
  };
  std::stable_sort(rows.begin(), rows.end(), [&](const BenchRow& x, const BenchRow& y) { return rank(x) < rank(y); });
}

// ---------------------------------------------------------------- double and interval rows

/// Certified intervals: Interval_nt<false> with the rounding mode set once per thread; the batch runs them as
/// IntervalPack, W per instruction (exact/interval_pack.hpp).
using I = CGAL::Interval_nt<false>;

/// The double and interval inputs and outputs of n items: the buffers of the benchmark's largest phase, into
/// which every kind of input is converted in turn (fill).
struct FloatBuffers {
  SymBatch<double> A;
  Vec4Batch<double> L;
  SymBatch<I> AI;
  Vec4Batch<I> LI;
  SymBatch<double> P, R, B;
  Vec4Batch<double> pi;
  AffineBatch<double> M;
  SymBatch<I> PI, RI, BI;
  Vec4Batch<I> piI;
  AffineBatch<I> MI;

  BufferPages pages;  ///< where the buffers lie and what was advised

  /// Allocates the buffers of n items, each advised huge pages when `huge` (before anything is written to it,
  /// as the batch functions do for the outputs they allocate: batch/pages.hpp), the outputs zeroed.
  FloatBuffers(Eigen::Index n, bool huge) {
    auto size = [&](auto&... x) { (pages.size(x, n, huge), ...); };
    size(A, L, AI, LI, P, R, B, pi, M, PI, RI, BI, piI, MI);
    P.setZero(), R.setZero(), B.setZero(), pi.setZero(), M.setZero();
    PI.setZero(), RI.setZero(), BI.setZero(), piI.setZero(), MI.setZero();
  }

  /// The inputs of one kind, converted into A, L (doubles) and AI, LI (intervals); returns the seconds it took
  /// (untimed by the rows: the report's generation_s).
  double fill(Kind kind, Eigen::Index n, int threads) {
    const auto t0 = Clock::now();
    if (kind == Kind::small_rational) fill_small_rational(n, threads);
    else fill_double_or_decimal(kind, n, threads);
    return seconds_since(t0);
  }

 private:
  /// doubles: p/q rounded once; intervals: the enclosure of p/q. Lights (x, y, z, 1) with z != 0 (a zero z
  /// becomes 1), so that the mirror plane has a normal.
  void fill_small_rational(Eigen::Index n, int threads) {
    parallel_for(n, threads, [&](Eigen::Index b, Eigen::Index e) {
      for (Eigen::Index i = b; i < e; ++i) {
        for (int k = 0; k < 13; ++k) {
          const SmallRational x = small_rational(i, k);
          const double v = static_cast<double>(x.p) / static_cast<double>(x.q);
          if (k < 10) A(i, k) = v;
          else L(i, k - 10) = v;
        }
        L(i, 3) = 1;
        if (L(i, 2) == 0) L(i, 2) = 1;
      }
      CGAL::Protect_FPU_rounding<true> up;  // the intervals round outwards
      for (Eigen::Index i = b; i < e; ++i) {
        for (int k = 0; k < 13; ++k) {
          const SmallRational x = small_rational(i, k);
          const I v = I(static_cast<double>(x.p)) / I(static_cast<double>(x.q));
          if (k < 10) AI(i, k) = v;
          else LI(i, k - 10) = v;
        }
        LI(i, 3) = I(1);
        if (small_rational(i, 12).p == 0) LI(i, 2) = I(1);
      }
    });
  }

  /// double-valued: the doubles themselves (point intervals); decimal-17: the double nearest to the text, and
  /// an enclosure of the text's value (one ulp each side).
  void fill_double_or_decimal(Kind kind, Eigen::Index n, int threads) {
    parallel_for(n, threads, [&](Eigen::Index b, Eigen::Index e) {
      for (Eigen::Index i = b; i < e; ++i)
        for (int k = 0; k < 13; ++k) {
          double x, lo, hi;
          if (kind == Kind::double_valued) {
            x = lo = hi = random_double(kSeedDouble, entry_index(i, k));
          } else {
            x = nearest_double(random_decimal(kSeedDecimal, entry_index(i, k)));
            lo = std::nextafter(x, -HUGE_VAL), hi = std::nextafter(x, HUGE_VAL);
          }
          if (k < 10) A(i, k) = x, AI(i, k) = I(lo, hi);
          else L(i, k - 10) = x, LI(i, k - 10) = I(lo, hi);
        }
      for (Eigen::Index i = b; i < e; ++i) L(i, 3) = 1, LI(i, 3) = I(1);
    });
  }
};

// ------------------------------------------------------------------ exact, small rationals

/// The exact rows on small rationals: each item's denominators cleared (a positive factor: the results are
/// projective), then the generic formulas on 128-bit integers, no gcd, no division; the outputs n items wide.
struct SmallRationalExact {
  SymBatch<Int> P, R, B;
  Vec4Batch<Int> pi;
  AffineBatch<Int> M;
  /// The same items as the double rows', as numerators and denominators (the arrays exist only now: 112
  /// bytes per item less at the memory peak of the double and interval rows).
  const RationalInputs q;
  std::atomic<long> beyond_bound{0};  ///< items beyond the 128-bit bound (GMP would be needed)

  /// Allocates the outputs (zeroed) and makes the inputs of n items on `threads` threads.
  SmallRationalExact(Eigen::Index n, int threads) : P(n, 10), R(n, 10), B(n, 10), pi(n, 4), M(n, 12), q(n, threads) {
    P.setZero(), R.setZero(), B.setZero(), pi.setZero(), M.setZero();
  }

  /// Item i with its denominators cleared: A times the lcm of its entries' denominators, the point
  /// (x, y, z, 1) times its common denominator.
  void load(Eigen::Index i, Mat4<Int>& a, Vec4<Int>& l) const {
    const long la = lcm_of(&q.den(i, 0), 10);
    for (int k = 0; k < 10; ++k) {
      const Int v = Int(q.num(i, k)) * (la / q.den(i, k));
      a(kSymRow[k], kSymCol[k]) = a(kSymCol[k], kSymRow[k]) = v;
    }
    const long ll = lcm_of(&q.den(i, 10), 3);
    for (int k = 0; k < 3; ++k) l(k) = Int(q.num(i, 10 + k)) * (ll / q.den(i, 10 + k));
    l(3) = Int(ll);
    if (l(2) == 0) l(2) = Int(ll);
  }

  /// The shadow rows of items [b, e); bit bound: |P| < 2^(3 bits(A) + 2 bits(L) + 5) must fit in 127 bits.
  void shadow(Eigen::Index b, Eigen::Index e) {
    Mat4<Int> a;
    Vec4<Int> l;
    for (Eigen::Index i = b; i < e; ++i) {
      load(i, a, l);
      if (3 * bits(max_abs(a)) + 2 * bits(max_abs(l)) + 5 > 126) {
        ++beyond_bound;
        continue;
      }
      const Vec4<Int> p = polar_plane<Int>(a, l);
      scatter_sym(P, i, tangent_cone_from_polar<Int>(a, l, p));
      pi.row(i) = p.transpose();
      scatter_sym(R, i, terminator_quadric_from_polar<Int>(l, p));
    }
  }

  /// The reflection rows of items [b, e) (the light as the mirror plane).
  void reflection(Eigen::Index b, Eigen::Index e) {
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
      scatter_sym(B, i, mirror_image_division_free<Int>(a, pl));
    }
  }
};

// ------------------------------------------- exact, double-valued and decimal-17 inputs

/// The exact rows on double-valued or decimal-17 inputs: the first nx items drawn once (doubles, or decimal
/// text as m 10^e), each item made integer by aligning its exponents, W items at once in digit blocks
/// (exact/digit_batch.hpp); an item whose block does not fit, or that ends a chunk, on WideInt<10> (counted in
/// `singly`, per op), and beyond WideInt's bound on GMP rationals (counted in `beyond`). WideInt one item at a time
/// is also a candidate of its own (shadow_wide, reflection_wide).
struct WideExact {
  Kind kind;
  std::vector<double> da, dl;    ///< double-valued: A's ten entries, the light's four, per item
  std::vector<Decimal> ca, cl;   ///< decimal-17: the same as decimals
  std::vector<std::int64_t> cam, clm;  ///< decimal-17 apart, for the digit blocks: mantissas
  std::vector<int> cae, cle;           ///< and exponents
  std::atomic<long> beyond{0}, singly[2] = {0, 0};  ///< singly: [0] shadows, [1] reflections

  /// Draws the first nx items of kind k on `threads` threads (the lights (x, y, z, 1)).
  WideExact(Kind k, Eigen::Index nx, int threads) : kind(k) {
    if (kind == Kind::double_valued) da.resize(static_cast<std::size_t>(nx) * 10), dl.resize(static_cast<std::size_t>(nx) * 4);
    else ca.resize(static_cast<std::size_t>(nx) * 10), cl.resize(static_cast<std::size_t>(nx) * 4);
    parallel_for(nx, threads, [&](Eigen::Index b, Eigen::Index e) {
      for (Eigen::Index i = b; i < e; ++i) {
        const auto u = static_cast<std::size_t>(i);
        for (int k = 0; k < 13; ++k) {
          if (kind == Kind::double_valued) (k < 10 ? da[u * 10 + k] : dl[u * 4 + k - 10]) = random_double(kSeedDouble, entry_index(i, k));
          else (k < 10 ? ca[u * 10 + k] : cl[u * 4 + k - 10]) = random_decimal(kSeedDecimal, entry_index(i, k));
        }
        if (kind == Kind::double_valued) dl[u * 4 + 3] = 1;
        else cl[u * 4 + 3] = Decimal{1, 0};
      }
    });
    if (kind == Kind::decimal17) {
      cam.resize(ca.size()), cae.resize(ca.size()), clm.resize(cl.size()), cle.resize(cl.size());
      for (std::size_t k = 0; k < ca.size(); ++k) cam[k] = ca[k].m, cae[k] = ca[k].e;
      for (std::size_t k = 0; k < cl.size(); ++k) clm[k] = cl[k].m, cle[k] = cl[k].e;
    }
  }

  /// Item i as integers times base^eA and base^eL; false when an entry does not fit.
  bool load(Eigen::Index i, Mat4<W>& A, Vec4<W>& L, int& eA, int& eL) const {
    const auto u = static_cast<std::size_t>(i);
    return kind == Kind::double_valued ? wide_item(&da[u * 10], &dl[u * 4], A, L, eA, eL)
                                       : wide_item(&ca[u * 10], &cl[u * 4], A, L, eA, eL);
  }

  /// GMP rationals for an item beyond the bound.
  void fallback(Eigen::Index i, bool shadow) {
    ++beyond;
    Mat4<Rational> A, X, Y;
    Vec4<Rational> L;
    exact_item(kind, i, A, L);
    if (shadow) generic_shadow<Rational>(A, L, X, Y);
    else generic_reflection<Rational>(A, L, X, Y);
  }

  /// The shadow of item i on WideInt (GMP rationals beyond its bound) into o.
  void shadow_item(Eigen::Index i, WideShadowOut& o) {
    Mat4<W> A;
    Vec4<W> L;
    int eA, eL;
    if (!load(i, A, L, eA, eL) || !shadow_fits(max_bits(A), max_bits(L))) return fallback(i, true);
    try {
      wide_shadow(A, L, o);
    } catch (const WideIntOverflow&) {
      return fallback(i, true);
    }
    o.scale = 2 * eA + 2 * eL;
  }
  /// The reflection of item i on WideInt (the light as the mirror plane).
  void reflection_item(Eigen::Index i, WideReflectionOut& o) {
    Mat4<W> A;
    Vec4<W> L;
    int eA, eL;
    if (!load(i, A, L, eA, eL) || !reflection_fits(max_bits(A), max_bits(L))) return fallback(i, false);
    try {
      wide_reflection(A, L, o);
    } catch (const WideIntOverflow&) {
      return fallback(i, false);
    }
    o.scale = eA + 4 * eL;
  }

  /// The shadows of items [b, e) on WideInt, one item at a time (a candidate).
  void shadow_wide(Eigen::Index b, Eigen::Index e) {
    std::vector<WideShadowOut> ring(kRing);
    for (Eigen::Index i = b; i < e; ++i) shadow_item(i, ring[static_cast<std::size_t>(i) % kRing]);
  }
  void reflection_wide(Eigen::Index b, Eigen::Index e) {
    std::vector<WideReflectionOut> ring(kRing);
    for (Eigen::Index i = b; i < e; ++i) reflection_item(i, ring[static_cast<std::size_t>(i) % kRing]);
  }

  /// Items [b, e) in digit blocks of W (exact/digit_batch.hpp), a chunk at a time, and singly on WideInt
  /// (`one`) where a block does not fit (an entry beyond 126 bits, a result beyond the digits, lanes that
  /// disagree on a decision) and at the end of a chunk that is not a whole number of blocks.
  template <class WideOut, class One> void blocks(DigitOp op, Eigen::Index b, Eigen::Index e, One&& one) {
    DigitBlocks out;
    WideOut single;
    for (Eigen::Index c = b; c < e; c += kDigitChunk) {
      const Eigen::Index n = std::min(kDigitChunk, e - c);
      const auto u = static_cast<std::size_t>(c);
      if (kind == Kind::double_valued) digit_blocks(op, DoubleItems{&da[u * 10], &dl[u * 4], n}, out);
      else digit_blocks(op, DecimalItems{&cam[u * 10], &cae[u * 10], &clm[u * 4], &cle[u * 4], n}, out);
      for (Eigen::Index i = 0; i < n; ++i)
        if (i >= out.blocks() * out.lanes || !out.done[static_cast<std::size_t>(i / out.lanes)]) {
          one(c + i, single);
          ++singly[op == DigitOp::shadow ? 0 : 1];
        }
    }
  }
  void shadow(Eigen::Index b, Eigen::Index e) {
    blocks<WideShadowOut>(DigitOp::shadow, b, e, [this](Eigen::Index i, WideShadowOut& o) { shadow_item(i, o); });
  }
  void reflection(Eigen::Index b, Eigen::Index e) {
    blocks<WideReflectionOut>(DigitOp::reflection, b, e, [this](Eigen::Index i, WideReflectionOut& o) { reflection_item(i, o); });
  }
};

/// The first m double-valued items as matrices of S (for the generic candidates): A and the light.
template <class S> std::pair<std::vector<Mat4<S>>, std::vector<Vec4<S>>> generic_inputs(const WideExact& w, Eigen::Index m) {
  std::pair<std::vector<Mat4<S>>, std::vector<Vec4<S>>> in;
  in.first.resize(static_cast<std::size_t>(m)), in.second.resize(static_cast<std::size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i)
    for (int k = 0; k < 14; ++k) {
      const auto u = static_cast<std::size_t>(i);
      const double v = k < 10 ? w.da[u * 10 + k] : w.dl[u * 4 + k - 10];
      if (k < 10) in.first[u](kSymRow[k], kSymCol[k]) = in.first[u](kSymCol[k], kSymRow[k]) = S(v);
      else in.second[u](k - 10) = S(v);
    }
  return in;
}

/// The shadow and the reflection of those items by the generic formulas on S, as two jobs (`inputs` must
/// outlive them).
template <class S>
std::vector<std::function<void()>> generic_jobs(const std::pair<std::vector<Mat4<S>>, std::vector<Vec4<S>>>& inputs,
                                                Eigen::Index m) {
  const auto* in = &inputs;
  return {[in, m] {
            Mat4<S> X, Y;
            for (Eigen::Index i = 0; i < m; ++i) generic_shadow<S>(in->first[i], in->second[i], X, Y);
          },
          [in, m] {
            Mat4<S> X, Y;
            for (Eigen::Index i = 0; i < m; ++i) generic_reflection<S>(in->first[i], in->second[i], X, Y);
          }};
}

// -------------------------------------------------------------------- verification

/// The verification's items: exact sample points of double-valued items (terminator points, points of A
/// reflected exactly), enclosed and cleared, with their results rounded and exact; items without a real
/// point are left out. Sampling is not part of the timed checks: its wall time is kept apart.
struct VerifyItems {
  std::vector<VerifyShadow> S;
  std::vector<VerifyReflection> Rf;
  double sample_shadow_s = 0, sample_reflection_s = 0;

  /// The exact points of the shadow items (terminator, generator and polar-plane points).
  std::size_t shadow_points() const {
    std::size_t n = 0;
    for (const auto& x : S) n += x.points();
    return n;
  }
  /// The exact reflected points of the reflection items.
  std::size_t reflection_points() const {
    std::size_t n = 0;
    for (const auto& x : Rf) n += x.pts.exact.size();
    return n;
  }
  /// Per shadow item, the weight that balances the threads: the (point, result) pairs it checks.
  std::vector<std::size_t> shadow_weights() const {
    std::vector<std::size_t> w;
    for (const auto& x : S) w.push_back(x.pairs());
    return w;
  }
  /// Per reflection item, its weight: its points (one pair each).
  std::vector<std::size_t> reflection_weights() const {
    std::vector<std::size_t> w;
    for (const auto& x : Rf) w.push_back(x.pts.exact.size());
    return w;
  }
  /// Bytes of the cleared integer points the exact proof reads (bytes_per_item of the exact rows).
  std::size_t shadow_proof_bytes() const {
    std::size_t b = 0;
    for (const auto& x : S) b += x.pts.cleared.limb_bytes() + x.gen.cleared.limb_bytes() + x.plane.cleared.limb_bytes();
    return b;
  }
  /// The same for the reflection items.
  std::size_t reflection_proof_bytes() const {
    std::size_t b = 0;
    for (const auto& x : Rf) b += x.pts.cleared.limb_bytes();
    return b;
  }
};

/// Samples the first K double-valued items on `threads` threads (item_seed(1, 1, A, L) for shadows,
/// item_seed(1, 2, A, plane) for reflections, as verify).
VerifyItems sample_verify_items(int K, int threads) {
  std::vector<std::optional<VerifyShadow>> vs(static_cast<std::size_t>(K));
  std::vector<std::optional<VerifyReflection>> vr(static_cast<std::size_t>(K));
  const std::vector<std::size_t> ones(static_cast<std::size_t>(K), 1);
  VerifyItems out;
  auto t0 = Clock::now();
  weighted_threads(ones, threads, [&](int, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Mat4<Rational> A;
      Vec4<Rational> L;
      exact_item(Kind::double_valued, static_cast<Eigen::Index>(i), A, L);
      ItemPoints ip = terminator_points(A, L, kVerifySamples, item_seed(1, 1, A, L));
      if (ip.points.empty()) continue;
      const Vec4<Rational> pe = polar_plane<Rational>(A, L);
      const Mat4<Rational> Pe = tangent_cone_from_polar<Rational>(A, L, pe), Re = terminator_quadric_from_polar<Rational>(L, pe);
      vs[i].emplace(VerifyShadow{FilterPoints(std::move(ip.points), ip.size, kVerifyAccuracy),
                                 FilterPoints(std::move(ip.generators), ip.size, kVerifyAccuracy),
                                 FilterPoints(std::move(ip.plane), ip.size, kVerifyAccuracy), rounded(Pe),
                                 rounded(Re), rounded(pe), IntegerQuadric(Pe), IntegerQuadric(Re), IntegerPlane(pe)});
    }
  });
  out.sample_shadow_s = seconds_since(t0);
  t0 = Clock::now();
  weighted_threads(ones, threads, [&](int, std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Mat4<Rational> A;
      Vec4<Rational> plane;
      exact_item(Kind::double_valued, static_cast<Eigen::Index>(i), A, plane);
      ItemPoints ip = reflected_points(A, reference_mirror(plane), kVerifySamples, item_seed(1, 2, A, plane));
      if (ip.points.empty()) continue;
      const Mat4<Rational> Be = mirror_image_of_plane<Rational>(A, plane);
      vr[i].emplace(VerifyReflection{FilterPoints(std::move(ip.points), ip.size, kVerifyAccuracy), rounded(Be),
                                     IntegerQuadric(Be)});
    }
  });
  out.sample_reflection_s = seconds_since(t0);
  for (auto& x : vs)
    if (x) out.S.push_back(std::move(*x));
  for (auto& x : vr)
    if (x) out.Rf.push_back(std::move(*x));
  return out;
}

/// Passes over the points per run of a filtered row: about 4 10^6 filtered checks (the same checks repeated:
/// a check keeps nothing from the previous pass).
int passes_for(std::size_t pairs) {
  return pairs == 0 ? 1 : static_cast<int>(std::max<std::size_t>(1, (4000000 + pairs - 1) / pairs));
}

/// The timed verification jobs' times and counts (over all threads, one run each), in the order
/// filtered shadow, filtered reflection, exact shadow, exact reflection.
struct VerifyTimes {
  std::vector<std::vector<double>> t;
  FilterCounts counts[4];
};

/// The counts of every thread added up.
FilterCounts total(const std::vector<FilterCounts>& v) {
  FilterCounts s;
  for (const auto& c : v) s += c;
  return s;
}

// ------------------------------------------------------------------------- the run

/// One run of the benchmark: the rows in the order they are measured (double and interval, paper, exact,
/// verification), each phase a function of its own with its own buffers, sharing the run's options, rows,
/// bandwidth copies and the sections they fill; then the report.
class BenchRun {
 public:
  /// The run's sizes from the options, and the bandwidth copy's buffers (allocated first, as they stay to the end).
  explicit BenchRun(const BenchOptions& opt)
      : opt_(opt), n_(opt.n), T_(opt.threads), rounds_(opt.repeats),
        nx_(std::min<Eigen::Index>(n_, bench_exact_items(n_))),
        copy_(static_cast<std::size_t>(n_) * kShadowBytes, opt.huge_pages) {}

  /// The double and interval rows, direct (interleaved with the bandwidth copy) and paper, on every kind of input.
  void float_rows() {
    FloatBuffers buf(n_, opt_.huge_pages);
    direct_rows(buf);
    paper_rows(buf);
  }

  /// The exact rows on small rationals: denominators cleared per item, 128-bit integers, no gcd, no division.
  void small_rational_exact_rows() {
    SmallRationalExact x(n_, T_);
    const auto t = interleaved_times(rounds_,
                                     {[&] { parallel_for(n_, T_, [&](Eigen::Index b, Eigen::Index e) { x.shadow(b, e); }); },
                                      [&] { parallel_for(n_, T_, [&](Eigen::Index b, Eigen::Index e) { x.reflection(b, e); }); }},
                                     progress("small-rational: exact rows"));
    const std::string how = "128-bit integers after clearing each item's denominators, no gcd, no division (bit bound checked)";
    rows_.push_back(batch_row(Kind::small_rational, "shadow", "exact", "direct", t[0], (10 + 4) * 8 + (10 + 4 + 10) * 16, n_));
    rows_.back().arithmetic = how;
    rows_.push_back(batch_row(Kind::small_rational, "reflection", "exact", "direct", t[1], (10 + 4) * 8 + (12 + 10) * 16, n_));
    rows_.back().arithmetic = how + "; the division-free mirror matrix (n.n) M and (n.n)^2 B in rank-one form (core/mirror_division_free.hpp)";
    mark_beyond_bound(x.beyond_bound.load());
  }

  /// The exact rows on double-valued or decimal-17 inputs (WideInt<10> after aligning exponents), on the
  /// first nx items; on double-valued inputs also the candidates for exact arithmetic.
  void wide_exact_rows(Kind kind) {
    WideExact w(kind, nx_, T_);
    const auto t = interleaved_times(rounds_,
                                     {[&] { parallel_for(nx_, T_, [&](Eigen::Index b, Eigen::Index e) { w.shadow(b, e); }); },
                                      [&] { parallel_for(nx_, T_, [&](Eigen::Index b, Eigen::Index e) { w.reflection(b, e); }); }},
                                     progress(std::string(kind_name(kind)) + ": exact rows"));
    const std::string lanes = std::to_string(digit_blocks_lanes());
    const std::string how =
        (kind == Kind::double_valued
             ? "integers after shifting each matrix's doubles to the smallest binary exponent among its entries (the "
               "exact results times a power of two), "
             : "integers after scaling each matrix's decimal text m 10^e to the smallest decimal exponent among its "
               "entries (the exact results times a power of ten), ") +
        lanes + " items at once in digit blocks (exact/digit_batch.hpp; " + digit_blocks_kernel() +
        "): DigitPack<24>, signed digits of radix 2^28 in SIMD lanes, lazy carries, one 32x32-bit multiply per "
        "digit product for all lanes; results normalized. No gcd, no division; a block that does not fit item by "
        "item on WideInt<10> (items_singly), GMP rationals beyond that (items_beyond_bit_bound)";
    const std::size_t in_bytes = (10 + 4) * (kind == Kind::double_valued ? 8 : sizeof(Decimal));
    rows_.push_back(batch_row(kind, "shadow", "exact", "direct", t[0], in_bytes + sizeof(WideShadowOut), nx_));
    rows_.back().arithmetic = how;
    rows_.push_back(batch_row(kind, "reflection", "exact", "direct", t[1], in_bytes + sizeof(WideReflectionOut), nx_));
    rows_.back().arithmetic = how + "; the division-free mirror matrix (n.n) M and (n.n)^2 B in rank-one form (core/mirror_division_free.hpp)";
    for (int k : {2, 1}) {
      rows_[rows_.size() - k].results = "kept per thread until the next chunk of " + std::to_string(kDigitChunk) +
                                        " items (bytes_per_item: the results as WideInt<10>)";
      rows_[rows_.size() - k].items_singly = w.singly[2 - k].load() / rounds_;  // k = 2: the shadow row
    }
    mark_beyond_bound(w.beyond.load());
    if (kind == Kind::double_valued) exact_candidates(w);
  }

  /// The verification rows: the filtered point check and the exact proof, on double-valued items.
  void verification_rows() {
    const int K = bench_verify_items(n_);
    say("bench: sampling " + std::to_string(kVerifySamples) + " exact points on " + std::to_string(K) +
        " double-valued items (terminators and mirror images)");
    const VerifyItems v = sample_verify_items(K, T_);
    const std::size_t shadow_points = v.shadow_points(), reflection_points = v.reflection_points();
    const std::vector<std::size_t> ws = v.shadow_weights();
    const int ps = passes_for(std::accumulate(ws.begin(), ws.end(), std::size_t(0))), pr = passes_for(reflection_points);
    const VerifyTimes vt = timed_checks(v, ps, pr);
    auto add = [&](const char* op, const char* precision, const char* method, int j, std::size_t distinct, int passes,
                   std::size_t bytes, std::size_t items) {
      if (vt.counts[j].checked == 0) return;  // no item had a real point to sample
      rows_.push_back(verify_row(op, precision, method, vt.t[j], vt.counts[j], T_, distinct, passes, bytes, items));
    };
    add("verify-shadow", "double", "filtered", 0, shadow_points, ps, sizeof(EnclosedPoint), v.S.size());
    add("verify-reflection", "double", "filtered", 1, reflection_points, pr, sizeof(EnclosedPoint), v.Rf.size());
    add("verify-shadow", "exact", "exact", 2, shadow_points, 1, shadow_points ? v.shadow_proof_bytes() / shadow_points : 0,
        v.S.size());
    add("verify-reflection", "exact", "exact", 3, reflection_points, 1,
        reflection_points ? v.reflection_proof_bytes() / reflection_points : 0, v.Rf.size());
    verification_ = {K, v.S.size(), v.Rf.size(), kVerifySamples, kVerifyAccuracy, v.sample_shadow_s, v.sample_reflection_s};
  }

  /// The report: the bandwidth limit (the best copy of all rounds: a shared machine's noise only adds time, to
  /// the copy as to the rows, so best against best), the rows finished against it, and the sections. Last: the
  /// rows and sections are moved into it.
  BenchReport report() {
    BenchReport r;
    r.threads = T_;
    r.n = n_;
    r.rounds = rounds_;
    r.exact_items = nx_;
    r.processor = processor_info();
    const double bandwidth = copy_.bytes() / best_of(copy_times_);
    r.memory_bandwidth_gbps = bandwidth / 1e9;
    for (double t : copy_times_) r.memory_bandwidth_gbps_runs.push_back(copy_.bytes() / t / 1e9);
    r.generation_s = generation_s_;
    r.pages = pages_;
    r.exact_arithmetic_items = std::min<Eigen::Index>(nx_, kCandidateItems);
    r.exact_arithmetic = std::move(candidates_);
    r.verification = verification_;
    finish_rows(rows_, bandwidth);
    r.rows = std::move(rows_);
    return r;
  }

 private:
  /// A line of progress, when the caller asked for them.
  void say(const std::string& s) const {
    if (opt_.progress) opt_.progress(s);
  }
  /// The progress line of each round of a phase.
  std::function<void(int)> progress(const std::string& what) const {
    return [this, what](int r) {
      say("bench: " + what + ", round " + std::to_string(r + 1) + "/" + std::to_string(rounds_));
    };
  }
  /// The copy that samples the bandwidth, timed.
  void timed_copy() {
    const auto t0 = Clock::now();
    copy_(T_);
    copy_times_.push_back(seconds_since(t0));
  }
  /// Items beyond the bit bound, counted over every round and both ops: per run, on the last two rows.
  void mark_beyond_bound(long beyond) {
    if (beyond > 0)
      for (int k : {2, 1}) rows_[rows_.size() - k].items_beyond_bit_bound = beyond / (2 * rounds_);
  }

  /// Each round: the copy, then for each kind its inputs (converted again, untimed) and the four double and
  /// interval direct rows, then the copy again; so that rows and bandwidth sample the same moments.
  void direct_rows(FloatBuffers& b) {
    std::vector<std::vector<double>> t(3 * 4);
    const std::vector<std::function<void()>> jobs{
        [&] { double_shadow_batch(b.A, b.L, Method::direct, b.P, b.pi, b.R, T_); },
        [&] { double_reflection_batch(b.A, b.L, Method::direct, b.M, b.B, T_); },
        [&] { interval_shadow_batch<false>(b.AI, b.LI, Method::direct, b.PI, b.piI, b.RI, T_); },
        [&] { interval_reflection_batch<false>(b.AI, b.LI, Method::direct, b.MI, b.BI, T_); }};
    for (int r = 0; r < rounds_; ++r) {
      say("bench: stream copy, double and interval direct rows of every kind of input, round " + std::to_string(r + 1) +
          "/" + std::to_string(rounds_));
      timed_copy();
      for (std::size_t k = 0; k < 3; ++k) {
        generation_s_ += b.fill(kKinds[k], n_, T_);
        for (std::size_t j = 0; j < 4; ++j) {
          const auto t0 = Clock::now();
          jobs[j]();
          t[4 * k + j].push_back(seconds_since(t0));
        }
      }
      timed_copy();
    }
    pages_ = bench_pages({&b.pages, &copy_.pages});
    for (std::size_t k = 0; k < 3; ++k) {
      rows_.push_back(batch_row(kKinds[k], "shadow", "double", "direct", t[4 * k], kShadowBytes, n_));
      rows_.push_back(batch_row(kKinds[k], "reflection", "double", "direct", t[4 * k + 1], kReflectionBytes, n_));
      rows_.push_back(batch_row(kKinds[k], "shadow", "interval", "direct", t[4 * k + 2], 2 * kShadowBytes, n_));
      rows_.push_back(batch_row(kKinds[k], "reflection", "interval", "direct", t[4 * k + 3], 2 * kReflectionBytes, n_));
    }
  }

  /// The paper route (one item at a time) against the direct one, on the same items, kind by kind.
  void paper_rows(FloatBuffers& b) {
    for (Kind kind : kKinds) {
      generation_s_ += b.fill(kind, n_, T_);
      const auto tp = interleaved_times(rounds_,
                                        {[&] { double_shadow_batch(b.A, b.L, Method::paper, b.P, b.pi, b.R, T_); },
                                         [&] { double_reflection_batch(b.A, b.L, Method::paper, b.M, b.B, T_); }},
                                        progress(std::string(kind_name(kind)) + ": double paper rows"));
      rows_.push_back(batch_row(kind, "shadow", "double", "paper", tp[0], kShadowBytes, n_));
      rows_.push_back(batch_row(kind, "reflection", "double", "paper", tp[1], kReflectionBytes, n_));
    }
  }

  /// The candidates for exact arithmetic on doubles (DigitPack<24>, WideInt<10>, CGAL::Mpzf, GMP rationals), on the same
  /// first items, one thread, all of them in every round (a shared machine: each round samples the same
  /// moments for all): the report's exact_arithmetic.
  void exact_candidates(WideExact& w) {
    const Eigen::Index m = std::min<Eigen::Index>(nx_, kCandidateItems);
    say("bench: exact arithmetic candidates on " + std::to_string(m) + " double-valued items");
    const auto mpzf = generic_inputs<CGAL::Mpzf>(w, m);
    const auto mpq = generic_inputs<Rational>(w, m);
    const long singly[2] = {w.singly[0].load(), w.singly[1].load()};
    std::vector<std::function<void()>> jobs{[&] { w.shadow(0, m); }, [&] { w.reflection(0, m); },
                                            [&] { w.shadow_wide(0, m); }, [&] { w.reflection_wide(0, m); }};
    for (auto& j : generic_jobs(mpzf, m)) jobs.push_back(j);
    for (auto& j : generic_jobs(mpq, m)) jobs.push_back(j);
    const auto tc = interleaved_times(rounds_, jobs, [](int) {});
    w.singly[0] = singly[0], w.singly[1] = singly[1];  // the rows' counts, not the candidates'
    const std::string digit_note = std::to_string(digit_blocks_lanes()) + " items at once in SIMD lanes (" +
                                   digit_blocks_kernel() +
                                   "), signed digits of radix 2^28 after aligning exponents (the exact rows' arithmetic)";
    const char* names[] = {"DigitPack<24>", "WideInt<10>", "CGAL::Mpzf", "GMP rationals"};
    const char* notes[] = {digit_note.c_str(), "640-bit integers in place after aligning exponents, one item at a time",
                           "mantissa and exponent per number, no gcd", "boost mpq_rational, a gcd per operation"};
    for (int c = 0; c < 4; ++c)
      candidates_.push_back({names[c], notes[c], 1e9 * best_of(tc[2 * c]) / static_cast<double>(m),
                             1e9 * best_of(tc[2 * c + 1]) / static_cast<double>(m)});
  }

  /// The four verification jobs, interleaved over the rounds: the filtered checks (ps and pr passes over the
  /// points) and the exact proofs (one pass), each on `T_` threads balanced by pairs.
  VerifyTimes timed_checks(const VerifyItems& v, int ps, int pr) {
    const auto& S = v.S;
    const auto& Rf = v.Rf;
    const std::vector<std::size_t> ws = v.shadow_weights(), wr = v.reflection_weights();
    std::vector<FilterCounts> cs(static_cast<std::size_t>(T_)), cr(cs), es(cs), er(cs);
    auto run_counted = [&](std::vector<FilterCounts>& out, const std::vector<std::size_t>& w, auto&& body) {
      std::fill(out.begin(), out.end(), FilterCounts{});
      weighted_threads(w, T_, [&](int t, std::size_t b, std::size_t e) { body(out[static_cast<std::size_t>(t)], b, e); });
    };
    VerifyTimes vt;
    vt.t = interleaved_times(
        rounds_,
        {[&] {
           run_counted(cs, ws, [&](FilterCounts& c, std::size_t b, std::size_t e) {
             for (int p = 0; p < ps; ++p)
               for (std::size_t i = b; i < e; ++i) {
                 c += check_quadric_filtered(S[i].pts, S[i].P);
                 c += check_plane_filtered(S[i].pts, S[i].pi);
                 c += check_quadric_filtered(S[i].pts, S[i].R);
                 c += check_quadric_filtered(S[i].gen, S[i].P);
                 c += check_quadric_filtered(S[i].plane, S[i].R);
               }
           });
         },
         [&] {
           run_counted(cr, wr, [&](FilterCounts& c, std::size_t b, std::size_t e) {
             for (int p = 0; p < pr; ++p)
               for (std::size_t i = b; i < e; ++i) c += check_quadric_filtered(Rf[i].pts, Rf[i].B);
           });
         },
         [&] {
           run_counted(es, ws, [&](FilterCounts& c, std::size_t b, std::size_t e) {
             for (std::size_t i = b; i < e; ++i) {
               c += S[i].pts.cleared.check_quadric(S[i].Pe);
               c += S[i].pts.cleared.check_plane(S[i].pie);
               c += S[i].pts.cleared.check_quadric(S[i].Re);
               c += S[i].gen.cleared.check_quadric(S[i].Pe);
               c += S[i].plane.cleared.check_quadric(S[i].Re);
             }
           });
         },
         [&] {
           run_counted(er, wr, [&](FilterCounts& c, std::size_t b, std::size_t e) {
             for (std::size_t i = b; i < e; ++i) c += Rf[i].pts.cleared.check_quadric(Rf[i].Be);
           });
         }},
        progress("verify-shadow, verify-reflection: filtered and exact point checks"));
    vt.counts[0] = total(cs), vt.counts[1] = total(cr), vt.counts[2] = total(es), vt.counts[3] = total(er);
    return vt;
  }

  const BenchOptions& opt_;
  const Eigen::Index n_;   ///< items of the double, interval, paper and small-rational exact rows
  const int T_;            ///< threads
  const int rounds_;
  const Eigen::Index nx_;  ///< items of the exact rows on double-valued and decimal-17 inputs
  StreamCopy copy_;        ///< as many bytes as the double shadow row moves
  std::vector<double> copy_times_;
  double generation_s_ = 0;  ///< converting the inputs, untimed by the rows
  std::vector<BenchRow> rows_;
  std::vector<ExactArithmeticCandidate> candidates_;
  BenchVerification verification_;
  BenchPages pages_;  ///< the pages the double and interval rows' buffers got
};

}  // namespace

BenchReport run_bench(const BenchOptions& opt) {
  BenchRun run(opt);
  run.float_rows();
  run.small_rational_exact_rows();
  for (Kind kind : {Kind::double_valued, Kind::decimal17}) run.wide_exact_rows(kind);
  run.verification_rows();
  return run.report();
}

}  // namespace qverify
