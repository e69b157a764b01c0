#pragma once
/// \file timed.hpp
/// Timed evaluation of a scene in one precision: the measurement behind the
/// precision audit's time axis (studies/audit.hpp).

#include <qverify/eval/results.hpp>

#include <algorithm>
#include <chrono>
#include <vector>

namespace qverify {

/// Results of one (precision, method) with the time per item.
struct TimedResult {
  ResultSet results;
  double ns_per_item = 0;  ///< median over batches
  long reps_per_batch = 0;
  int batches = 0;
  std::size_t inputs_rounded = 0;
};

/// Keeps `p`'s pointee alive as far as the optimiser can tell.
inline void clobber(const void* p) { asm volatile("" : : "r"(p) : "memory"); }

/// Times evaluate_items (inputs already rounded into S) in batches of at least
/// `batch_seconds`, median of `batches`, and returns the results converted
/// exactly.
template <class S>
TimedResult timed_results(const Scene& sc, const Precision& prec, Method method, double batch_seconds, int batches) {
  using clock = std::chrono::steady_clock;
  TimedResult tr;
  Evaluation<S> ev;
  ev.scene = typed_scene<S>(sc);
  prepare<S>(sc, Frame::world, ev);  // the ladder compares precisions in the world frame
  tr.inputs_rounded = ev.scene.rounded_inputs.size();
  const std::size_t items = sc.shadows.size() + sc.reflections.size();
  auto batch = [&](long reps) {
    const auto t0 = clock::now();
    for (long r = 0; r < reps; ++r) {
      evaluate_items<S>(sc, method, ev);
      clobber(ev.shadows.data());
      clobber(ev.reflections.data());
    }
    return std::chrono::duration<double>(clock::now() - t0).count();
  };
  long reps = 1;
  while (items > 0 && batch(reps) < batch_seconds && reps < (1L << 24)) reps *= 2;
  std::vector<double> ns;
  for (int b = 0; items > 0 && b < batches; ++b) ns.push_back(batch(reps) * 1e9 / static_cast<double>(reps * items));
  std::sort(ns.begin(), ns.end());
  tr.ns_per_item = ns.empty() ? 0 : ns[ns.size() / 2];
  tr.reps_per_batch = reps;
  tr.batches = static_cast<int>(ns.size());
  evaluate_items<S>(sc, method, ev);
  check_items<S>(sc, method, ev, AccuracyOptions{});  // error bounds, flags and exact statuses, not timed
  tr.results = result_set<S>(sc, ev, prec, method);
  return tr;
}

TimedResult timed_results(const Scene& sc, const Precision& prec, Method method, double batch_seconds, int batches);

}  // namespace qverify
