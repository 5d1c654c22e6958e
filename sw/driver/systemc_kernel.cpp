#include "driver/systemc_kernel.h"

#include <cstdlib>

#include <systemc>

#include "grid/rt_grid_unit.h"
#include "isect/rt_isect_top.h"
#include "octree/rt_octree_unit.h"

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

struct Systems {
  sc::rt_isect_top* isect;
  sc::rt_grid_top* grid;
  sc::rt_octree_top* octree;
  sc::rt_trav_top<sc::rt_grid_unit>& of(sc::rt_grid_unit*) { return *grid; }
  sc::rt_trav_top<sc::rt_octree_unit>& of(sc::rt_octree_unit*) { return *octree; }
};

// Never destroyed: SystemC cannot tear down an elaborated design and start again.
Systems& systems() {
  static Systems* const all = [] {
    routeReports();
    // Every traversal top makes the Verilated SystemC models' context current
    // before it builds them; the grid's comes first, as it always has.
    auto* grid = new sc::rt_grid_top("lancer_grid");
    auto* isect = new sc::rt_isect_top("lancer_isect");
    return new Systems{isect, grid, new sc::rt_octree_top("lancer_octree")};
  }();
  return *all;
}

}  // namespace

std::mutex& mutex() {
  static std::mutex m;
  return m;
}

// Every run fetches its system through these, under the lock.
sc::rt_isect_top& isectSystem() {
  Systems& all = systems();
  sc::use_verilated_context();  // the one context of every Verilated SystemC model
  return *all.isect;
}

template <class Unit>
sc::rt_trav_top<Unit>& traversalSystem() {
  Systems& all = systems();
  sc::use_verilated_context();
  return all.of(static_cast<Unit*>(nullptr));
}

template sc::rt_grid_top& traversalSystem<sc::rt_grid_unit>();
template sc::rt_octree_top& traversalSystem<sc::rt_octree_unit>();

}  // namespace lancer::systemc_kernel
