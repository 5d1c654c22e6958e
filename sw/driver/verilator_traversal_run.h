#pragma once

// The members of VerilatorTraversalDevice<Top, Image>. Included by the .cpp of
// each unit's device only, after the Verilated header, followed by
// LANCER_VERILATED_TRAVERSAL_UNIT (below), which writes the specialization
// TraversalTop<Top> (traversal_run.h lists its members), the device's
// explicit instantiation and its factory. The run loop is traversal_run.h's,
// over VerilatedUnit<Top>.

#include <memory>
#include <span>
#include <tuple>
#include <vector>

#include "driver/traversal_run.h"
#include "driver/verilated_unit.h"
#include "driver/verilator_traversal_device.h"

namespace lancer {

template <class Top, class Image>
VerilatorTraversalDevice<Top, Image>::VerilatorTraversalDevice() {
  units_.push_back(std::make_unique<VerilatedUnit<Top>>(TraversalTop<Top>::Desc::kNames.module));
  units_.front()->reset(trav_detail::idleInputs<Top>);
}

template <class Top, class Image>
VerilatorTraversalDevice<Top, Image>::~VerilatorTraversalDevice() = default;

template <class Top, class Image>
int VerilatorTraversalDevice<Top, Image>::maxRaysInFlight() const {
  return TraversalTop<Top>::kMaxSlots;
}

template <class Top, class Image>
TraversalRunStats VerilatorTraversalDevice<Top, Image>::run(const Image& image, std::span<const fx::QRay> rays,
                                                            std::vector<fx::TraversalTrace>& traces,
                                                            const TraversalRunOptions& options) {
  using Desc = typename TraversalTop<Top>::Desc;
  checkTraversalOptions(options, name(), maxRaysInFlight(), Desc::kNames.unit, Desc::kNames.slotsOption);
  return runTraversalChip(
      units_, [] { return std::make_unique<VerilatedUnit<Top>>(Desc::kNames.module); }, image, rays, traces, options,
      portTrace_);
}

}  // namespace lancer

// A unit's Verilated device, in its verilator_<unit>_device.cpp: the traits of
// the Verilated model `Top` for the descriptor `Descriptor` (its configuration
// port is `CfgPort`, it has `Slots` ray slots), the device's explicit
// instantiation and its factory.
#define LANCER_VERILATED_TRAVERSAL_UNIT(Top, Descriptor, Slots, CfgPort)                                 \
  namespace lancer {                                                                                             \
  template <>                                                                                                    \
  struct TraversalTop<Top> {                                                                                     \
    using Desc = Descriptor;                                                                                     \
    static constexpr int kMaxSlots = Slots;                                                                      \
    static auto nodePort(Top& t) {                                                                               \
      return std::tie(t.node_req_valid_o, t.node_req_addr_o, t.node_req_tag_o, t.node_req_ready_i,              \
                      t.node_rsp_valid_i, t.node_rsp_data_i, t.node_rsp_tag_i);                                  \
    }                                                                                                            \
    static auto& configPort(Top& t) { return t.CfgPort; }                                                        \
  };                                                                                                             \
  template class VerilatorTraversalDevice<Top, Descriptor::Image>;                                               \
  template <>                                                                                                    \
  std::unique_ptr<DeviceOf<Descriptor>> makeVerilatorDevice<Descriptor>() {                                      \
    return std::make_unique<VerilatorTraversalDevice<Top, Descriptor::Image>>();                                 \
  }                                                                                                              \
  }  // namespace lancer
