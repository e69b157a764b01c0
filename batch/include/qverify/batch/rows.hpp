#pragma once
/// \file rows.hpp
/// The batch layout alone (no SIMD, no threads): what an API that takes or
/// returns batches needs to name them. A batch of symmetric matrices is an
/// `n x 10` row-major Eigen matrix, item i's ten entries (A00 A01 A02 A03 A11
/// A12 A13 A22 A23 A33) contiguous; a batch of 4-vectors is `n x 4`; the
/// three non-trivial rows of affine matrices, `n x 12`. batch.hpp computes
/// them.

#include <Eigen/Core>

namespace qverify {

template <class S> using SymBatch = Eigen::Matrix<S, Eigen::Dynamic, 10, Eigen::RowMajor>;
template <class S> using Vec4Batch = Eigen::Matrix<S, Eigen::Dynamic, 4, Eigen::RowMajor>;
/// The three non-trivial rows of mirror matrices (row 4 is 0 0 0 1).
template <class S> using AffineBatch = Eigen::Matrix<S, Eigen::Dynamic, 12, Eigen::RowMajor>;

/// Entry order of a symmetric matrix in a SymBatch row.
constexpr int kSymRow[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
constexpr int kSymCol[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

}  // namespace qverify
