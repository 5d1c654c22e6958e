#include "common/rt_trav_top.h"

#if LANCER_SC_HAVE_GRID_RTL || LANCER_SC_HAVE_OCTREE_RTL || LANCER_SC_HAVE_RTL
#include "verilated.h"
#endif

namespace lancer::sc {

void use_verilated_context() {
#if LANCER_SC_HAVE_GRID_RTL || LANCER_SC_HAVE_OCTREE_RTL || LANCER_SC_HAVE_RTL
  static VerilatedContext* const context = new VerilatedContext;  // lives as long as the models
  Verilated::threadContextp(context);
#endif
}

}  // namespace lancer::sc
