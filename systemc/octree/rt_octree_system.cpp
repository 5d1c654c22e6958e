// rt_octree's SystemC system (rt_trav_top over its traits, common/rt_trav_top_impl.h),
// instantiated with its cycle model and, when the build has it, its Verilated class.
#include "common/rt_trav_top_impl.h"
#include "octree/rt_octree_model.h"

#if LANCER_SC_HAVE_OCTREE_RTL
#include "Vrt_octree_sc.h"

namespace lancer::sc {
template <>
struct rt_trav_rtl<rt_octree_unit> {
  using type = Vrt_octree_sc;
};
}  // namespace lancer::sc
#endif

template class lancer::sc::rt_trav_top<lancer::sc::rt_octree_unit>;
