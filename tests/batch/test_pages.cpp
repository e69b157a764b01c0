// batch/pages.hpp: the huge-page advice covers whole huge pages inside a buffer and nothing else, never
// changes a value, and the batch functions give it to the outputs they allocate (sized_output).
#include <qverify/batch/batch.hpp>
#include <qverify/batch/pages.hpp>
#include <qverify/exact/scalars.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <vector>

using namespace qverify;

namespace {
/// Whether this kernel has transparent huge pages (then madvise(MADV_HUGEPAGE) must succeed).
bool kernel_has_thp() { return std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled").good(); }
}  // namespace

TEST_CASE("huge-page advice covers the whole huge pages inside a buffer and only those", "[batch][pages]") {
  const std::size_t page = huge_page_bytes();
  CHECK(page >= 4096);
  CHECK((page & (page - 1)) == 0);
  if (page > (std::size_t(2) << 20)) return;  // (e.g. 512 MiB with 64 KiB base pages: buffers of that size are not for a unit test)
  CHECK(advise_huge_pages(nullptr, 8 * page) == 0);
  std::vector<double> small(1000, 1.5);
  CHECK(advise_huge_pages(small.data(), small.size() * sizeof(double)) == 0);  // less than one huge page
  std::vector<char> big(5 * page + 12345, 7);  // 5 huge pages and a bit (10 MiB): 4 or 5 whole aligned ones inside
  const std::size_t advised = advise_huge_pages(big.data(), big.size());
  const auto begin = reinterpret_cast<std::uintptr_t>(big.data());
  const std::uintptr_t first = (begin + page - 1) / page * page;  // the first whole huge page inside
  CHECK(advised % page == 0);
  CHECK(first + advised <= begin + big.size());  // the advised range ends inside the buffer
  if (kernel_has_thp()) {
    CHECK(advised >= 4 * page);
    CHECK(advised <= 5 * page);
  } else {
    CHECK(advised == 0);
  }
  CHECK(std::count(big.begin(), big.end(), 7) == static_cast<std::ptrdiff_t>(big.size()));  // no value changed
}

TEST_CASE("an output batch is sized to the items and its storage reused when it has the size already", "[batch][pages]") {
  // storage Eigen constructs in resize (exact rationals) has been touched already: not advised
  SymBatch<Rational> Q;
  CHECK(sized_output(Q, 1000) == 0);
  CHECK(Q.rows() == 1000);
  if (huge_page_bytes() > (std::size_t(2) << 20)) return;  // as above
  SymBatch<double> X;
  CHECK(sized_output(X, 3) == 0);  // 240 bytes: no whole huge page
  CHECK(X.rows() == 3);
  X.setConstant(2.0);
  const double* storage = X.data();
  CHECK(sized_output(X, 3) == 0);
  CHECK(X.data() == storage);
  CHECK((X.array() == 2.0).all());
  // just over 4 huge pages, so at least 3 whole aligned ones inside wherever the storage starts
  const Eigen::Index n = 4 * static_cast<Eigen::Index>(huge_page_bytes() / (10 * sizeof(double))) + 1;
  const std::size_t advised = sized_output(X, n);
  CHECK(X.rows() == n);
  CHECK(X.cols() == 10);
  if (kernel_has_thp()) CHECK(advised >= 3 * huge_page_bytes());  // the new storage was advised
  X.setConstant(-1.0);  // written after the advice, as the batches write it
  CHECK((X.array() == -1.0).all());
}

TEST_CASE("batches large enough for huge pages give the single-item results", "[batch][pages]") {
  const Eigen::Index n = 40000;  // P, R, B and M of 3 MiB and more (2 MiB huge pages): sized_output advises them
  SymBatch<double> A(n, 10);
  Vec4Batch<double> L(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = static_cast<double>(i % 97) / 8;
    A.row(i) << 2 + t, 0, 0, -t, 1, 0, 1, 3, 0, -5 - t;
    L.row(i) << t, 1 - t, 4 + t, 1;  // point lights only: every block runs in packs
  }
  SymBatch<double> P, R, B;
  Vec4Batch<double> pi;
  AffineBatch<double> M;
  shadow_batch<double>(A, L, Method::direct, P, pi, R, 2);
  reflection_batch<double>(A, L, Method::direct, M, B, 2);
  for (Eigen::Index i = 0; i < n; i += 997) {
    const Mat4<double> a = gather_sym(A, i);
    const Vec4<double> l = L.row(i).transpose();
    const Vec4<double> p = polar_plane<double>(a, l);
    CHECK(gather_sym(P, i) == tangent_cone_from_polar<double>(a, l, p));
    CHECK(Vec4<double>(pi.row(i).transpose()) == p);
    CHECK(gather_sym(R, i) == terminator_quadric_from_polar<double>(l, p));
    CHECK(gather_sym(B, i) == mirror_image_of_plane<double>(a, l));
    const Mat4<double> m = mirror_matrix<double>(l);
    for (int k = 0; k < 12; ++k) CHECK(M(i, k) == m(k / 4, k % 4));
  }
}
