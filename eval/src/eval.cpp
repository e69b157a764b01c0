#include <qverify/eval/instantiate.hpp>

QVERIFY_FOR_EACH_SCALAR(QVERIFY_EXTERN)

namespace qverify {

nlohmann::ordered_json skipped_json(const Scene& sc) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const Pair& p : sc.skipped_shadows())
    out.push_back({{"quadric", sc.quadrics[p.quadric].id},
                   {"light", sc.lights[p.other].id},
                   {"reason", "not requested (requests.shadows)"}});
  for (const Pair& p : sc.skipped_reflections())
    out.push_back({{"quadric", sc.quadrics[p.quadric].id},
                   {"mirror", sc.mirrors[p.other].id},
                   {"reason", "not requested (requests.reflections)"}});
  return out;
}

nlohmann::ordered_json eval_document(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame,
                                     const AccuracyOptions& accuracy) {
  return with_scalar(prec, [&](auto tag) { return eval_document<decltype(tag)>(sc, prec, method, frame, accuracy); });
}

ResultSet computed_results(const Scene& sc, const Precision& prec, Method method, std::optional<Frame> frame,
                           const std::optional<AccuracyOptions>& accuracy) {
  return with_scalar(prec, [&](auto tag) { return computed_results<decltype(tag)>(sc, prec, method, frame, accuracy); });
}

TimedResult timed_results(const Scene& sc, const Precision& prec, Method method, double batch_seconds, int batches) {
  return with_scalar(prec, [&](auto tag) { return timed_results<decltype(tag)>(sc, prec, method, batch_seconds, batches); });
}

}  // namespace qverify
