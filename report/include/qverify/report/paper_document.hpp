#pragma once
/// \file paper_document.hpp
/// The audit of the paper's formulas written out: the `qverify-paper/1`
/// document (docs/json-documents.md) and the text `qverify paper` prints.

#include <qverify/studies/paper_audit.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace qverify {

nlohmann::ordered_json paper_json(const std::vector<AuditEntry>& entries);
std::string paper_text(const std::vector<AuditEntry>& entries);

}  // namespace qverify
