// The law suite (laws.hpp) for one scalar type.
#include "laws.hpp"

#include <qverify/exact/scalars.hpp>

using namespace qverify;

TEST_CASE("laws hold in long double", "[laws][f80]") {

  test::run_law_suite<long double>(40);
}
