// rt_grid's SystemC system (rt_trav_top over its traits, common/rt_trav_top_impl.h),
// instantiated with its cycle model and, when the build has it, its Verilated class.
#include "common/rt_trav_top_impl.h"
#include "grid/rt_grid_model.h"

#if LANCER_SC_HAVE_GRID_RTL
#include "Vrt_grid_sc.h"

namespace lancer::sc {
template <>
struct rt_trav_rtl<rt_grid_unit> {
  using type = Vrt_grid_sc;
};
}  // namespace lancer::sc
#endif

template class lancer::sc::rt_trav_top<lancer::sc::rt_grid_unit>;
