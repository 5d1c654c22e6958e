#include "isect/rt_isect_top.h"

#include <stdexcept>

#include "isect/rt_isect_bench.h"
#include "isect/rt_isect_pin_model.h"

#if LANCER_SC_HAVE_RTL
#include "Vrt_isect_sc.h"
#include "verilated.h"
#if LANCER_SC_RTL_FST
#include "verilated_fst_sc.h"
#endif
#endif

namespace lancer::sc {

rt_isect_top::rt_isect_top(sc_core::sc_module_name name) : sc_core::sc_module(name) {
  auto model = std::make_unique<rt_isect_bench<rt_isect_pin_model>>("u_model");
  model_tb_ = &model->u_tb;
  model_ = std::move(model);
#if LANCER_SC_HAVE_RTL
#if LANCER_SC_RTL_FST
  Verilated::traceEverOn(true);  // before the Verilated model is built
#endif
  auto rtl = std::make_unique<rt_isect_bench<Vrt_isect_sc>>("u_rtl");
  rtl_tb_ = &rtl->u_tb;
  rtl_ = std::move(rtl);
#endif
}

rt_isect_top::~rt_isect_top() = default;

bool rt_isect_top::has_rtl() { return LANCER_SC_HAVE_RTL != 0; }

bool rt_isect_top::has_waves() { return has_rtl() && rt_fst_wave::available(); }

rt_isect_tb& rt_isect_top::tb(rt_isect_impl impl) {
  if (impl == rt_isect_impl::model) return *model_tb_;
  if (rtl_tb_ == nullptr) {
    throw std::runtime_error("the Verilated RTL is not part of this build (configure with the RTL sources)");
  }
  return *rtl_tb_;
}

void rt_isect_top::open_wave([[maybe_unused]] const std::string& path) {
#if LANCER_SC_HAVE_RTL && LANCER_SC_RTL_FST
  auto& dut = static_cast<rt_isect_bench<Vrt_isect_sc>*>(rtl_.get())->u_dut;
  wave_.open(path, [&dut](VerilatedFstSc* fst) { dut.trace(fst, 99); });
#else
  throw std::runtime_error("the Verilated RTL of this build has no FST tracing");
#endif
}

void rt_isect_top::close_wave() { wave_.close(); }

}  // namespace lancer::sc
