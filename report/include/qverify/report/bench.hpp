#pragma once
/// \file bench.hpp
/// A BenchReport written out: the `qverify-bench/1` document
/// (docs/json-documents.md) and the text `qverify bench` prints.

#include <qverify/studies/bench.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace qverify {

/// The `qverify-bench/1` document.
nlohmann::ordered_json bench_json(const BenchReport& report);
/// The text of `qverify bench` (without --json): the run, the processor, one line per row.
std::string bench_text(const BenchReport& report);

}  // namespace qverify
