// The ports between rt_trav_shell and a unit's walk (the unit's module, which
// instantiates the shell): one list for the shell's port list and for the
// unit's nets, which `.*` joins to them. Each name is the same at both ends,
// so it carries no _i/_o suffix; RT_TO_SHELL and RT_TO_WALK give its
// direction.
//
// Define RT_WALK_PORTS_OF_SHELL before including it in the shell's port list
// (every entry then ends with a comma: more ports must follow); without it, it
// declares the unit's nets. It undefines what it defines.
// Needs N, SlotW, NodeRspW, VisitIdW, ExitW, DenW, RunPorts and WalkPartW (the
// unit's figures, which RT_WALK_PARAMS passes to the shell by name; WalkPartW
// 0: the unit does not set walks aside) and WalkPortW (WalkPartW, at least 1).
`ifdef RT_WALK_PORTS_OF_SHELL
  `define RT_TO_SHELL input
  `define RT_TO_WALK  output
  `define RT_END      ,
`else
  `define RT_TO_SHELL
  `define RT_TO_WALK
  `define RT_END      ;
`endif
`ifndef RT_WALK_PARAMS
  `define RT_WALK_PARAMS .N(N), .SlotW(SlotW), .NodeRspW(NodeRspW), .VisitIdW(VisitIdW), \
                         .ExitW(ExitW), .DenW(DenW), .RunPorts(RunPorts), .WalkPartW(WalkPartW)
`endif
`ifndef RT_WALK_HIT_W
  // A closest hit as a walk record carries it: {has hit, prim id, t_num, det, u_num, v_num}.
  `define RT_WALK_HIT_W (1 + 32 + rt_pkg::T_NUM_W + rt_pkg::DET_ABS_W + 2 * rt_pkg::BARY_W)
`endif

  // Allocation (the shell's: a ray accepted into a free alloc_slot) and the
  // slot's setup (init: the walk's setup hands the shell the ray, its dominant
  // |d| and the exit test's denominator). A slot is the walk's from init to
  // its done grant.
  `RT_TO_WALK  logic                             alloc                     `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 alloc_slot                `RT_END
  `RT_TO_SHELL logic                             init                      `RT_END
  `RT_TO_SHELL logic [SlotW-1:0]                 init_slot                 `RT_END
  `RT_TO_SHELL rt_pkg::isect_ray_t               init_ray                  `RT_END
  `RT_TO_SHELL logic [rt_pkg::DIR_W-1:0]         init_dom                  `RT_END
  `RT_TO_SHELL logic [DenW-1:0]                  init_den                  `RT_END

  // Node reads (a grid's cells, an octree's child groups, a BVH's nodes) and
  // their responses.
  `RT_TO_SHELL logic [N-1:0]                     want_node                 `RT_END
  `RT_TO_WALK  logic                             node_go                   `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 node_slot                 `RT_END
  `RT_TO_SHELL logic [rt_pkg::MEM_ADDR_W-1:0]    node_addr                 `RT_END  // of node_slot
  `RT_TO_WALK  logic                             node_valid                `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 node_tag                  `RT_END
  `RT_TO_WALK  logic [NodeRspW-1:0]              node_data                 `RT_END

  // Visits: a granted slot enters a region (the shell counts it, and writes
  // its visit record with visit_id).
  `RT_TO_SHELL logic [N-1:0]                     want_visit                `RT_END
  `RT_TO_WALK  logic                             visit_go                  `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 visit_slot                `RT_END
  `RT_TO_SHELL logic [VisitIdW-1:0]              visit_id                  `RT_END  // of visit_slot

  // Index runs (a leaf's or a cell's triangles): port p starts slot
  // run_slot[p]'s run of run_count[p] triangles. The shell counts them as
  // tests, asks for their index reads (one per grant, at idx_addr: the run's
  // first + idx_issued) and counts their results (res_last: the result
  // completes the run).
  `RT_TO_SHELL logic [RunPorts-1:0]              run_start                 `RT_END
  `RT_TO_SHELL logic [RunPorts*SlotW-1:0]        run_slot                  `RT_END
  `RT_TO_SHELL logic [RunPorts*32-1:0]           run_count                 `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 idx_slot                  `RT_END
  `RT_TO_WALK  logic [31:0]                      idx_issued                `RT_END  // of idx_slot: reads before this one
  `RT_TO_SHELL logic [rt_pkg::MEM_ADDR_W-1:0]    idx_addr                  `RT_END  // of idx_slot

  // The intersection results with the closest-hit state.
  `RT_TO_SHELL logic [N-1:0]                     fetching                  `RT_END  // slots that expect triangles (assertions)
  `RT_TO_WALK  logic                             isect_valid               `RT_END  // a result of slot isect_slot
  `RT_TO_WALK  logic [SlotW-1:0]                 isect_slot                `RT_END
  `RT_TO_WALK  logic                             isect_hit                 `RT_END  // it is a hit
  `RT_TO_WALK  logic                             res_last                  `RT_END  // it completes its slot's run
  `RT_TO_WALK  logic [N-1:0]                     bound                     `RT_END  // a closest hit so far, or a segment end

  // Exit tests: granted in cycle t, the exit parameter of check_sel read in
  // t+1, the answer for check_slot in t + EXIT_TEST_LATENCY.
  `RT_TO_SHELL logic [N-1:0]                     want_check                `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 check_sel                 `RT_END
  `RT_TO_SHELL logic [ExitW-1:0]                 check_exit                `RT_END  // of check_sel
  `RT_TO_WALK  logic                             check_go                  `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 check_slot                `RT_END
  `RT_TO_WALK  logic                             check_holds               `RT_END

  // Results: a granted slot's record leaves, and the slot is free again.
  `RT_TO_SHELL logic [N-1:0]                     want_done                 `RT_END
  `RT_TO_WALK  logic                             done_go                   `RT_END
  `RT_TO_WALK  logic [SlotW-1:0]                 done_slot                 `RT_END

  // Walks set aside and resumed (the treelet schedule: a unit with WalkPartW
  // > 0; the others tie these off). A resumed ray's closest hit so far comes
  // with its init; a suspended walk's own part (its record less the closest
  // hit, which the result record carries) goes with done_slot's result, and
  // leaves with it as {the result's hit, the part} (res_walk: 0 unless
  // res_suspend).
  `RT_TO_SHELL logic                             init_resume               `RT_END  // init: the ray resumes a walk
  `RT_TO_SHELL logic [`RT_WALK_HIT_W-1:0]        init_hit                  `RT_END  // its closest hit so far
  `RT_TO_SHELL logic                             done_suspend              `RT_END  // done_slot's walk is set aside:
  `RT_TO_SHELL logic [WalkPortW-1:0]             done_walk                 `RT_END  // its part of the walk record
  `RT_TO_WALK  logic                             res_suspend               `RT_END  // with the result leaving (res_valid_o)
  `RT_TO_WALK  logic [`RT_WALK_HIT_W+WalkPortW-1:0] res_walk               `RT_END

`undef RT_TO_SHELL
`undef RT_TO_WALK
`undef RT_END
`undef RT_WALK_PORTS_OF_SHELL
