// libFuzzer target: the reader of candidate documents (qverify-eval/1 from any
// program) against a fixed scene. A rejected document must be an InputError.
#include <qverify/verify/verifier.hpp>

#include <cstdint>
#include <string>

namespace {
const char* kScene = R"({"format": "qverify-scene/1", "name": "fuzz",
  "quadrics": [{"id": "ball", "sphere": {"center": [0, 0, 2], "radius": 1}},
               {"id": "pipe", "cylinder": {"point": [0, 0, 0], "axis": [0, 1, 1], "radius": 0.5}}],
  "lights": [{"id": "lamp", "position": [3, 4, 8]}, {"id": "sun", "direction": [0, 0, -1]}],
  "mirrors": [{"id": "floor", "plane": [0, 0, 1, 0]}]})";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const qverify::Scene scene = qverify::parse_scene(kScene, "scene.json");
  static const qverify::Precision dbl = *qverify::parse_precision("double");
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)qverify::candidate_results_text(scene, text, "fuzz.json", dbl);
  } catch (const qverify::InputError&) {
  }
  return 0;
}
