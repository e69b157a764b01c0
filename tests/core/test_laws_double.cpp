// The law suite (laws.hpp) for one scalar type.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>

using namespace qverify;

TEST_CASE("laws hold in double", "[laws][double]") {

  test::run_law_suite<double>(40);
}
