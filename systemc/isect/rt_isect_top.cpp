#include "isect/rt_isect_top.h"

#include <stdexcept>

#include "isect/rt_isect_bench.h"
#include "isect/rt_isect_model.h"

#if LANCER_SC_HAVE_RTL
#include "Vrt_isect_sc.h"
#include "verilated.h"
#if LANCER_SC_RTL_FST
#include "verilated_fst_sc.h"
#endif
#endif

namespace lancer::sc {

struct rt_isect_top::wave {
#if LANCER_SC_HAVE_RTL && LANCER_SC_RTL_FST
  std::unique_ptr<VerilatedFstSc> fst;
  // VerilatedFstSc registers itself with the kernel in its constructor but never
  // unregisters (it expects to live until exit), and derives from sc_trace_file
  // privately: the C-style cast is the one conversion that may name a private
  // base. Needed so that one FST per run can be opened and dropped again.
  sc_core::sc_trace_file* kernelHandle() const { return (sc_core::sc_trace_file*)fst.get(); }
#endif
};

rt_isect_top::rt_isect_top(sc_core::sc_module_name name) : sc_core::sc_module(name) {
  auto model = std::make_unique<rt_isect_bench<rt_isect_model>>("u_model");
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

bool rt_isect_top::has_waves() {
#if LANCER_SC_HAVE_RTL && LANCER_SC_RTL_FST
  return true;
#else
  return false;
#endif
}

rt_isect_tb& rt_isect_top::tb(rt_isect_impl impl) {
  if (impl == rt_isect_impl::model) return *model_tb_;
  if (rtl_tb_ == nullptr) {
    throw std::runtime_error("the Verilated RTL is not part of this build (configure with the RTL sources)");
  }
  return *rtl_tb_;
}

void rt_isect_top::open_wave([[maybe_unused]] const std::string& path) {
#if LANCER_SC_HAVE_RTL && LANCER_SC_RTL_FST
  close_wave();
  auto w = std::make_unique<wave>();
  w->fst = std::make_unique<VerilatedFstSc>();  // registers itself with the kernel
  static_cast<rt_isect_bench<Vrt_isect_sc>*>(rtl_.get())->u_dut.trace(w->fst.get(), 99);
  w->fst->open(path.c_str());
  if (!w->fst->isOpen()) {
    sc_core::sc_get_curr_simcontext()->remove_trace_file(w->kernelHandle());
    throw std::runtime_error("cannot open waveform file " + path);
  }
  wave_ = std::move(w);
#else
  throw std::runtime_error("the Verilated RTL of this build has no FST tracing");
#endif
}

void rt_isect_top::close_wave() {
#if LANCER_SC_HAVE_RTL && LANCER_SC_RTL_FST
  if (!wave_) return;
  wave_->fst->close();
  sc_core::sc_get_curr_simcontext()->remove_trace_file(wave_->kernelHandle());
  wave_.reset();
#endif
}

}  // namespace lancer::sc
