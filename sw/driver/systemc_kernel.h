#pragma once

// The one SystemC kernel of the process, shared by every SystemC device.
//
// SystemC elaborates once per process and cannot instantiate modules after the
// first sc_start(), so every SystemC system a device may run (the intersection
// pipeline's rt_isect_top, and each traversal unit's rt_trav_top, registered
// by its systemc_<unit>_device.cpp) is built together on the first use of any
// of them and kept for the life of the process. Runs of
// any SystemC device are serialized by one mutex (one kernel per process).
// The first use also routes SystemC's reports (banner off, info and warnings
// dropped unless LANCER_SC_VERBOSE is set, errors thrown as sc_report).

#include <mutex>

namespace lancer::sc {
class rt_isect_top;
}  // namespace lancer::sc

namespace lancer::systemc_kernel {

std::mutex& mutex();
sc::rt_isect_top& isectSystem();

// Adds a traversal unit's system to those built on the first use (`build`
// makes it); the systems are built in `order` (its fx::UnitKind), then the
// intersection pipeline's. Returns true, for a static registration.
bool registerTraversalSystem(int order, void (*build)());
// Builds every registered system, once.
void buildSystems();

}  // namespace lancer::systemc_kernel
