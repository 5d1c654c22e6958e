// Linked into the RTL GoogleTest programs of a -DLANCER_RTL_COVERAGE=ON build
// (tests/rtl/CMakeLists.txt, scripts/coverage): after every test it hands the
// test's verdict to sw/driver/rtl_coverage.h, which writes the Verilated
// models' coverage counts only when the test passed.
#include <string>

#include <gtest/gtest.h>

#include "driver/rtl_coverage.h"

#ifndef LANCER_RTL_COVERAGE
#error "coverage_listener.cpp belongs to a LANCER_RTL_COVERAGE build only"
#endif

namespace {

class CoverageListener : public testing::EmptyTestEventListener {
  void OnTestEnd(const testing::TestInfo& info) override {
    lancer::rtl_coverage::endTest(info.result()->Passed() && !info.result()->Skipped(),
                                  std::string(info.test_suite_name()) + "." + info.name());
  }
  void OnTestProgramEnd(const testing::UnitTest&) override { lancer::rtl_coverage::close(); }
};

// Registered before main() (gtest_main) runs the tests; GoogleTest owns the listener.
const bool kRegistered = [] {
  testing::UnitTest::GetInstance()->listeners().Append(new CoverageListener);
  return true;
}();

}  // namespace
