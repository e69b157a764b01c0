// The law suite (laws.hpp) for one scalar type.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>

using namespace qverify;

TEST_CASE("laws hold in Float128", "[laws][f128]") {

  test::run_law_suite<Float128>(40);
}
