// The law suite (laws.hpp) for one scalar type.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>

using namespace qverify;

TEST_CASE("laws hold in float", "[laws][float]") {

  test::run_law_suite<float>(40);
}
