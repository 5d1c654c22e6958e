#include "base/rt_fst_wave.h"

#include <stdexcept>

#include <systemc>

#if LANCER_SC_RTL_FST
#include "verilated_fst_sc.h"
#endif

namespace lancer::sc {

namespace {

#if LANCER_SC_RTL_FST
// VerilatedFstSc derives from sc_trace_file privately: the C-style cast is the
// one conversion that may name a private base.
sc_core::sc_trace_file* kernelHandle(VerilatedFstSc* fst) { return (sc_core::sc_trace_file*)fst; }
#endif

}  // namespace

struct rt_fst_wave::state {
#if LANCER_SC_RTL_FST
  std::unique_ptr<VerilatedFstSc> fst;
#endif
};

rt_fst_wave::rt_fst_wave() : state_(std::make_unique<state>()) {}

rt_fst_wave::~rt_fst_wave() { close(); }

bool rt_fst_wave::available() { return LANCER_SC_RTL_FST != 0; }

void rt_fst_wave::open([[maybe_unused]] const std::string& path,
                       [[maybe_unused]] const std::function<void(VerilatedFstSc*)>& attach) {
#if LANCER_SC_RTL_FST
  close();
  // Verilator traces a model only once elaboration is complete (else it
  // aborts the process): a waveform asked for before the process's first
  // run completes it here, at time zero, with every clock at rest.
  if (sc_core::sc_get_status() == sc_core::SC_ELABORATION) sc_core::sc_start(sc_core::SC_ZERO_TIME);
  auto fst = std::make_unique<VerilatedFstSc>();  // registers itself with the kernel
  attach(fst.get());
  fst->open(path.c_str());
  if (!fst->isOpen()) {
    sc_core::sc_get_curr_simcontext()->remove_trace_file(kernelHandle(fst.get()));
    throw std::runtime_error("cannot open waveform file " + path);
  }
  state_->fst = std::move(fst);
#else
  throw std::runtime_error("the Verilated RTL of this build has no FST tracing");
#endif
}

void rt_fst_wave::close() {
#if LANCER_SC_RTL_FST
  if (!state_->fst) return;
  state_->fst->close();
  sc_core::sc_get_curr_simcontext()->remove_trace_file(kernelHandle(state_->fst.get()));
  state_->fst.reset();
#endif
}

}  // namespace lancer::sc
