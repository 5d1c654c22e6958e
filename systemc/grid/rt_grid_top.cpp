#include "grid/rt_grid_top.h"

#include "common/rt_trav_top_impl.h"
#include "grid/rt_grid_model.h"

#if LANCER_SC_HAVE_GRID_RTL
#include "Vrt_grid_sc.h"
#endif

namespace lancer::sc {

template <>
struct rt_trav_rtl<rt_grid_unit> {
#if LANCER_SC_HAVE_GRID_RTL
  using type = Vrt_grid_sc;
#else
  using type = void;  // no LANCER_RTL_GRID_SOURCES
#endif
};

template class rt_trav_top<rt_grid_unit>;

}  // namespace lancer::sc
