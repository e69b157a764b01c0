// libFuzzer target: the scene parser and loader, then evaluation in double and
// (for small inputs) exact arithmetic, written as the eval document. A rejected
// scene must be an InputError; any other exception, crash, leak or sanitizer
// report is a finding.
#include <qverify/report/eval_document.hpp>

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  qverify::Scene sc;
  try {
    sc = qverify::parse_scene(text, "fuzz.json");
  } catch (const qverify::InputError&) {
    return 0;
  }
  if (sc.shadows.size() + sc.reflections.size() > 16) return 0;
  const qverify::AccuracyOptions few{qverify::kDefaultAccuracy, 4, 1};  // error bounds on 4 points: fuzzing wants speed
  for (const char* p : {"double", "float"}) {  // (a legal scene is computed in every precision: no InputError here)
    (void)qverify::eval_json(qverify::eval_report(sc, *qverify::parse_precision(p), qverify::Method::direct, std::nullopt, few)).dump();
    (void)qverify::eval_json(qverify::eval_report(sc, *qverify::parse_precision(p), qverify::Method::paper, std::nullopt, few)).dump();
  }
  if (size < 1024)
    (void)qverify::eval_json(qverify::eval_report(sc, *qverify::parse_precision("exact"), qverify::Method::paper, std::nullopt, few)).dump();
  return 0;
}
