// The traversal units of the SystemC build: each unit's system (rt_trav_top
// over its traits, common/rt_trav_top_impl.h) instantiated with its cycle model
// and, when the build has it, its Verilated class. Adding a unit: its traits
// and cycle model (systemc/<unit>/), its Verilated class below, lancer_sc_verilate()
// in systemc/CMakeLists.txt.
#include "common/rt_trav_top_impl.h"
#include "grid/rt_grid_model.h"
#include "octree/rt_octree_model.h"

#if LANCER_SC_HAVE_GRID_RTL
#include "Vrt_grid_sc.h"
#endif
#if LANCER_SC_HAVE_OCTREE_RTL
#include "Vrt_octree_sc.h"
#endif

namespace lancer::sc {

#if LANCER_SC_HAVE_GRID_RTL
template <>
struct rt_trav_rtl<rt_grid_unit> {
  using type = Vrt_grid_sc;
};
#endif
#if LANCER_SC_HAVE_OCTREE_RTL
template <>
struct rt_trav_rtl<rt_octree_unit> {
  using type = Vrt_octree_sc;
};
#endif

template class rt_trav_top<rt_grid_unit>;
template class rt_trav_top<rt_octree_unit>;

}  // namespace lancer::sc
