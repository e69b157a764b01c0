// The law suite (laws.hpp) for one scalar type.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>

using namespace qverify;

TEST_CASE("laws hold in Rational", "[laws][exact]") {

  test::run_law_suite<Rational>(40);
}
