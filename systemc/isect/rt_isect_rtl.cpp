#include "isect/rt_isect_rtl.h"

#include <stdexcept>

#if LANCER_SC_HAVE_RTL
#include "Vrt_isect_sc.h"
#endif

namespace lancer::sc {

std::unique_ptr<sc_core::sc_module> make_rtl_isect([[maybe_unused]] const char* name,
                                                   [[maybe_unused]] sc_core::sc_in<bool>& clk,
                                                   [[maybe_unused]] sc_core::sc_in<bool>& rst,
                                                   [[maybe_unused]] rt_isect_signals& s) {
#if LANCER_SC_HAVE_RTL
  auto m = std::make_unique<Vrt_isect_sc>(name);
  m->clk_i(clk);
  m->rst_ni(rst);
  bindIsectPorts(*m, s);
  return m;
#else
  throw std::runtime_error("the Verilated rt_isect is not part of this build");
#endif
}

}  // namespace lancer::sc
