#pragma once
// Scenes from audits that more than one test file reads (eval's bounds and verify's verdicts), held
// once: exact rationals as the audits wrote them.

namespace qverify::test {

/// Audit 39a's items whose ball bounds were 10^3 to 10^7 times their error (verify failed them).
/// A two-sheet hyperboloid lit from its asymptotic cone (a parabola), moved by an exact rotation and
/// translation: h . x = 0 meets the parabola 2.4 object sizes from the ball's centre.
inline constexpr const char* kTwoSheetsMoved = R"({"format":"qverify-scene/1","name":"f1_h2_moved","quadrics":[{"id":"q","matrix":[
  ["-41629336/4941729","10143713/1520532","-23505832/4941729","1149649352251/652308228"],
  ["10143713/1520532","-2366863/467856","1238942/380133","-1721673156767/1404971568"],
  ["-23505832/4941729","1238942/380133","-10207696/4941729","128201308450/163077057"],
  ["1149649352251/652308228","-1721673156767/1404971568","128201308450/163077057","-179789802028486393/602732802672"]]}],
  "lights":[{"id":"p8","position":["117722/5187","2539/627","248815/741"]}],"mirrors":[]})";
/// A cone of eigenvalues -1, 1e-6, 1 under a sun along its flat direction nearly (L^T A L = 1e-6):
/// a line pair on which A's gradient is 0.58 |x - apex| and more, where A's floor over all of its
/// points is 1e-3 |x - apex| (the S-lemma's; 1e-6 from its least |eigenvalue|).
inline constexpr const char* kFlatConeSun = R"({"format":"qverify-scene/1","name":"CO_adv1 d6","quadrics":[{"id":"q","matrix":[
  ["-5249999/56250000","-21000001/22500000","17999993/56250000","-1532998733/675000000"],
  ["-21000001/22500000","1/9000000","-2999993/22500000","167998733/270000000"],
  ["17999993/56250000","-2999993/22500000","5250049/56250000","-369008869/675000000"],
  ["-1532998733/675000000","167998733/270000000","-369008869/675000000","24865605289/8100000000"]]}],
  "lights":[{"id":"d6","direction":["1/5","1","-7/5"]}],"mirrors":[]})";
/// A cone of eigenvalues -1/9, 1, 1e6 lit from 1.4 beside its apex: P is nearly a plane pair, curved
/// 1.7 up and 4e-7 down, and its value at the apex is negative.
inline constexpr const char* kNarrowCone = R"({"format":"qverify-scene/1","name":"CO_adv2 p3","quadrics":[{"id":"q","matrix":[
  ["5183999825/7569","791999848/2523","-864000256/2523","118295997515/15138"],
  ["791999848/2523","121000560/841","-131999588/841","9036499930/2523"],
  ["-864000256/2523","-131999588/841","144000207/841","-6572000595/1682"],
  ["118295997515/15138","9036499930/2523","-6572000595/1682","674862242650/7569"]]}],
  "lights":[{"id":"p3","position":["-18406251/1812500","-20124991/21750000","144499937/87000000"]}],"mirrors":[]})";
/// The flat cone's one-sheet hyperboloid (the same matrix, A's value at the centre -1) under a sun
/// along its asymptotic cone nearly (L^T A L = 1e-6): P is nearly the double plane (pi . x)^2, and
/// at its waist, 1000 from the centre, A's gradient on the terminator falls to 0.003, where P's
/// gradient direction curves against it (the first order's guard fails) while P curves 1.5e-12 up.
inline constexpr const char* kFlatHyperboloidSun = R"({"format":"qverify-scene/1","name":"H1_adv1 d7","quadrics":[{"id":"q","matrix":[
  ["-5249999/56250000","-21000001/22500000","17999993/56250000","-1532998733/675000000"],
  ["-21000001/22500000","1/9000000","-2999993/22500000","167998733/270000000"],
  ["17999993/56250000","-2999993/22500000","5250049/56250000","-369008869/675000000"],
  ["-1532998733/675000000","167998733/270000000","-369008869/675000000","16765605289/8100000000"]]}],
  "lights":[{"id":"d7","direction":["1/5","1","-7/5"]}],"mirrors":[]})";
/// A two-sheet hyperboloid (eigenvalues -0.049, -0.04, 0.11, its own size 3.8) lit from 4.2 of its
/// sizes below its centre: h meets the terminator 0.79 and 0.83 of the object's size (21) from the
/// centre, inside the sampled ball.
inline constexpr const char* kTwoSheetsLitBelow = R"({"format":"qverify-scene/1","name":"H2_0_matrix p8","quadrics":[{"id":"q","matrix":[
  ["-44131/1476225","46592/1476225","30862/1476225","-711616/4428675"],
  ["46592/1476225","85331/1476225","100366/1476225","612062/4428675"],
  ["30862/1476225","100366/1476225","-9124/1476225","3232/4428675"],
  ["-711616/4428675","612062/4428675","3232/4428675","-25687201/13286025"]]}],
  "lights":[{"id":"p8","position":["-6","1","-103/6"]}],"mirrors":[]})";

}  // namespace qverify::test
