// The slot core every traversal unit's walk shares, in two parts.
//
// Before the module: RT_WALK_UNIT_PARAMS, the parameters every unit has (the
// slots, the index buffer, whether it holds rt_quadric, and the widths they imply), first in its
// parameter list. In the port list, rt_trav_ports.svh gives the clock, the
// reset, the slot count and the streams.
//
// In the body (define RT_WALK_CORE_BODY before the include), once the unit
// has set the figures of its ports toward the shell (VisitIdW, ExitW, DenW,
// RunPorts, WalkPartW: its walk record less the closest hit, 0 if it does not
// set walks aside) and whether the shell registers node responses (RegRsp): the
// walk's nets toward the shell (rt_walk_ports.svh), the shell itself, the
// shell's events as one-hot slot vectors, which each walk's state vectors
// lose and gain, and the checks that every grant of the shell names a slot
// that asked for it. RT_WALK_SETUP_PORTS joins the unit's per-ray setup (the
// ports of rt_setup_ports.svh) to the shell's allocation and init.
`ifndef RT_WALK_CORE_BODY

`ifndef RT_WALK_CORE_SVH
`define RT_WALK_CORE_SVH
`define RT_WALK_UNIT_PARAMS \
  parameter int unsigned RaysInFlight = 32,  /* ray slots, 1..256 */ \
  parameter int unsigned IdxBufDepth  = 64,  /* index responses buffered (credits) */ \
  parameter int unsigned Quadrics     = 0,   /* 1: rt_quadric beside rt_isect (spheres and cones) */ \
  parameter int unsigned SlotW = (RaysInFlight > 1) ? $clog2(RaysInFlight) : 1,  /* derived */ \
  parameter int unsigned CfgSlotsW = $clog2(RaysInFlight + 1)                     /* derived */
// A closest hit as a walk record carries it (also in rt_walk_ports.svh, for the shell).
`ifndef RT_WALK_HIT_W
`define RT_WALK_HIT_W (1 + 32 + rt_pkg::T_NUM_W + rt_pkg::DET_ABS_W + 2 * rt_pkg::BARY_W)
`endif
`define RT_WALK_SETUP_PORTS .clk_i, .rst_ni, .valid_i(alloc), .slot_i(alloc_slot), .ray_i(ray_data_i), \
                            .valid_o(init), .slot_o(init_slot), .ray_o(init_ray), .dom_o(init_dom)
`endif

`else
`undef RT_WALK_CORE_BODY

  localparam int unsigned N = RaysInFlight;
  localparam int unsigned WalkPortW = (WalkPartW > 0) ? WalkPartW : 1;
`include "rt_walk_ports.svh"

  // A unit that does not set walks aside (WalkPartW = 0): no ray resumes, no
  // result is a suspension.
  if (WalkPartW == 0) begin : g_no_suspension
    assign init_resume  = 1'b0;
    assign init_hit     = '0;
    assign done_suspend = 1'b0;
    assign done_walk    = '0;
    logic unused_suspension;
    assign unused_suspension = ^{res_suspend, res_walk};
  end

  // The shell (streams, memory ports, rt_isect and rt_quadric, closest hits, exit tests, the
  // counts) and the walk, joined by name.
  rt_trav_shell #(`RT_WALK_PARAMS, .IdxBufDepth(IdxBufDepth), .RegRsp(RegRsp), .Quadrics(Quadrics)) u_shell (.*);

  function automatic logic [N-1:0] onehot(input logic valid, input logic [SlotW-1:0] s);
    onehot = valid ? (N'(1) << s) : '0;
  endfunction

  // This cycle's events of the shell, bit s for slot s.
  logic [N-1:0] init_oh, visit_oh, node_oh, rsp_oh, check_oh, done_oh;
  assign init_oh  = onehot(init, init_slot);            // the slot's setup is done
  assign visit_oh = onehot(visit_go, visit_slot);       // it enters a region
  assign node_oh  = onehot(node_go, node_slot);         // its node read leaves
  assign rsp_oh   = onehot(node_valid, node_tag);       // a node response comes in
  assign check_oh = onehot(check_go, check_slot);       // its exit test answers
  assign done_oh  = onehot(done_go, done_slot);         // its result leaves: FREE

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Every grant names a slot that asked for it, and results come for slots
  // that expect them.
  `RT_CHECK_IF(a_visit_go, visit_go, want_visit[visit_slot])
  `RT_CHECK_IF(a_node_go, node_go, want_node[node_slot])
  `RT_CHECK_IF(a_check_go, check_go, want_check[check_slot])
  `RT_CHECK_IF(a_done_go, done_go, want_done[done_slot])
  `RT_CHECK_IF(a_res_fetch, isect_valid, fetching[isect_slot])
`endif
`endif
