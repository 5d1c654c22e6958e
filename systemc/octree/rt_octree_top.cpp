#include "octree/rt_octree_top.h"

#include <stdexcept>

#include "octree/rt_octree_bench.h"
#include "octree/rt_octree_model.h"

#if LANCER_SC_HAVE_OCTREE_RTL
#include "Vrt_octree_sc.h"
#include "verilated.h"
#if LANCER_SC_RTL_FST
#include "verilated_fst_sc.h"
#endif
#endif

namespace lancer::sc {

struct rt_octree_top::wave {
#if LANCER_SC_HAVE_OCTREE_RTL && LANCER_SC_RTL_FST
  std::unique_ptr<VerilatedFstSc> fst;
  // See rt_isect_top.cpp: VerilatedFstSc derives from sc_trace_file privately.
  sc_core::sc_trace_file* kernelHandle() const { return (sc_core::sc_trace_file*)fst.get(); }
#endif
};

namespace {

template <class Bench>
void keep(std::unique_ptr<Bench> bench, std::unique_ptr<sc_core::sc_module>& owner, rt_octree_tb*& tb,
          rt_octree_mem*& mem) {
  tb = &bench->u_tb;
  mem = &bench->u_mem;
  owner = std::move(bench);
}

}  // namespace

rt_octree_top::rt_octree_top(sc_core::sc_module_name name) : sc_core::sc_module(name) {
  keep(std::make_unique<rt_octree_bench<rt_octree_model>>("u_model"), model_.bench, model_.tb, model_.mem);
#if LANCER_SC_HAVE_OCTREE_RTL
#if LANCER_SC_RTL_FST
  Verilated::traceEverOn(true);  // before the Verilated model is built
#endif
  keep(std::make_unique<rt_octree_bench<Vrt_octree_sc>>("u_rtl"), rtl_.bench, rtl_.tb, rtl_.mem);
#endif
}

rt_octree_top::~rt_octree_top() = default;

bool rt_octree_top::has_rtl() { return LANCER_SC_HAVE_OCTREE_RTL != 0; }

bool rt_octree_top::has_waves() {
#if LANCER_SC_HAVE_OCTREE_RTL && LANCER_SC_RTL_FST
  return true;
#else
  return false;
#endif
}

rt_octree_top::bench_refs& rt_octree_top::refs(rt_octree_impl impl) {
  bench_refs& r = impl == rt_octree_impl::model ? model_ : rtl_;
  if (r.tb == nullptr) {
    throw std::runtime_error("this implementation of rt_octree is not part of the build (no Verilated RTL)");
  }
  return r;
}

rt_octree_tb& rt_octree_top::tb(rt_octree_impl impl) { return *refs(impl).tb; }
rt_octree_mem& rt_octree_top::mem(rt_octree_impl impl) { return *refs(impl).mem; }

void rt_octree_top::open_wave([[maybe_unused]] const std::string& path) {
#if LANCER_SC_HAVE_OCTREE_RTL && LANCER_SC_RTL_FST
  close_wave();
  // Verilator's trace() needs elaboration complete: the first run of the process
  // may ask for a wave. Zero time with every clock at rest changes nothing.
  if (!sc_core::sc_start_of_simulation_invoked()) sc_core::sc_start(sc_core::SC_ZERO_TIME);
  auto w = std::make_unique<wave>();
  w->fst = std::make_unique<VerilatedFstSc>();  // registers itself with the kernel
  static_cast<rt_octree_bench<Vrt_octree_sc>*>(rtl_.bench.get())->u_dut.trace(w->fst.get(), 99);
  w->fst->open(path.c_str());
  if (!w->fst->isOpen()) {
    sc_core::sc_get_curr_simcontext()->remove_trace_file(w->kernelHandle());
    throw std::runtime_error("cannot open waveform file " + path);
  }
  wave_ = std::move(w);
#else
  throw std::runtime_error("the Verilated rt_octree of this build has no FST tracing");
#endif
}

void rt_octree_top::close_wave() {
#if LANCER_SC_HAVE_OCTREE_RTL && LANCER_SC_RTL_FST
  if (!wave_) return;
  wave_->fst->close();
  sc_core::sc_get_curr_simcontext()->remove_trace_file(wave_->kernelHandle());
  wave_.reset();
#endif
}

}  // namespace lancer::sc
