#pragma once
/// \file bench.hpp
/// `qverify bench`: the batch API (core/batch.hpp) at scale: items per second
/// per op, precision and method, bytes moved per item, the memory bandwidth
/// measured in the same run, and the fraction of the bandwidth limit reached.

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

/// The `qverify-bench/1` document.
nlohmann::ordered_json run_bench(const BenchOptions& opt);

}  // namespace qverify
