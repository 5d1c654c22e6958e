#include "isect/rt_isect_top.h"

#include <stdexcept>

#include "isect/rt_pipe_bench.h"
#include "isect/rt_pipe_pin_model.h"

#if LANCER_SC_HAVE_RTL
#include "Vrt_isect_sc.h"
#include "Vrt_quadric_sc.h"
#include "verilated.h"
#if LANCER_SC_RTL_FST
#include "verilated_fst_sc.h"
#endif
#endif

namespace lancer::sc {

namespace {

// A pipeline's bench of one implementation, its testbench noted in `tb`.
template <class Kind, class Dut>
std::unique_ptr<sc_core::sc_module> makeBench(const char* name, rt_pipe_tb<Kind>*& tb) {
  auto bench = std::make_unique<rt_pipe_bench<Kind, Dut>>(name);
  tb = &bench->u_tb;
  return bench;
}

}  // namespace

rt_isect_top::rt_isect_top(sc_core::sc_module_name name) : sc_core::sc_module(name) {
  isect_.model = makeBench<isect_kind, rt_pipe_pin_model<isect_kind>>("u_model", isect_.model_tb);
  quadric_.model = makeBench<quadric_kind, rt_pipe_pin_model<quadric_kind>>("u_quadric_model", quadric_.model_tb);
#if LANCER_SC_HAVE_RTL
#if LANCER_SC_RTL_FST
  Verilated::traceEverOn(true);  // before the Verilated models are built
#endif
  isect_.rtl = makeBench<isect_kind, Vrt_isect_sc>("u_rtl", isect_.rtl_tb);
  quadric_.rtl = makeBench<quadric_kind, Vrt_quadric_sc>("u_quadric_rtl", quadric_.rtl_tb);
#endif
}

rt_isect_top::~rt_isect_top() = default;

bool rt_isect_top::has_rtl() { return LANCER_SC_HAVE_RTL != 0; }

bool rt_isect_top::has_waves() { return has_rtl() && rt_fst_wave::available(); }

template <>
rt_isect_top::benches<isect_kind>& rt_isect_top::of<isect_kind>() { return isect_; }
template <>
rt_isect_top::benches<quadric_kind>& rt_isect_top::of<quadric_kind>() { return quadric_; }

template <class Kind>
rt_pipe_tb<Kind>& rt_isect_top::tb(rt_isect_impl impl) {
  benches<Kind>& b = of<Kind>();
  if (impl == rt_isect_impl::model) return *b.model_tb;
  if (b.rtl_tb == nullptr) {
    throw std::runtime_error("the Verilated RTL is not part of this build (configure with the RTL sources)");
  }
  return *b.rtl_tb;
}

template <class Kind>
void rt_isect_top::open_wave([[maybe_unused]] const std::string& path) {
#if LANCER_SC_HAVE_RTL && LANCER_SC_RTL_FST
  using Dut = std::conditional_t<std::is_same_v<Kind, isect_kind>, Vrt_isect_sc, Vrt_quadric_sc>;
  auto& dut = static_cast<rt_pipe_bench<Kind, Dut>*>(of<Kind>().rtl.get())->u_dut;
  wave_.open(path, [&dut](VerilatedFstSc* fst) { dut.trace(fst, 99); });
#else
  throw std::runtime_error("the Verilated RTL of this build has no FST tracing");
#endif
}

void rt_isect_top::close_wave() { wave_.close(); }

template rt_pipe_tb<isect_kind>& rt_isect_top::tb<isect_kind>(rt_isect_impl);
template rt_pipe_tb<quadric_kind>& rt_isect_top::tb<quadric_kind>(rt_isect_impl);
template void rt_isect_top::open_wave<isect_kind>(const std::string&);
template void rt_isect_top::open_wave<quadric_kind>(const std::string&);

}  // namespace lancer::sc
