#pragma once
/// \file report.hpp
/// The studies' reports as files: report.json, self-contained HTML (no
/// external resource: the SVG plots are inlined) and one SVG per figure. The
/// one place where the audit and stress reports become files.

#include <qverify/studies/audit.hpp>
#include <qverify/studies/stress.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>

#include <string>
#include <vector>

namespace qverify {

/// Writes DIR/report.json, DIR/report.html and DIR/error-vs-time.svg (checked
/// writes, scene/files.hpp: throws FileWriteError naming the path).
void write_audit_report(const std::filesystem::path& dir, const AuditReport& report);
/// Writes DIR/report.json, DIR/report.html and DIR/FAMILY.svg per family.
void write_stress_report(const std::filesystem::path& dir, const StressReport& report);

/// The files write_audit_report writes into DIR, to be checked before the
/// audit runs (check_writable, scene/files.hpp): an unwritable report fails
/// before minutes of measuring, not after.
std::vector<std::filesystem::path> audit_report_files(const std::filesystem::path& dir);
/// The files write_stress_report writes into DIR for these families, likewise.
std::vector<std::filesystem::path> stress_report_files(const std::filesystem::path& dir,
                                                       const std::vector<std::string>& families);
/// Before any work of audit or stress (the CLI and Python alike): makes DIR, checks that these report
/// files can be written there and, with `reproducers` (a candidate runs), that DIR/failures/ can hold
/// the reproducers written during the run. Throws FileWriteError naming the path.
void check_report_outputs(const std::filesystem::path& dir, const std::vector<std::filesystem::path>& files,
                          bool reproducers);

/// report.html of `qverify audit` from its report.json document and the plot.
std::string audit_html(const nlohmann::ordered_json& doc, const std::string& svg);

/// report.html of `qverify stress` from its document and one SVG per family.
std::string stress_html(const nlohmann::ordered_json& doc, const std::vector<std::pair<std::string, std::string>>& svgs);

/// Shared page frame: head with inline CSS, a title, the body, a footer.
std::string html_page(const std::string& title, const std::string& body);

/// "1.23e-16" style, or "0" / "-" for zero and null.
std::string sci(const nlohmann::ordered_json& v);

}  // namespace qverify
