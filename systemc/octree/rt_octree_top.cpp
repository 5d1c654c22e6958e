#include "octree/rt_octree_top.h"

#include "common/rt_trav_top_impl.h"
#include "octree/rt_octree_model.h"

#if LANCER_SC_HAVE_OCTREE_RTL
#include "Vrt_octree_sc.h"
#endif

namespace lancer::sc {

template <>
struct rt_trav_rtl<rt_octree_unit> {
#if LANCER_SC_HAVE_OCTREE_RTL
  using type = Vrt_octree_sc;
#else
  using type = void;  // no LANCER_RTL_OCTREE_SOURCES
#endif
};

template class rt_trav_top<rt_octree_unit>;

}  // namespace lancer::sc
