// The law suite (laws.hpp) for one scalar type.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>

using namespace qverify;

TEST_CASE("laws hold in Mpfr", "[laws][mpfr]") {
  set_mpfr_bits(256);
  test::run_law_suite<Mpfr>(40);
}
