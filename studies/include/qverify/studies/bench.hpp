#pragma once
/// \file bench.hpp
/// `qverify bench`: the batch API (batch/batch.hpp) at scale: items per second
/// per op, precision, method and kind of inputs (small rationals, doubles with
/// full mantissas and spread exponents, 17-digit decimal text), bytes moved per
/// item, the memory bandwidth measured in the same run and the fraction of the
/// bandwidth limit reached; exact arithmetic for each kind of input; the
/// filtered verifier's point checks per second (verify-shadow,
/// verify-reflection); the processor it ran on.
///
/// The result is typed (BenchReport); report/bench.hpp writes it as the
/// `qverify-bench/1` document and as the text `qverify bench` prints.

#include <qverify/verify/point_filter.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace qverify {

struct BenchOptions {
  long n = 10000000;
  int threads = static_cast<int>(std::thread::hardware_concurrency());
  int repeats = 5;  ///< rounds: each row is timed once per round, best of
  /// Advise huge pages for the buffers of the double and interval rows and of the bandwidth copy alike
  /// (batch/pages.hpp); false: the pages malloc gives (4 KiB on most systems), for comparison.
  bool huge_pages = true;
  std::function<void(const std::string&)> progress;
};

/// Memory a run of `qverify bench` takes per item (the buffers of its largest phase).
std::size_t bench_bytes_per_item();

/// Items of the exact rows on double-valued and decimal-17 inputs, and items
/// sampled for the verification rows, for a run of n items.
long bench_exact_items(long n);
int bench_verify_items(long n);

/// The processor a benchmark ran on, and the build's vector instructions.
struct ProcessorInfo {
  std::optional<std::string> vendor, model_name;  ///< /proc/cpuinfo's vendor_id and model name (first processor)
  std::optional<int> family, model;               ///< its cpu family and model
  std::string instruction_set;                    ///< the widest x86 vector extension this build was compiled for
  /// What the double batches run (exact/double_batch.hpp): the build's instruction set, or a
  /// second kernel's, e.g. "AVX-512 (run-time dispatch)" or "AVX2, clang 14.0.6 (run-time
  /// dispatch)"; and its doubles per instruction (batch/pack.hpp)
  std::string double_kernel;
  int lanes = 1;
  /// What the interval batches run (exact/interval_batch.hpp): the build's instruction set, or
  /// a second kernel's, e.g. "AVX-512 (run-time dispatch)"
  std::string interval_kernel;
  /// What the exact rows on doubles and decimals run (exact/digit_batch.hpp): the same choice for
  /// the digit blocks, and their lanes (items per block)
  std::string exact_kernel;
  int exact_lanes = 1;
  std::vector<std::string> supports;  ///< of SSE2, AVX2, AVX-512 and AVX-512 IFMA, those the processor has
  unsigned logical_cpus = 0;
};

/// The processor this runs on (/proc/cpuinfo: vendor, model name, family,
/// model) and the instruction set this build was compiled for.
ProcessorInfo processor_info();

/// What a verification row counted beside its times: the (point, result) pairs checked and how they were decided.
struct VerifyRowFacts {
  FilterCounts counts;  ///< over all threads, in one run
  int threads = 0;
  std::size_t distinct_points = 0;
  int passes = 0;  ///< checks of every pair per run
};

/// One row: an op (shadow, reflection, verify-shadow, verify-reflection), precision, method and kind of inputs
/// (small-rational, double-valued, decimal-17), its times and the bytes it moves per item. A verification
/// row counts a point check as an item.
struct BenchRow {
  std::string op, precision, method, inputs;
  long n = 0;  ///< items per run (verification rows: items with points)
  double items_per_s = 0;         ///< best of the runs
  double ns_per_item = 0;         ///< best of the runs
  double ns_per_item_median = 0;
  std::vector<double> ns_per_item_runs;
  std::size_t bytes_per_item = 0;
  std::string arithmetic, results;             ///< exact rows: how they compute, where the results go
  std::optional<long> items_beyond_bit_bound;  ///< exact rows: items that needed GMP rationals, when any
  std::optional<long> items_singly;            ///< exact rows on doubles and decimals: items not in a SIMD block
  std::optional<VerifyRowFacts> verify;        ///< set for a verification row
  double roofline_fraction = 0;                ///< items/s x bytes/item against the memory bandwidth
  /// Time against double/direct of the same op and inputs (verification rows: against their double, filtered row).
  std::optional<double> cost_vs_double_direct;
};

/// An arithmetic for exact results from doubles, timed on the same items by the same generic formulas.
struct ExactArithmeticCandidate {
  std::string arithmetic, note;
  double shadow_ns_per_item = 0, reflection_ns_per_item = 0;
};

/// The verification rows' items: double-valued items with exact sample points (items without a real point
/// are left out), and the wall time of sampling them (not part of the rows).
struct BenchVerification {
  int items_drawn = 0;
  std::size_t shadow_items = 0, reflection_items = 0;
  int samples_per_item = 0;  ///< exact points per item, as `verify`
  double accuracy = 0;       ///< the target the points are checked against, as `verify`
  double sampling_shadow_s = 0, sampling_reflection_s = 0;
};

/// The pages the buffers of the double and interval rows and of the bandwidth copy got.
struct BenchPages {
  /// BenchOptions::huge_pages, and the system took the advice (advised_bytes > 0)
  bool huge_pages_advised = false;
  std::size_t advised_bytes = 0;       ///< the bytes advised (whole huge pages inside the buffers)
  std::string transparent_huge_pages;  ///< the system's mode: always, madvise or never ("" where unknown)
  std::size_t buffer_bytes = 0;        ///< those buffers' bytes
  /// The huge pages of the mappings that hold those buffers once they were written (/proc/self/smaps);
  /// 0 where none or unknown
  std::size_t buffer_huge_page_bytes = 0;
};

/// What a benchmark run measured.
struct BenchReport {
  int threads = 0;
  long n = 0;       ///< items of the double, interval, paper and small-rational exact rows
  int rounds = 0;   ///< each row timed once per round, best of
  long exact_items = 0;  ///< items of the exact rows on double-valued and decimal-17 inputs
  ProcessorInfo processor;
  double memory_bandwidth_gbps = 0;               ///< the best stream copy of the run
  std::vector<double> memory_bandwidth_gbps_runs;  ///< every copy, in order (two per round)
  double generation_s = 0;                        ///< converting the inputs, untimed by the rows
  BenchPages pages;
  long exact_arithmetic_items = 0;                ///< items of the exact arithmetic candidates (one thread)
  std::vector<ExactArithmeticCandidate> exact_arithmetic;
  BenchVerification verification;
  std::vector<BenchRow> rows;  ///< op group (batch, then verification), inputs, precision, method, op
};

/// Runs the benchmark.
BenchReport run_bench(const BenchOptions& opt);

}  // namespace qverify
