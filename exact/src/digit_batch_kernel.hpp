#pragma once
// The entry points of the second digit kernel (digit_batch_kernel.cpp, compiled for the other
// x86-64 level; exact/digit_batch.hpp says why). Only qverify::second_kernel::* stays global in
// its object (exact/CMakeLists.txt). The outputs are plain structures of std::vector: the same
// layout whatever the instruction set, allocated by the one global operator new.
#include <qverify/exact/digit_batch.hpp>

namespace qverify::second_kernel {

long digit_blocks(DigitOp op, const DoubleItems& in, DigitBlocks& out);
long digit_blocks(DigitOp op, const DecimalItems& in, DigitBlocks& out);
/// The lanes of its packs.
int digit_lanes();

}  // namespace qverify::second_kernel
