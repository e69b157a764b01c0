#pragma once
/// \file verify_document.hpp
/// The `qverify-verify/1` document (docs/json-documents.md) of a VerifyReport,
/// and its text: written here only.

#include <qverify/verify/verifier.hpp>

#include <nlohmann/json.hpp>

namespace qverify {

/// The document of `report`, the verdicts on `sc`'s requested items.
nlohmann::ordered_json verify_document(const Scene& sc, const VerifyReport& report);

/// The text of `qverify verify` (without --json).
std::string verify_text(const Scene& sc, const VerifyReport& report);

}  // namespace qverify
