// The second digit kernel: the digit blocks of digit_batch_impl.hpp compiled with the -march of
// the second kernel (exact/CMakeLists.txt; exact/digit_batch.hpp says why and when it runs).
#include "digit_batch_kernel.hpp"

#include "digit_batch_impl.hpp"

// The point of this file is its instruction set: a -march lost or overridden on the way must fail
// the build, not give a second copy of the build's own kernel.
#if QVERIFY_SECOND_KERNEL_LEVEL == 4 && !defined(__AVX512F__)
#error "the second digit kernel must be compiled with AVX-512 (-march=x86-64-v4)"
#elif QVERIFY_SECOND_KERNEL_LEVEL == 3 && !defined(__AVX2__)
#error "the second digit kernel must be compiled with AVX2 (-march=x86-64-v3)"
#endif

namespace qverify::second_kernel {

long digit_blocks(DigitOp op, const DoubleItems& in, DigitBlocks& out) { return run_blocks(op, in, out); }
long digit_blocks(DigitOp op, const DecimalItems& in, DigitBlocks& out) { return run_blocks(op, in, out); }
int digit_lanes() { return kW; }

}  // namespace qverify::second_kernel
