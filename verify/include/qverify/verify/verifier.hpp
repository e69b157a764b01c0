#pragma once
/// \file verifier.hpp
/// `qverify verify`: exact sample points on every requested terminator
/// (A ∩ polar plane) and on every requested quadric, checked against results
/// computed in any precision, or read from another program's eval document
/// (`--candidate`).
///
/// The sample points are exact (Q(sqrt delta), from the exact scene). The
/// results are converted *exactly* to rationals (a binary float is a dyadic
/// rational), so x^T Q x is evaluated without any rounding; only its size is
/// then measured, to 80 digits. In exact arithmetic a zero is a proof.

#include <qverify/eval/results.hpp>

#include <nlohmann/json.hpp>

namespace qverify {

/// Reads a `qverify-eval/1` document made by any program. Numbers are read
/// exactly from their text (JSON numbers, "p/q" or decimal strings, and
/// {"lo", "hi"} intervals, checked at their midpoint). Malformed documents are
/// InputErrors (file, JSON path); requested items it lacks are reported by the
/// verifier as failures.
ResultSet candidate_results(const Scene& sc, const std::string& file, const Precision& fallback);
/// The same from text (`file` names it in messages).
ResultSet candidate_results_text(const Scene& sc, const std::string& text, const std::string& file,
                                 const Precision& fallback);

struct VerifyOptions {
  int samples = kDefaultSamples;
  std::uint64_t seed = 1;
  double accuracy = kDefaultAccuracy;  ///< the accuracy target T (relative to the object size)
};

/// The `qverify-verify/1` document and how many checks failed.
struct VerifyOutcome {
  nlohmann::ordered_json document;
  int passed = 0, failed = 0, skipped = 0;
};
VerifyOutcome verify_results(const Scene& sc, const ResultSet& rs, const VerifyOptions& opt);

}  // namespace qverify
