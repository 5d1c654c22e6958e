// The shared RTL suite over this test program's unit (LANCER_TEST_UNIT, its
// descriptor, from tests/rtl/CMakeLists.txt's loop over the units).
#include "trav_rtl_suite.h"

namespace lancer::rtltest {
INSTANTIATE_TYPED_TEST_SUITE_P(Unit, RtTraversal, fx::LANCER_TEST_UNIT);
}  // namespace lancer::rtltest
