#pragma once
/// \file items.hpp
/// Threads over independent items of uneven cost (exact checks, accuracy
/// measures): each thread takes the next item index from a shared counter,
/// so one slow item does not hold a whole chunk back. (parallel_for in
/// batch.hpp is for many cheap items of equal cost: contiguous chunks.)

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace qverify {

/// progress(done, total) after each finished item: the calls are serialised and
/// `done` counts 1, 2, ..., total in the order the items finish.
using ItemProgress = std::function<void(std::size_t done, std::size_t total)>;

/// The number of threads to use for `threads` (0: one per logical processor).
inline int item_threads(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// Runs f(k) for every k in [0, n) on item_threads(threads) threads, and
/// `progress` (when set) after each. f must write only to item k's own
/// results. The first exception thrown by f is rethrown here once every thread
/// has stopped (the items not yet started are left undone).
template <class F> void for_each_item(std::size_t n, int threads, const ItemProgress& progress, F&& f) {
  const int T = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(item_threads(threads)), n));
  std::size_t done = 0;
  std::mutex progress_mutex;
  auto run = [&](std::size_t k) {
    f(k);
    if (!progress) return;
    const std::lock_guard<std::mutex> lock(progress_mutex);
    progress(++done, n);
  };
  if (T <= 1) {
    for (std::size_t k = 0; k < n; ++k) run(k);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    for (std::size_t k; !stop && (k = next++) < n;) {
      try {
        run(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        stop = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < T; ++t) pool.emplace_back(work);
  work();
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

/// for_each_item without progress.
template <class F> void for_each_item(std::size_t n, int threads, F&& f) {
  for_each_item(n, threads, ItemProgress(), std::forward<F>(f));
}

}  // namespace qverify
