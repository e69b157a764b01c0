#pragma once
/// \file report.hpp
/// Self-contained HTML reports (no external resource: the SVG plots are inlined).

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace qverify {

/// report.html of `qverify audit` from its report.json document and the plot.
std::string audit_html(const nlohmann::ordered_json& doc, const std::string& svg);

/// report.html of `qverify stress` from its document and one SVG per family.
std::string stress_html(const nlohmann::ordered_json& doc, const std::vector<std::pair<std::string, std::string>>& svgs);

/// Shared page frame: head with inline CSS, a title, the body, a footer.
std::string html_page(const std::string& title, const std::string& body);

/// "1.23e-16" style, or "0" / "-" for zero and null.
std::string sci(const nlohmann::ordered_json& v);

}  // namespace qverify
