#pragma once
/// \file eval_document.hpp
/// An EvalReport written out: the `qverify-eval/1` document
/// (docs/json-documents.md) and the text `qverify eval` prints. The one place
/// where an evaluation becomes JSON or text; the numbers' encoding is shared
/// with the verify and audit documents.

#include <qverify/eval/eval_report.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace qverify {

/// A number as JSON: a number, a string (decimal or rational text), {"lo", "hi"}, or null.
nlohmann::ordered_json number_json(const Number& x);
/// A finite double as a JSON number, anything else as null.
nlohmann::ordered_json number_or_null(double v);
/// A matrix as rows of numbers; a column vector (a plane) as one flat array.
nlohmann::ordered_json matrix_json(const NumberMatrix& m);
/// An origin (exact doubles) as three JSON numbers.
nlohmann::ordered_json origin_json(const std::array<double, 3>& o);
nlohmann::ordered_json origin_json(const Vec3<Rational>& o);
/// The `skipped` list: every pair that was not requested, with the reason.
nlohmann::ordered_json skipped_json(const std::vector<SkippedPair>& pairs);

/// The `qverify-eval/1` document.
nlohmann::ordered_json eval_json(const EvalReport& report);
/// The text of `qverify eval` (without --json).
std::string eval_text(const EvalReport& report);

}  // namespace qverify
