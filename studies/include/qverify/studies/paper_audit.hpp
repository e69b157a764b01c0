#pragma once
/// \file paper_audit.hpp
/// `qverify paper`: every printed formula of the paper, (1) to (11), taken as
/// printed in the transcription and checked against its own definition, in
/// exact arithmetic (report/paper_document.hpp writes it as a document and as text). Evidence is symbolic wherever possible: the formula is run
/// through the generic core with the symbolic scalar `Poly` and the claim is
/// decided as a polynomial identity. A failing formula gets an exact
/// counterexample and a corrected form, itself proved symbolically.

#include <string>
#include <vector>

namespace qverify {

struct AuditEntry {
  std::string id;        ///< "(4)"
  std::string claim;     ///< what the paper says the formula is
  std::string reading;   ///< how ambiguous symbols were read
  std::string verdict;   ///< holds | holds-up-to-factor | fails | definition
  std::string evidence;  ///< symbolic identity, counterexample
  std::string corrected; ///< corrected formula (when it fails)
  std::string factor;    ///< the factor (holds-up-to-factor)
};

/// Runs the whole audit (a fraction of a second).
std::vector<AuditEntry> audit_paper();

}  // namespace qverify
