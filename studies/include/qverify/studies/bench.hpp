#pragma once
/// \file bench.hpp
/// `qverify bench`: the batch API (core/batch.hpp) at scale: items per second
/// per op, precision, method and kind of inputs (small rationals, doubles with
/// full mantissas and spread exponents, 17-digit decimal text), bytes moved per
/// item, the memory bandwidth measured in the same run and the fraction of the
/// bandwidth limit reached; exact arithmetic for each kind of input; the
/// filtered verifier's point checks per second (verify-shadow,
/// verify-reflection); the processor it ran on.

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <thread>

namespace qverify {

struct BenchOptions {
  long n = 10000000;
  int threads = static_cast<int>(std::thread::hardware_concurrency());
  int repeats = 5;  ///< rounds: each row is timed once per round, best of
  std::function<void(const std::string&)> progress;
};

/// Memory a run of `qverify bench` takes per item (the buffers of its largest phase).
std::size_t bench_bytes_per_item();

/// Items of the exact rows on double-valued and decimal-17 inputs, and items
/// sampled for the verification rows, for a run of n items.
long bench_exact_items(long n);
int bench_verify_items(long n);

/// The processor this runs on (/proc/cpuinfo: vendor, model name, family,
/// model) and the instruction set this build was compiled for.
nlohmann::ordered_json processor_info();

/// The `qverify-bench/1` document.
nlohmann::ordered_json run_bench(const BenchOptions& opt);

}  // namespace qverify
