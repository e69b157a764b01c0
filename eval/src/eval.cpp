#include <qverify/eval/instantiate.hpp>

QVERIFY_FOR_EACH_SCALAR(QVERIFY_EXTERN)

namespace qverify {

std::vector<SkippedPair> skipped_pairs(const Scene& sc) {
  std::vector<SkippedPair> out;
  for (const Pair& p : sc.skipped_shadows()) out.push_back({true, sc.quadrics[p.quadric].id, sc.lights[p.other].id});
  for (const Pair& p : sc.skipped_reflections())
    out.push_back({false, sc.quadrics[p.quadric].id, sc.mirrors[p.other].id});
  return out;
}

EvalReport eval_report(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame,
                       const AccuracyOptions& accuracy) {
  return with_scalar(prec, [&](auto tag) { return eval_report<decltype(tag)>(sc, prec, method, frame, accuracy); });
}

ResultSet computed_results(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame,
                           const std::optional<AccuracyOptions>& accuracy) {
  return with_scalar(prec, [&](auto tag) { return computed_results<decltype(tag)>(sc, prec, method, frame, accuracy); });
}

TimedResult timed_results(const Scene& sc, const Precision& prec, Method method, double batch_seconds, int batches) {
  return with_scalar(prec, [&](auto tag) { return timed_results<decltype(tag)>(sc, prec, method, batch_seconds, batches); });
}

}  // namespace qverify
