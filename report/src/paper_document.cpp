#include <qverify/report/paper_document.hpp>

#include <fmt/format.h>

#include <sstream>

namespace qverify {
namespace {

/// Wraps text at `width` columns with an indent.
std::string wrap_text(const std::string& text, std::size_t width, const std::string& indent) {
  std::string out, line;
  std::istringstream words(text);
  std::string w;
  while (words >> w) {
    if (!line.empty() && line.size() + 1 + w.size() > width) {
      out += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) out += indent + line + "\n";
  return out;
}

}  // namespace

nlohmann::ordered_json paper_json(const std::vector<AuditEntry>& entries) {
  nlohmann::ordered_json doc;
  doc["format"] = "qverify-paper/1";
  doc["paper"] = "Hashimoto & Suenaga, A study on the transformation of quadric surfaces (NTT, 2T-7)";
  doc["equations"] = nlohmann::ordered_json::array();
  for (const AuditEntry& e : entries) {
    nlohmann::ordered_json j;
    j["id"] = e.id;
    j["claim"] = e.claim;
    j["reading"] = e.reading;
    j["verdict"] = e.verdict;
    if (!e.factor.empty()) j["factor"] = e.factor;
    j["evidence"] = e.evidence;
    if (!e.corrected.empty()) j["corrected"] = e.corrected;
    doc["equations"].push_back(j);
  }
  return doc;
}

std::string paper_text(const std::vector<AuditEntry>& entries) {
  std::string out = fmt::format("Audit of Hashimoto & Suenaga, 'A study on the transformation of quadric surfaces' (exact arithmetic)\n\n");
  out += fmt::format("{:<6} {:<20} {}\n", "eq.", "verdict", "claim");
  out += fmt::format("{:-<6} {:-<20} {:-<70}\n", "", "", "");
  for (const auto& e : entries)
    out += fmt::format("{:<6} {:<20} {}\n", e.id, e.verdict + (e.factor.empty() ? "" : " (" + e.factor.substr(0, e.factor.find(' ')) + ")"),
                       e.claim.substr(0, 70) + (e.claim.size() > 70 ? "..." : ""));
  for (const auto& e : entries) {
    out += fmt::format("\n{} {}\n", e.id, e.verdict);
    out += fmt::format("  claim:\n{}", wrap_text(e.claim, 96, "    "));
    if (!e.reading.empty()) out += fmt::format("  reading:\n{}", wrap_text(e.reading, 96, "    "));
    if (!e.factor.empty()) out += fmt::format("  factor:   {}\n", e.factor);
    out += fmt::format("  evidence:\n{}", wrap_text(e.evidence, 96, "    "));
    if (!e.corrected.empty()) out += fmt::format("  corrected:\n{}", wrap_text(e.corrected, 96, "    "));
  }
  return out;
}

}  // namespace qverify
