#pragma once

// Coverage of the Verilated models (scripts/coverage, docs/coverage.md).
//
// In a build with -DLANCER_RTL_COVERAGE=ON the three models are Verilated with
// --coverage-line --coverage-toggle, and every VerilatedUnit attaches its
// context here when it is made and detaches it before its model goes. The
// counts are written only for a test that passed: the GoogleTest listener of
// tests/rtl/coverage_listener.cpp calls endTest() after every test, which
// writes the counts of every live model (and keeps those of the models the
// test destroyed) when the test passed, and throws them away when it failed;
// either way the counters restart from zero for the next test. Files go to
// $LANCER_RTL_COVERAGE_DIR (default ./rtl-coverage), one per model and test,
// named <test>-<pid>-<n>.dat; verilator_coverage merges them.
//
// In every other build these are empty inline functions.

#include <string>

#include "verilated.h"

#ifdef LANCER_RTL_COVERAGE
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>
#include <vector>

#include <unistd.h>

#include "verilated_cov.h"
#endif

namespace lancer::rtl_coverage {

#ifdef LANCER_RTL_COVERAGE

struct Registry {
  std::mutex mutex;
  std::set<VerilatedContext*> live;
  std::vector<std::string> pending;  // counts of models the current test destroyed
  bool closed = false;               // after the last test: nothing more is written
  unsigned serial = 0;
};

// Never destroyed: devices held in static storage detach after main() returns.
inline Registry& registry() {
  static Registry* const r = new Registry;
  return *r;
}

inline std::string fileFor(Registry& r, const std::string& tag) {
  const char* dir = std::getenv("LANCER_RTL_COVERAGE_DIR");
  const std::filesystem::path base = dir && *dir ? dir : "rtl-coverage";
  std::filesystem::create_directories(base);
  std::string safe = tag;
  for (char& c : safe) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return (base / (safe + "-" + std::to_string(::getpid()) + "-" + std::to_string(r.serial++) + ".dat")).string();
}

inline void attach(VerilatedContext& context) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.live.insert(&context);
}

// Before the model of `context` is destroyed (its counters live in the model).
inline void detach(VerilatedContext& context) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.live.erase(&context);
  if (r.closed) return;
  const std::string file = fileFor(r, "pending");
  context.coveragep()->write(file.c_str());
  r.pending.push_back(file);
}

// After each test: keep its counts if it passed, drop them if not.
inline void endTest(bool passed, const std::string& testName) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (VerilatedContext* context : r.live) {
    if (passed) context->coveragep()->write(fileFor(r, testName).c_str());
    context->coveragep()->zero();
  }
  for (const std::string& file : r.pending) {
    if (passed) {
      std::filesystem::rename(file, fileFor(r, testName));
    } else {
      std::filesystem::remove(file);
    }
  }
  r.pending.clear();
}

// After the last test: models destroyed later (static devices) write nothing.
inline void close() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.closed = true;
}

#else

inline void attach(VerilatedContext&) {}
inline void detach(VerilatedContext&) {}

#endif

}  // namespace lancer::rtl_coverage
