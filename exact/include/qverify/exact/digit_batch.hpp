#pragma once
/// \file digit_batch.hpp
/// Exact results of many items given as doubles or decimal text, W items at a time on DigitPack
/// (digit_pack.hpp), in the instruction set the configure measured fastest for it: the build's
/// own, or a second kernel compiled for the other x86-64 level and run where the processor has it
/// (cmake/ChooseArch.cmake; the interval batches do the same, interval_batch.hpp). On this
/// project's AMD Zen 5 machine the AVX-512 kernel (8 lanes) takes about 2/3 of the AVX2 one's time
/// per item while the build itself is AVX2 (README, "bench").
///
/// Inputs: per item A's upper triangle in the order of kSymRow/kSymCol (batch/rows.hpp: (0,0),
/// (0,1), (0,2), (0,3), (1,1), ...), ten numbers, and a light or mirror plane, four. Each matrix is
/// shifted to the smallest exponent of its entries (binary for doubles, decimal for m 10^e): the
/// direct division-free formulas (polar plane, cone, R; the scaled mirror matrix and the image of
/// core/mirror_division_free.hpp) run on the integers, and every result is the exact one times a
/// known power of the base (a positive factor: the results are projective).
///
/// Output: DigitBlocks, lane-major as the packs hold them: the normalized digits (radix 2^28, the
/// lower ones in [0, 2^28), the top one signed) of every result entry of every block, read back
/// exactly by value(). Only whole blocks are computed; a block that does not fit (an entry beyond
/// 126 bits, a result beyond the digits, lanes that disagree on a decision such as L_w = 0) is left
/// to the caller (`done` 0), as are the last n mod W items.

#include <qverify/exact/scalars.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace qverify {

/// n items as doubles: a[10 i + k] and l[4 i + k].
struct DoubleItems {
  const double* a = nullptr;
  const double* l = nullptr;
  Eigen::Index n = 0;
};

/// n items as decimal text m 10^e: A's entry k of item i is am[10 i + k] 10^ae[10 i + k], the
/// light's lm[4 i + k] 10^le[4 i + k].
struct DecimalItems {
  const std::int64_t* am = nullptr;
  const int* ae = nullptr;
  const std::int64_t* lm = nullptr;
  const int* le = nullptr;
  Eigen::Index n = 0;
};

/// What to compute: the shadow (entries P (ten, kSymRow order), pi (four), R (ten)) or the
/// reflection in the plane l (entries (n.n) M (rows 0 to 2, twelve), (n.n)^2 B (ten)).
enum class DigitOp { shadow, reflection };

/// The exact integer results of whole blocks of W items, lane-major.
struct DigitBlocks {
  static constexpr int max_digits = 24;
  static constexpr int radix_bits = 28;
  DigitOp op = DigitOp::shadow;
  int lanes = 0;    ///< W: the items of a block (the kernel that ran)
  int entries = 0;  ///< results per item: 24 (shadow) or 22 (reflection)
  int base = 2;     ///< 2 for doubles, 10 for decimal text
  Eigen::Index items = 0;
  std::vector<std::int64_t> digits;  ///< [block][entry][digit < max_digits][lane]
  std::vector<std::int8_t> counts;   ///< [block][entry]: the digits in use
  std::vector<std::uint8_t> done;    ///< [block]: computed here
  std::vector<int> a_exponent, l_exponent;  ///< [item]: A = A_int base^a, L = L_int base^l

  Eigen::Index blocks() const { return lanes ? items / lanes : 0; }
  /// The exact value of result `entry` of `item` (its block done): the integer times base^(the
  /// entry's exponent: P 2a + 2l, pi a + l, R a + 2l, M 2l, B a + 4l).
  Rational value(Eigen::Index item, int entry) const;
  /// The integer alone (the value without the power of the base).
  Rational integer(Eigen::Index item, int entry) const;
};

/// Computes the whole blocks of `in` into `out` (resized; its buffers are reused from call to
/// call). Returns the blocks not done. std::invalid_argument for inf or NaN.
long digit_blocks(DigitOp op, const DoubleItems& in, DigitBlocks& out);
long digit_blocks(DigitOp op, const DecimalItems& in, DigitBlocks& out);

/// The lanes of the kernel digit_blocks runs here, and its instruction set (with "(run-time
/// dispatch)" when it is the second kernel).
int digit_blocks_lanes();
const char* digit_blocks_kernel();
/// The -march of the second digit kernel this build carries and chose ("" for none), and
/// whether it runs here (this processor has its instruction set).
const char* digit_blocks_second_kernel();
bool digit_blocks_dispatched();

}  // namespace qverify
