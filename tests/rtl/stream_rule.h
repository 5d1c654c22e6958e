#pragma once

// The stream-assertion tests' common step (coverage_cases_test.cpp for the
// traversal units' ray input, verilated_context_test.cpp for rt_isect's
// request): a producer that offers, is refused, then withdraws its offer.

#include <stdexcept>
#include <string>

#include "driver/verilated_unit.h"

namespace lancer::rtltest {

// Runs offer() (it drives `unit` until an offer stands refused, and returns ""
// or why it could not), then withdraws the offer untaken (withdraw(top)) and
// clocks two more cycles: the hold assertion fires on the edge after the
// withdrawal. Returns what the unit threw ("" if nothing), or offer()'s reason.
template <class Top, class Offer, class Withdraw>
std::string withdrawRefused(VerilatedUnit<Top>& unit, Offer offer, Withdraw withdraw) {
  try {
    if (const std::string why = offer(); !why.empty()) return why;
    withdraw(unit.top());
    unit.step(2);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace lancer::rtltest
