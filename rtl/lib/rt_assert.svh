// rt_assert.svh: one-line assertions for rtl/, after lowRISC's prim_assert.
// Each check is a concurrent assertion on the rising edge of clk (clk_i unless
// given), disabled while rst_n (rst_ni unless given) is low; its label names it
// in a simulator's failure message.
//
//   `RT_ASSERT(a_name, req_i |-> ready_o)      the property holds
//   `RT_ASSERT_KNOWN(a_name, valid_o)          the signal is never X or Z
//   `RT_ASSERT_STATIC(g_name, N <= 256, "msg") an elaboration-time check
//
// The checks exist only with RT_ASSERT_ON (Verilator with --assert,
// LANCER_RTL_VERILATOR_ARGS); without it the macros expand to nothing. Files
// include this one inside their `ifdef RT_ASSERT_ON section, so Yosys and
// Icarus, which read the sources without it, need neither the include path
// nor default macro arguments.
`ifndef RT_ASSERT_SVH
`define RT_ASSERT_SVH

`ifdef RT_ASSERT_ON

`define RT_ASSERT(name, prop, clk = clk_i, rst_n = rst_ni) \
  name : assert property (@(posedge clk) disable iff (!(rst_n)) (prop));

`define RT_ASSERT_KNOWN(name, sig, clk = clk_i, rst_n = rst_ni) \
  `RT_ASSERT(name, !$isunknown(sig), clk, rst_n)

// A generate block that fails elaboration with msg when cond does not hold.
`define RT_ASSERT_STATIC(name, cond, msg) \
  if (!(cond)) begin : name $error(msg); end

`else

`define RT_ASSERT(name, prop, clk = clk_i, rst_n = rst_ni)
`define RT_ASSERT_KNOWN(name, sig, clk = clk_i, rst_n = rst_ni)
`define RT_ASSERT_STATIC(name, cond, msg)

`endif
`endif
