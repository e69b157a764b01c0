#pragma once
/// \file stress.hpp
/// A StressReport written out: the `qverify-stress/1` document
/// (docs/json-documents.md) and the text `qverify stress` prints; and the
/// list of families of `qverify stress --list`.

#include <qverify/studies/stress.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace qverify {

/// The `qverify-stress/1` document.
nlohmann::ordered_json stress_json(const StressReport& report);
/// The text of `qverify stress` (without --json); `dir` is where the files were written.
std::string stress_text(const StressReport& report, const std::string& dir);

/// `qverify stress --list --json`: {"families": [{name, parameter, description}, ...]}.
nlohmann::ordered_json stress_families_json(const std::vector<StressFamily>& families);
/// `qverify stress --list`: one line per family, its name and description.
std::string stress_families_text(const std::vector<StressFamily>& families);

}  // namespace qverify
