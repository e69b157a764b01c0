#pragma once
// The digit blocks of exact/digit_batch.hpp, compiled twice: by digit_batch.cpp for the build's
// instruction set and by digit_batch_kernel.cpp for the second kernel's (exact/CMakeLists.txt),
// whose symbols are made local but its entry points. Internal linkage here, so that the two copies
// (with packs of different widths) never meet.
#include <qverify/batch/rows.hpp>
#include <qverify/core/mirror.hpp>
#include <qverify/core/mirror_division_free.hpp>
#include <qverify/core/shadow.hpp>
#include <qverify/exact/digit_batch.hpp>
#include <qverify/exact/digit_pack.hpp>
#include <qverify/exact/wide_int.hpp>

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace qverify {
namespace {

using DP = DigitPack<DigitBlocks::max_digits>;
static_assert(DP::radix_bits == DigitBlocks::radix_bits, "DigitBlocks reads DigitPack's digits");
constexpr int kW = DP::lanes;

/// Block b of doubles: lane l is item W b + l; false when an item does not fit.
bool load_block(const DoubleItems& in, Eigen::Index b, DP (&a)[10], DP (&l)[4], int (&ea)[kW], int (&el)[kW]) {
  const double* xa[kW];
  const double* xl[kW];
  for (int j = 0; j < kW; ++j) {
    const auto i = static_cast<std::size_t>(b * kW + j);
    xa[j] = in.a + 10 * i, xl[j] = in.l + 4 * i;
  }
  return DP::from_doubles(xa, 10, a, ea) && DP::from_doubles(xl, 4, l, el);
}

/// count entries of W items of decimal text as DigitPacks, lane j times 10^k[j] (its smallest exponent).
bool decimal_lanes(const std::int64_t* const (&m)[kW], const int* const (&e)[kW], int count, DP* out, int (&k)[kW]) {
  __int128 v[10][kW];
  for (int j = 0; j < kW; ++j) {
    k[j] = e[j][0];
    for (int c = 1; c < count; ++c) k[j] = std::min(k[j], e[j][c]);
    for (int c = 0; c < count; ++c)
      if (!decimal_to_int128(m[j][c], e[j][c] - k[j], v[c][j])) return false;
  }
  const int bits = DP::bits_of(&v[0][0], count * kW);  // one bound, one digit count for the matrix
  for (int c = 0; c < count; ++c) out[c] = DP::from_lanes(v[c], bits);
  return true;
}

bool load_block(const DecimalItems& in, Eigen::Index b, DP (&a)[10], DP (&l)[4], int (&ea)[kW], int (&el)[kW]) {
  const std::int64_t* am[kW];
  const std::int64_t* lm[kW];
  const int* ae[kW];
  const int* le[kW];
  for (int j = 0; j < kW; ++j) {
    const auto i = static_cast<std::size_t>(b * kW + j);
    am[j] = in.am + 10 * i, ae[j] = in.ae + 10 * i, lm[j] = in.lm + 4 * i, le[j] = in.le + 4 * i;
  }
  return decimal_lanes(am, ae, 10, a, ea) && decimal_lanes(lm, le, 4, l, el);
}

/// Entry `entry` of block b: normalized, its digits copied lane-major.
void store(DigitBlocks& out, Eigen::Index b, int entry, const DP& x) {
  x.normalize();
  const auto at = static_cast<std::size_t>(b * out.entries + entry);
  out.counts[at] = static_cast<std::int8_t>(x.digits());
  x.copy_digits(&out.digits[at * DigitBlocks::max_digits * kW]);
}

template <class Items> long run_blocks(DigitOp op, const Items& in, DigitBlocks& out) {
  out.op = op;
  out.lanes = kW;
  out.entries = op == DigitOp::shadow ? 24 : 22;
  out.base = std::is_same_v<Items, DoubleItems> ? 2 : 10;
  out.items = in.n;
  const Eigen::Index blocks = out.blocks();
  const auto nb = static_cast<std::size_t>(blocks), ne = static_cast<std::size_t>(out.entries);
  out.digits.resize(nb * ne * DigitBlocks::max_digits * kW);
  out.counts.assign(nb * ne, 0);
  out.done.assign(nb, 0);
  out.a_exponent.assign(static_cast<std::size_t>(in.n), 0);
  out.l_exponent.assign(static_cast<std::size_t>(in.n), 0);
  long left = 0;
  DP a[10], l[4];
  Mat4<DP> A;
  Vec4<DP> L;
  int ea[kW], el[kW];
  for (Eigen::Index b = 0; b < blocks; ++b) {
    try {
      if (!load_block(in, b, a, l, ea, el)) {
        ++left;
        continue;
      }
      for (int k = 0; k < 10; ++k) A(kSymRow[k], kSymCol[k]) = A(kSymCol[k], kSymRow[k]) = a[k];
      for (int k = 0; k < 4; ++k) L(k) = l[k];
      if (op == DigitOp::shadow) {
        const Vec4<DP> p = polar_plane<DP>(A, L);
        const Mat4<DP> P = tangent_cone_from_polar<DP>(A, L, p);
        const Mat4<DP> R = terminator_quadric_from_polar<DP>(L, p);
        for (int k = 0; k < 10; ++k) store(out, b, k, P(kSymRow[k], kSymCol[k]));
        for (int k = 0; k < 4; ++k) store(out, b, 10 + k, p(k));
        for (int k = 0; k < 10; ++k) store(out, b, 14 + k, R(kSymRow[k], kSymCol[k]));
      } else {
        const Mat4<DP> M = scaled_mirror_matrix<DP>(L);
        const Mat4<DP> B = mirror_image_division_free<DP>(A, L);
        for (int k = 0; k < 12; ++k) store(out, b, k, M(k / 4, k % 4));
        for (int k = 0; k < 10; ++k) store(out, b, 12 + k, B(kSymRow[k], kSymCol[k]));
      }
    } catch (const DigitPackOverflow&) {
      ++left;
      continue;
    } catch (const MixedLanes&) {
      ++left;
      continue;
    }
    out.done[static_cast<std::size_t>(b)] = 1;
    for (int j = 0; j < kW; ++j) {
      const auto i = static_cast<std::size_t>(b * kW + j);
      out.a_exponent[i] = ea[j], out.l_exponent[i] = el[j];
    }
  }
  return left;
}

}  // namespace
}  // namespace qverify
