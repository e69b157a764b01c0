// batch/pages.hpp: the huge-page advice covers whole 2 MiB pages inside a buffer and nothing else, never
// changes a value, and the batch functions give it to the outputs they allocate (sized_output).
#include <qverify/batch/batch.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

using namespace qverify;

TEST_CASE("huge-page advice covers the whole 2 MiB pages inside a buffer, and only those", "[batch][pages]") {
  CHECK(advise_huge_pages(nullptr, 8 * kHugePageBytes) == 0);
  std::vector<double> small(1000, 1.5);
  CHECK(advise_huge_pages(small.data(), small.size() * sizeof(double)) == 0);  // less than one huge page
  std::vector<char> big(5 * kHugePageBytes + 12345, 7);
  const std::size_t advised = advise_huge_pages(big.data(), big.size());
  CHECK(advised % kHugePageBytes == 0);
  CHECK(advised <= big.size());
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // 5 MiB + change hold at least 4 whole aligned huge pages wherever they start; a system without
  // transparent huge pages refuses the advice (0)
  if (advised != 0) CHECK(advised >= 4 * kHugePageBytes);
#else
  CHECK(advised == 0);
#endif
  CHECK(std::count(big.begin(), big.end(), 7) == static_cast<std::ptrdiff_t>(big.size()));  // no value changed
}

TEST_CASE("an output batch is sized to the items, its storage reused when it has the size already", "[batch][pages]") {
  SymBatch<double> X;
  sized_output(X, 3);
  CHECK(X.rows() == 3);
  X.setConstant(2.0);
  const double* storage = X.data();
  sized_output(X, 3);
  CHECK(X.data() == storage);
  CHECK((X.array() == 2.0).all());
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(kHugePageBytes / (10 * sizeof(double)));  // 6 MiB
  sized_output(X, n);
  CHECK(X.rows() == n);
  CHECK(X.cols() == 10);
  X.setConstant(-1.0);  // the new storage is written after the advice, as the batches write it
  CHECK((X.array() == -1.0).all());
}

TEST_CASE("a batch large enough for huge pages gives the single-item results", "[batch][pages]") {
  const Eigen::Index n = 40000;  // outputs of 3 MiB and more: sized_output advises them
  SymBatch<double> A(n, 10);
  Vec4Batch<double> L(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = static_cast<double>(i % 97) / 8;
    A.row(i) << 2 + t, 0, 0, -t, 1, 0, 1, 3, 0, -5 - t;
    L.row(i) << t, 1 - t, 4 + t, i % 2;
  }
  SymBatch<double> P, R;
  Vec4Batch<double> pi;
  shadow_batch<double>(A, L, Method::direct, P, pi, R, 2);
  for (Eigen::Index i = 0; i < n; i += 997) {
    const Mat4<double> a = gather_sym(A, i);
    const Vec4<double> l = L.row(i).transpose();
    const Vec4<double> p = polar_plane<double>(a, l);
    CHECK(gather_sym(P, i) == tangent_cone_from_polar<double>(a, l, p));
    CHECK(Vec4<double>(pi.row(i).transpose()) == p);
    CHECK(gather_sym(R, i) == terminator_quadric_from_polar<double>(l, p));
  }
}
