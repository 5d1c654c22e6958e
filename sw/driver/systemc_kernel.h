#pragma once

// The one SystemC kernel of the process, shared by every SystemC device.
//
// SystemC elaborates once per process and cannot instantiate modules after the
// first sc_start(), so every SystemC system a device may run (the intersection
// pipeline's rt_isect_top, the grid unit's rt_grid_top, the octree unit's
// rt_octree_top) is built together on
// the first use of any of them and kept for the life of the process. Runs of
// any SystemC device are serialized by one mutex (one kernel per process).
// The first use also routes SystemC's reports (banner off, info and warnings
// dropped unless LANCER_SC_VERBOSE is set, errors thrown as sc_report).

#include <mutex>

namespace lancer::sc {
class rt_isect_top;
template <class Unit>
class rt_trav_top;
struct rt_grid_unit;
struct rt_octree_unit;
}  // namespace lancer::sc

namespace lancer::systemc_kernel {

std::mutex& mutex();
sc::rt_isect_top& isectSystem();
// The system of a traversal unit (sc::rt_grid_unit, sc::rt_octree_unit).
template <class Unit>
sc::rt_trav_top<Unit>& traversalSystem();

}  // namespace lancer::systemc_kernel
