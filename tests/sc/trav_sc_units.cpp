// The shared SystemC suite over this test program's unit (LANCER_TEST_UNIT,
// its descriptor, from tests/sc/CMakeLists.txt's loop over the units).
#include "trav_sc_suite.h"

namespace lancer::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Unit, ScTraversal, fx::LANCER_TEST_UNIT);
}  // namespace lancer::test
