#include "driver/systemc_kernel.h"

#include <cstdlib>
#include <map>

#include <systemc>

#include "common/rt_trav_top.h"
#include "isect/rt_isect_top.h"

namespace lancer::systemc_kernel {

namespace {

// SystemC's own messages. Its banner is switched off (before the kernel exists);
// informational reports are dropped and warnings too unless LANCER_SC_VERBOSE is
// set, so that programs print only their own summaries; errors and fatal errors
// are thrown (as sc_core::sc_report) and turned into std::runtime_error by the devices.
void routeReports() {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  using sc_core::sc_report_handler;
  const bool verbose = std::getenv("LANCER_SC_VERBOSE") != nullptr;
  sc_report_handler::set_actions(sc_core::SC_INFO, verbose ? sc_core::SC_DISPLAY : sc_core::SC_DO_NOTHING);
  sc_report_handler::set_actions(sc_core::SC_WARNING, verbose ? sc_core::SC_DISPLAY : sc_core::SC_DO_NOTHING);
  sc_report_handler::set_actions(sc_core::SC_ERROR, sc_core::SC_THROW);
  sc_report_handler::set_actions(sc_core::SC_FATAL, sc_core::SC_THROW);
}

// The traversal systems' builders by their order.
std::map<int, void (*)()>& registry() {
  static std::map<int, void (*)()> builders;
  return builders;
}

// Never destroyed: SystemC cannot tear down an elaborated design and start again.
sc::rt_isect_top& systems() {
  static sc::rt_isect_top* const isect = [] {
    routeReports();
    // Every traversal top makes the Verilated SystemC models' context current
    // before it builds them.
    for (const auto& [order, build] : registry()) build();
    return new sc::rt_isect_top("lancer_isect");
  }();
  return *isect;
}

}  // namespace

std::mutex& mutex() {
  static std::mutex m;
  return m;
}

bool registerTraversalSystem(int order, void (*build)()) {
  registry().emplace(order, build);
  return true;
}

void buildSystems() { systems(); }

// Every run fetches its system through these, under the lock.
sc::rt_isect_top& isectSystem() {
  sc::rt_isect_top& isect = systems();
  sc::use_verilated_context();  // the one context of every Verilated SystemC model
  return isect;
}

}  // namespace lancer::systemc_kernel
