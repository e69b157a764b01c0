#pragma once
/// \file candidate_section.hpp
/// The parts of the audit and stress documents that describe a candidate
/// (another implementation, verify/candidate_run.hpp): who it is, and the
/// reproducers written for its failures.

#include <qverify/verify/candidate_run.hpp>

#include <nlohmann/json.hpp>

namespace qverify {

/// The head of a report's "candidate" section: name, source, command,
/// timeout_seconds (null: none) and the accuracy target; each study appends
/// its rule and its counts.
nlohmann::ordered_json candidate_head_json(const Candidate& c, double accuracy);

/// A reproducer's entry: family, k, param, reason, and its files' paths
/// (returned: null when the candidate returned nothing).
nlohmann::ordered_json reproducer_json(const Reproducer& r);

}  // namespace qverify
