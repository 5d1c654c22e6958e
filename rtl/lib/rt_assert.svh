// rt_assert.svh: one-line assertions for rtl/, after lowRISC's prim_assert.
// Each check holds at the rising edge of clk (clk_i unless given) while rst_n
// (rst_ni unless given) is high; its label names it in a simulator's failure
// message.
//
//   `RT_CHECK(a_name, count_q <= FULL)         the condition holds
//   `RT_CHECK_IF(a_name, req_i, ready_o)       when req_i holds, so does ready_o
//   `RT_ASSERT_KNOWN(a_name, valid_o)          the signal is never X or Z
//   `RT_ASSERT(a_name, a |=> $stable(b))       a temporal property
//   `RT_ASSERT_STATIC(g_name, N <= 256, "msg") an elaboration-time check
//
// RT_CHECK and RT_CHECK_IF are immediate assertions in an always_ff: they read
// the values at the edge. RT_ASSERT is a concurrent assertion, for properties
// over more than one cycle only: Verilator keeps a sampled copy of every
// signal a concurrent assertion reads and refreshes it at every evaluation,
// two per cycle, which cost the traversal units 4 % of their host time when
// every check was concurrent.
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

`define RT_CHECK_IF(name, cond, prop, clk = clk_i, rst_n = rst_ni) \
  always_ff @(posedge clk) if ((rst_n) && (cond)) name : assert (prop);

`define RT_CHECK(name, prop, clk = clk_i, rst_n = rst_ni) \
  `RT_CHECK_IF(name, 1'b1, prop, clk, rst_n)

`define RT_ASSERT_KNOWN(name, sig, clk = clk_i, rst_n = rst_ni) \
  `RT_CHECK(name, !$isunknown(sig), clk, rst_n)

// A generate block that fails elaboration with msg when cond does not hold.
`define RT_ASSERT_STATIC(name, cond, msg) \
  if (!(cond)) begin : name $error(msg); end

`else

`define RT_ASSERT(name, prop, clk = clk_i, rst_n = rst_ni)
`define RT_CHECK_IF(name, cond, prop, clk = clk_i, rst_n = rst_ni)
`define RT_CHECK(name, prop, clk = clk_i, rst_n = rst_ni)
`define RT_ASSERT_KNOWN(name, sig, clk = clk_i, rst_n = rst_ni)
`define RT_ASSERT_STATIC(name, cond, msg)

`endif
`endif
