// exact/digit_batch.hpp: the build's own digit blocks, the dispatch to the second kernel
// (digit_batch_kernel.cpp) where the configure measured it faster and the processor has it, and
// the reading of the results.
#include "digit_batch_impl.hpp"

#include "digit_batch_kernel.hpp"
#include "processor_level.hpp"

#include <qverify/exact/interval_batch.hpp>

#ifndef QVERIFY_DIGIT_SECOND_KERNEL_LEVEL  // set by exact/CMakeLists.txt where the build has one
#define QVERIFY_DIGIT_SECOND_KERNEL_LEVEL 0
#endif

#include <stdexcept>
#include <string>

namespace qverify {
namespace {

/// Does the second kernel exist in this build and run on this processor?
bool second_digit_kernel_here() { return second_kernel_runs(QVERIFY_DIGIT_SECOND_KERNEL_LEVEL); }

template <class Items> long dispatch(DigitOp op, const Items& in, DigitBlocks& out) {
  if (in.n < 0) throw std::invalid_argument("digit_blocks: a negative item count");
#if QVERIFY_DIGIT_SECOND_KERNEL_LEVEL  // (else no call to it, not even an unreachable one)
  if (second_digit_kernel_here()) return second_kernel::digit_blocks(op, in, out);
#endif
  return run_blocks(op, in, out);
}

}  // namespace

long digit_blocks(DigitOp op, const DoubleItems& in, DigitBlocks& out) { return dispatch(op, in, out); }
long digit_blocks(DigitOp op, const DecimalItems& in, DigitBlocks& out) { return dispatch(op, in, out); }

int digit_blocks_lanes() {
#if QVERIFY_DIGIT_SECOND_KERNEL_LEVEL
  if (second_digit_kernel_here()) return second_kernel::digit_lanes();
#endif
  return kW;
}

const char* digit_blocks_second_kernel() {
#if QVERIFY_DIGIT_SECOND_KERNEL_LEVEL
  return QVERIFY_DIGIT_SECOND_KERNEL_MARCH;
#else
  return "";
#endif
}

bool digit_blocks_dispatched() { return second_digit_kernel_here(); }

const char* digit_blocks_kernel() {
#if QVERIFY_DIGIT_SECOND_KERNEL_LEVEL
  if (second_digit_kernel_here()) return QVERIFY_DIGIT_SECOND_KERNEL_NAME " (run-time dispatch)";
#endif
  return build_instruction_set();
}

Rational DigitBlocks::integer(Eigen::Index item, int entry) const {
  if (item < 0 || item >= blocks() * lanes || entry < 0 || entry >= entries)
    throw std::out_of_range("DigitBlocks: no such item or entry");
  const Eigen::Index b = item / lanes;
  const int lane = static_cast<int>(item % lanes);
  if (!done[static_cast<std::size_t>(b)]) throw std::logic_error("DigitBlocks: that item's block was not computed");
  const auto at = static_cast<std::size_t>(b * entries + entry);
  const int n = counts[at];
  const std::int64_t* d = &digits[at * max_digits * static_cast<std::size_t>(lanes)];
  boost::multiprecision::mpz_int z = 0;
  if (n > 0) {
    z = d[static_cast<std::size_t>((n - 1) * lanes + lane)];  // the top digit, signed
    for (int k = n - 2; k >= 0; --k) {
      z <<= radix_bits;
      z += d[static_cast<std::size_t>(k * lanes + lane)];  // the lower ones, in [0, 2^28)
    }
  }
  return Rational(z);
}

Rational DigitBlocks::value(Eigen::Index item, int entry) const {
  Rational v = integer(item, entry);
  const auto i = static_cast<std::size_t>(item);
  const int a = a_exponent[i], l = l_exponent[i];
  // the entry's exponent: P 2a + 2l, pi a + l, R a + 2l; M 2l, B a + 4l
  const int e = op == DigitOp::shadow ? (entry < 10 ? 2 * a + 2 * l : entry < 14 ? a + l : a + 2 * l)
                                      : (entry < 12 ? 2 * l : a + 4 * l);
  boost::multiprecision::mpz_int p = 1;
  for (int k = 0; k < std::abs(e); ++k) p *= base;
  return e >= 0 ? Rational(v * Rational(p)) : Rational(v / Rational(p));
}

}  // namespace qverify
