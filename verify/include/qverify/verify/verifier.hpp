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

#include <functional>

#include <qverify/verify/check.hpp>

namespace qverify {

/// Reads a `qverify-eval/1` document made by any program. Entries are JSON
/// numbers, "p/q" or decimal strings, or {"lo", "hi"} intervals (checked at
/// their midpoint). A number of a float, double or interval document (a decimal
/// string of a long-double, float128 or mpfr one, at the working precision of
/// its BITS) is the value of that format its text round-trips to, the value the
/// writer held; "p/q" strings and exact documents are read exactly. Malformed documents are
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
  /// Proof mode whatever the results' precision (verify --precision exact --candidate FILE): every
  /// residual must be exactly zero. Results of precision exact are always judged so.
  bool prove = false;
  /// Threads over the items (0: one per logical processor); the report does not depend on it.
  int threads = 0;
  /// Called after each item is checked with (items done, items in all), from
  /// one thread at a time (not necessarily the caller's).
  std::function<void(std::size_t, std::size_t)> progress = nullptr;
};

/// The verdict on one requested item (a shadow or a reflection of the scene).
struct VerifyCheck {
  std::string kind;       ///< "shadow" or "reflection"
  std::string quadric;    ///< the quadric's id
  std::string other;      ///< the light's id (shadow) or the mirror's (reflection)
  std::string exact_status;  ///< the status word of the exact inputs
  /// The check of the item's results; nullopt when the results are missing or unusable.
  std::optional<CheckReport> report;
  std::string missing;    ///< why there is no report ("missing", "non-finite entries ...")
  bool inaccurate = false;  ///< the results carried eval's flag `inaccurate`
  std::optional<Vec3<Rational>> origin;  ///< the results' frame (local coordinates x - origin)

  bool skipped() const { return report && report->skipped; }
  bool passed() const { return report && !report->skipped && report->passed; }
  /// "pass", "fail" or "skipped" (nothing to sample: neither pass nor fail).
  const char* status() const { return skipped() ? "skipped" : passed() ? "pass" : "fail"; }
};

/// What `verify` found: one check per requested item, in the scene's order
/// (shadows, then reflections), and the counts. report/verify_document.hpp
/// writes it as the `qverify-verify/1` document.
struct VerifyReport {
  Precision precision;  ///< of the results judged
  Method method = Method::direct;
  std::string source;   ///< "computed" or the candidate's file
  VerifyOptions options;
  std::vector<VerifyCheck> checks;
  int passed = 0, failed = 0, skipped = 0;
  std::vector<std::string> notes;  ///< the results' notes (e.g. from a candidate's reader)

  /// Were the results judged in proof mode (every residual exactly zero)?
  bool proof() const { return options.prove || precision.kind == Precision::Kind::exact; }
};

/// Checks every requested item's results on exact sample points against
/// references computed here from the exact scene (check_shadow_exact,
/// check_reflection_exact; check.hpp).
VerifyReport verify_results(const Scene& sc, const ResultSet& rs, const VerifyOptions& opt);

}  // namespace qverify
