#pragma once

// One clock cycle at the ports of rt_isect, as the testbench samples it at the
// rising edge that ends the cycle. Free of SystemC types so that the driver and
// the tests can hold traces without including SystemC.

#include <cstdint>
#include <vector>

namespace lancer::sc {

struct IsectCycle {
  uint64_t cycle = 0;       // counted from the first cycle after reset of the run
  bool reqValid = false;    // req_valid_i
  bool reqReady = false;    // req_ready_o
  bool resValid = false;    // res_valid_o
  bool resReady = false;    // res_ready_i
  std::vector<uint32_t> resData;  // res_data_o's wire image while res_valid_o, else empty
  bool operator==(const IsectCycle&) const = default;
};

}  // namespace lancer::sc
