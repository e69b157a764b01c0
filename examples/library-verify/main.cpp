// library_verify SCENE: loads a qverify-scene/1 file, computes every requested shadow and
// reflection in double (the default robust path, method direct) and checks the results on
// exact sample points, all through the library. Prints one line per check and a summary;
// exit 0 when every check passes, 1 when one fails, 2 on a bad scene.
#include <qverify/scene/scene.hpp>
#include <qverify/verify/verifier.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: library_verify SCENE.json\n";
    return 2;
  }
  try {
    const qverify::Scene scene = qverify::load_scene(argv[1]);
    const qverify::ResultSet results =
        qverify::computed_results(scene, *qverify::parse_precision("double"), qverify::Method::direct);
    qverify::VerifyOptions options;  // 64 exact points per item, seed 1, accuracy target 1e-9
    const qverify::VerifyReport report = qverify::verify_results(scene, results, options);

    for (const qverify::VerifyCheck& check : report.checks) {
      std::cout << check.kind << " " << check.quadric << " / " << check.other << ": " << check.status();
      if (!check.report) std::cout << " (" << check.missing << ")";
      else if (!check.passed()) std::cout << "\n" << check.report->summary();  // which point, how far, relative to what
      std::cout << "\n";
    }
    std::cout << scene.name << ": " << report.passed << " passed, " << report.failed << " failed, " << report.skipped
              << " skipped\n";
    return report.failed > 0 ? 1 : 0;
  } catch (const qverify::InputError& e) {  // the message names the file, the JSON path and the problem
    std::cerr << "library_verify: " << e.what() << "\n";
    return 2;
  }
}
