#pragma once
/// \file method.hpp
/// Which route a result takes: the direct projective formulas, or the paper's
/// own (the frame of eqs. (3)-(5) for a shadow, M^-1 of eq. (9) for a mirror).

namespace qverify {

/// How a result was computed.
enum class Method { direct, paper };

}  // namespace qverify
