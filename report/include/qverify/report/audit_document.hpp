#pragma once
/// \file audit_document.hpp
/// An AuditReport written out: the `qverify-audit/1` document
/// (docs/json-documents.md) and the text `qverify audit` prints.

#include <qverify/studies/audit.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace qverify {

/// The `qverify-audit/1` document.
nlohmann::ordered_json audit_json(const AuditReport& report);
/// The text of `qverify audit` (without --json); `dir` is where the files were written.
std::string audit_text(const AuditReport& report, const std::string& dir);

}  // namespace qverify
