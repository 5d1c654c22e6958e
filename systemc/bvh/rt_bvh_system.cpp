// rt_bvh's SystemC system (rt_trav_top over its traits, common/rt_trav_top_impl.h),
// instantiated with its cycle model and, when the build has it, its Verilated class.
#include "common/rt_trav_top_impl.h"
#include "bvh/rt_bvh_model.h"

#if LANCER_SC_HAVE_BVH_RTL
#include "Vrt_bvh_sc.h"

namespace lancer::sc {
template <>
struct rt_trav_rtl<rt_bvh_unit> {
  using type = Vrt_bvh_sc;
};
}  // namespace lancer::sc
#endif

template class lancer::sc::rt_trav_top<lancer::sc::rt_bvh_unit>;
