// rt_grid: the integer-DDA uniform-grid traversal unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseGrid (sw/golden/grid.h): for every ray the same
// cells in the same order, every triangle of every visited cell tested (index
// list order, duplicates across cells included), the closest hit by
// fx::closerResult, and the same stop rule (stop once the closest hit so far
// lies within the current cell, or when the ray leaves the grid).
// docs/grid-unit.md specifies the micro-architecture cycle by cycle.
//
//   ray_*      rays in (valid/ready); accepted while a usable slot is free
//   u_setup    per-ray setup, multiplications only (2 stages)
//   g_slot     RaysInFlight slots (rt_grid_slot): DDA state, FSM, closest hit
//   cell port  one cell-table read per visited cell (round robin over slots)
//   idx port   one index-list read per test (round robin over slots), credit-
//              limited by the index buffer (IdxBufDepth)
//   tri port   one triangle read per index response, in index-response order
//   u_isect    rt_isect; a triangle response enters it in the cycle it arrives
//   closest    one isect result per cycle updates its slot's closest hit
//   check      one exit test per cycle (round robin over slots with a hit)
//   visit_*    one record per cell entered; res_* one record per ray
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based: index responses land in the index buffer, which is never
// overfilled; cell and triangle responses are consumed in their cycle).
// Responses per port must come in request order; the tag is the slot.
//
// Latency:    >= 3 (setup) + per cell: 1 + cell read + (reads + ISECT_LATENCY
//             if the cell holds triangles) + 1 (check) cycles per ray.
// Throughput: per cycle at most one ray accepted, one cell read, one index
//             read, one triangle read, one intersection test, one exit test,
//             one visit record and one result.
module rt_grid #(
  parameter int unsigned RaysInFlight = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth  = 64,  // index responses buffered (credits)
  parameter int unsigned SlotW = (RaysInFlight > 1) ? $clog2(RaysInFlight) : 1,  // derived
  parameter int unsigned CfgSlotsW = $clog2(RaysInFlight + 1)                     // derived
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,

  // Configuration, static while rays are in flight.
  input  logic [3*rt_pkg::GRID_RESOLUTION_W-1:0] cfg_res_i,    // {Rz, Ry, Rx}, each 1..256
  input  logic [CfgSlotsW-1:0]                   cfg_slots_i,  // slots to use, 1..RaysInFlight

  // Rays in.
  input  logic                                   ray_valid_i,
  output logic                                   ray_ready_o,
  input  rt_pkg::isect_ray_t                     ray_data_i,

  // One result per ray, in any order.
  output logic                                   res_valid_o,
  input  logic                                   res_ready_i,
  output rt_pkg::grid_res_t                      res_data_o,

  // One record per cell entered, in visiting order per ray.
  output logic                                   visit_valid_o,
  input  logic                                   visit_ready_i,
  output rt_pkg::grid_visit_t                    visit_data_o,

  // Cell table reads.
  output logic                                   cell_req_valid_o,
  input  logic                                   cell_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          cell_req_addr_o,
  output logic [SlotW-1:0]                       cell_req_tag_o,
  input  logic                                   cell_rsp_valid_i,
  input  rt_pkg::grid_cell_t                     cell_rsp_data_i,
  input  logic [SlotW-1:0]                       cell_rsp_tag_i,

  // Index list reads.
  output logic                                   idx_req_valid_o,
  input  logic                                   idx_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          idx_req_addr_o,
  output logic [SlotW-1:0]                       idx_req_tag_o,
  input  logic                                   idx_rsp_valid_i,
  input  logic [31:0]                            idx_rsp_data_i,
  input  logic [SlotW-1:0]                       idx_rsp_tag_i,

  // Triangle table reads.
  output logic                                   tri_req_valid_o,
  input  logic                                   tri_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          tri_req_addr_o,
  output logic [SlotW-1:0]                       tri_req_tag_o,
  input  logic                                   tri_rsp_valid_i,
  input  rt_pkg::isect_tri_t                     tri_rsp_data_i,
  input  logic [SlotW-1:0]                       tri_rsp_tag_i,

  // Performance: a ray-triangle pair enters rt_isect this cycle.
  output logic                                   perf_isect_fire_o
);

  localparam int N     = RaysInFlight;
  localparam int RES_W    = rt_pkg::GRID_RESOLUTION_W;
  localparam int CELL_W   = rt_pkg::CELL_INDEX_W;
  localparam int ID_W     = 3 * CELL_W;
  localparam int ADDR_W   = rt_pkg::MEM_ADDR_W;
  localparam int ACC_W    = rt_pkg::GRID_ACC_W;
  localparam int PAIR_W   = rt_pkg::GRID_PAIR_W;
  localparam int TRIPLE_W = rt_pkg::GRID_TRIPLE_W;
  localparam int DIR_W    = rt_pkg::DIR_W;
  localparam int T_NUM_W  = rt_pkg::T_NUM_W;
  localparam int DET_W    = rt_pkg::DET_ABS_W;
  localparam int RAY_W    = rt_pkg::ISECT_RAY_W;
  localparam int RES_REC_W = rt_pkg::ISECT_RES_W;
  localparam int MEMREQ_W = ADDR_W + SlotW;
  localparam int IDXBUF_W = 32 + SlotW;
  localparam int CREDIT_W = $clog2(IdxBufDepth + 1);
  // Exit test: exit_acc * dominant * det  vs  t_num * triple.
  localparam int LHS_W    = ACC_W + DIR_W + DET_W;
  localparam int RHS_W    = T_NUM_W + TRIPLE_W;
  localparam int CHK_W    = (LHS_W > RHS_W) ? LHS_W : RHS_W;
  // Closest hit: t_num * det of the other.
  localparam int CLO_W    = T_NUM_W + DET_W;

  // ---- Configuration: strides of the cell id ----------------------------------
  logic [ID_W-1:0] stride_x, stride_y, stride_z;
  assign stride_x = ID_W'(1);
  assign stride_y = ID_W'(cfg_res_i[0 +: RES_W]);
  assign stride_z = ID_W'(cfg_res_i[0 +: RES_W]) * ID_W'(cfg_res_i[RES_W +: RES_W]);

  // ---- Per-slot signals, flattened by slot -------------------------------------
  logic [N-1:0]          free, usable, want_visit, want_idx, want_check, want_done;
  logic [N-1:0]          fetching, waiting_cell, has_hit;
  logic [N-1:0]          alloc, init, visit_gnt, cell_rsp, idx_gnt, res_hit_slot, check_gnt, done_gnt;
  logic [N*RAY_W-1:0]    slot_ray;
  logic [N*32-1:0]       slot_ray_id;
  logic [N*ID_W-1:0]     slot_cell_id;
  logic [N*32-1:0]       slot_idx_addr, slot_cells, slot_tests;
  logic [N*ACC_W-1:0]    slot_exit_acc;
  logic [N*TRIPLE_W-1:0] slot_triple;
  logic [N*DIR_W-1:0]    slot_dom;
  logic [N*RES_REC_W-1:0] slot_best;

  // ---- Ray input and slot allocation --------------------------------------------
  // The lowest free usable slot takes the ray; ray_ready_o depends on slot state only.
  logic [SlotW-1:0] alloc_idx;
  logic             ray_fire;

  always_comb begin
    for (int s = 0; s < N; s++) begin
      usable[s] = (CfgSlotsW'(s) < cfg_slots_i);
    end
  end

  always_comb begin
    alloc_idx = '0;
    for (int s = N - 1; s >= 0; s--) begin
      if (free[s] && usable[s]) alloc_idx = SlotW'(s);
    end
  end

  assign ray_ready_o = |(free & usable);
  assign ray_fire    = ray_valid_i && ray_ready_o;

  always_comb begin
    alloc = '0;
    alloc[alloc_idx] = ray_fire;
  end

  // ---- Setup ---------------------------------------------------------------------
  logic                 su_valid;
  logic [SlotW-1:0]     su_slot;
  rt_pkg::isect_ray_t   su_ray;
  logic [3*CELL_W-1:0]  su_cell, su_cell_id;
  logic [2:0]           su_active, su_neg;
  logic [3*ACC_W-1:0]   su_acc;
  logic [3*PAIR_W-1:0]  su_pair;
  logic [TRIPLE_W-1:0]  su_triple;
  logic [DIR_W-1:0]     su_dom;

  rt_grid_setup #(.SlotW(SlotW)) u_setup (
    .clk_i,
    .rst_ni,
    .cfg_res_i,
    .valid_i   (ray_fire),
    .slot_i    (alloc_idx),
    .ray_i     (ray_data_i),
    .valid_o   (su_valid),
    .slot_o    (su_slot),
    .ray_o     (su_ray),
    .cell_o    (su_cell),
    .cell_id_o (su_cell_id),
    .active_o  (su_active),
    .neg_o     (su_neg),
    .acc_o     (su_acc),
    .pair_o    (su_pair),
    .triple_o  (su_triple),
    .dom_o     (su_dom)
  );

  always_comb begin
    init = '0;
    init[su_slot] = su_valid;
  end

  // ---- Arbiters -------------------------------------------------------------------
  logic             visit_any, idx_any, check_any, done_any;
  logic [SlotW-1:0] visit_idx, idx_idx, check_idx, done_idx;
  logic [N-1:0]     visit_oh, idx_oh, check_oh, done_oh;
  logic             visit_go, idx_go, done_go;
  logic             cellq_ready, visitq_ready, idxq_ready, resq_ready;
  logic [CREDIT_W-1:0] credit_q;
  logic             idxbuf_pop;

  rt_rr_arb #(.N(N)) u_visit_arb (
    .clk_i, .rst_ni, .req_i(want_visit), .ack_i(visit_go),
    .valid_o(visit_any), .gnt_o(visit_oh), .idx_o(visit_idx));
  rt_rr_arb #(.N(N)) u_idx_arb (
    .clk_i, .rst_ni, .req_i(want_idx), .ack_i(idx_go),
    .valid_o(idx_any), .gnt_o(idx_oh), .idx_o(idx_idx));
  rt_rr_arb #(.N(N)) u_check_arb (
    .clk_i, .rst_ni, .req_i(want_check), .ack_i(check_any),
    .valid_o(check_any), .gnt_o(check_oh), .idx_o(check_idx));
  rt_rr_arb #(.N(N)) u_done_arb (
    .clk_i, .rst_ni, .req_i(want_done), .ack_i(done_go),
    .valid_o(done_any), .gnt_o(done_oh), .idx_o(done_idx));

  // A visit needs room for both the cell read and the visit record.
  assign visit_go  = visit_any && cellq_ready && visitq_ready;
  assign visit_gnt = visit_go ? visit_oh : '0;
  // An index read needs a credit: a place in the index buffer for its response.
  assign idx_go    = idx_any && idxq_ready && (credit_q != '0);
  assign idx_gnt   = idx_go ? idx_oh : '0;
  assign check_gnt = check_oh;
  assign done_go   = done_any && resq_ready;
  assign done_gnt  = done_go ? done_oh : '0;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      credit_q <= CREDIT_W'(IdxBufDepth);
    end else if (idx_go && !idxbuf_pop) begin
      credit_q <= credit_q - 1'b1;
    end else if (idxbuf_pop && !idx_go) begin
      credit_q <= credit_q + 1'b1;
    end
  end

  // ---- Cell reads and visit records -------------------------------------------------
  logic [ID_W-1:0] visit_cell_id;
  rt_pkg::grid_visit_t visit_rec;
  assign visit_cell_id = slot_cell_id[visit_idx*ID_W +: ID_W];
  // Addresses as wires of their own: Yosys 0.23 drops a size cast inside a concatenation.
  logic [ADDR_W-1:0] cell_addr, idx_addr, tri_addr;
  assign cell_addr = ADDR_W'(visit_cell_id);
  assign idx_addr  = ADDR_W'(slot_idx_addr[idx_idx*32 +: 32]);
  assign visit_rec.ray_id  = slot_ray_id[visit_idx*32 +: 32];
  assign visit_rec.cell_id = visit_cell_id;

  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_cell_q (
    .clk_i, .rst_ni,
    .in_valid_i (visit_go),
    .in_ready_o (cellq_ready),
    .in_data_i  ({cell_addr, visit_idx}),
    .out_valid_o(cell_req_valid_o),
    .out_ready_i(cell_req_ready_i),
    .out_data_o ({cell_req_addr_o, cell_req_tag_o})
  );

  rt_fifo #(.Width(rt_pkg::GRID_VISIT_W), .Depth(4)) u_visit_q (
    .clk_i, .rst_ni,
    .in_valid_i (visit_go),
    .in_ready_o (visitq_ready),
    .in_data_i  (visit_rec),
    .out_valid_o(visit_valid_o),
    .out_ready_i(visit_ready_i),
    .out_data_o (visit_data_o)
  );

  always_comb begin
    cell_rsp = '0;
    cell_rsp[cell_rsp_tag_i] = cell_rsp_valid_i;
  end

  // ---- Index reads, index buffer, triangle reads -------------------------------------
  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_idx_q (
    .clk_i, .rst_ni,
    .in_valid_i (idx_go),
    .in_ready_o (idxq_ready),
    .in_data_i  ({idx_addr, idx_idx}),
    .out_valid_o(idx_req_valid_o),
    .out_ready_i(idx_req_ready_i),
    .out_data_o ({idx_req_addr_o, idx_req_tag_o})
  );

  logic                 idxbuf_valid, idxbuf_ready, triq_ready;
  logic [IDXBUF_W-1:0]  idxbuf_data;

  rt_fifo #(.Width(IDXBUF_W), .Depth(IdxBufDepth)) u_idx_buf (
    .clk_i, .rst_ni,
    .in_valid_i (idx_rsp_valid_i),
    .in_ready_o (idxbuf_ready),
    .in_data_i  ({idx_rsp_data_i, idx_rsp_tag_i}),
    .out_valid_o(idxbuf_valid),
    .out_ready_i(triq_ready),
    .out_data_o (idxbuf_data)
  );
  assign idxbuf_pop = idxbuf_valid && triq_ready;
  assign tri_addr   = ADDR_W'(idxbuf_data[IDXBUF_W-1 -: 32]);

  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_tri_q (
    .clk_i, .rst_ni,
    .in_valid_i (idxbuf_valid),
    .in_ready_o (triq_ready),
    .in_data_i  ({tri_addr, idxbuf_data[SlotW-1:0]}),
    .out_valid_o(tri_req_valid_o),
    .out_ready_i(tri_req_ready_i),
    .out_data_o ({tri_req_addr_o, tri_req_tag_o})
  );

  // ---- Intersection: the triangle response and its slot's ray --------------------------
  // The slot index travels in the ray id field through rt_isect; the real ray
  // id stays in the slot. rt_isect's results are always taken (res_ready_i = 1),
  // so its req_ready_o is always 1 and a triangle response enters at once.
  rt_pkg::isect_ray_t isect_ray, tri_ray;
  logic               isect_req_ready, isect_res_valid;
  rt_pkg::isect_res_t isect_res;

  assign tri_ray = slot_ray[tri_rsp_tag_i*RAY_W +: RAY_W];
  always_comb begin
    isect_ray        = tri_ray;
    isect_ray.ray_id = 32'(tri_rsp_tag_i);
  end

  rt_isect u_isect (
    .clk_i,
    .rst_ni,
    .req_valid_i (tri_rsp_valid_i),
    .req_ready_o (isect_req_ready),
    .req_ray_i   (isect_ray),
    .req_tri_i   (tri_rsp_data_i),
    .res_valid_o (isect_res_valid),
    .res_ready_i (1'b1),
    .res_data_o  (isect_res)
  );
  assign perf_isect_fire_o = tri_rsp_valid_i && isect_req_ready;

  // ---- Closest hit: one result per cycle against its slot's best --------------------
  // closerResult: t1 < t2 as t_num1 * det2 < t_num2 * det1, ties to the lower prim id.
  logic [SlotW-1:0]   res_slot;
  rt_pkg::isect_res_t res_best, res_for_slot;
  logic               res_best_valid, res_take;
  logic [CLO_W-1:0]   clo_new, clo_old;

  assign res_slot       = isect_res.ray_id[SlotW-1:0];
  assign res_best       = slot_best[res_slot*RES_REC_W +: RES_REC_W];
  assign res_best_valid = has_hit[res_slot];
  assign clo_new        = CLO_W'(isect_res.t_num) * CLO_W'(res_best.det);
  assign clo_old        = CLO_W'(res_best.t_num) * CLO_W'(isect_res.det);
  assign res_take       = isect_res.hit && (!res_best_valid || clo_new < clo_old ||
                          (clo_new == clo_old && isect_res.prim_id < res_best.prim_id));
  always_comb begin
    res_hit_slot = '0;
    res_hit_slot[res_slot] = isect_res_valid;
    res_for_slot = isect_res;
  end

  // ---- Exit test: does the closest hit lie within the cell? ------------------------
  // fx::GridDda::holds: !(N_exit * dominant * det < t_num * triple).
  rt_pkg::isect_res_t chk_best;
  logic [CHK_W-1:0]   chk_lhs, chk_rhs;
  logic               check_holds;
  assign chk_best    = slot_best[check_idx*RES_REC_W +: RES_REC_W];
  assign chk_lhs     = CHK_W'(slot_exit_acc[check_idx*ACC_W +: ACC_W]) *
                       CHK_W'(slot_dom[check_idx*DIR_W +: DIR_W]) * CHK_W'(chk_best.det);
  assign chk_rhs     = CHK_W'(chk_best.t_num) * CHK_W'(slot_triple[check_idx*TRIPLE_W +: TRIPLE_W]);
  assign check_holds = !(chk_lhs < chk_rhs);

  // ---- Slots -------------------------------------------------------------------------
  for (genvar s = 0; s < N; s++) begin : g_slot
    rt_grid_slot u_slot (
      .clk_i,
      .rst_ni,
      .cfg_res_i,
      .stride_x_i     (stride_x),
      .stride_y_i     (stride_y),
      .stride_z_i     (stride_z),
      .alloc_i        (alloc[s]),
      .init_i         (init[s]),
      .init_ray_i     (su_ray),
      .init_cell_i    (su_cell),
      .init_cell_id_i (su_cell_id),
      .init_active_i  (su_active),
      .init_neg_i     (su_neg),
      .init_acc_i     (su_acc),
      .init_pair_i    (su_pair),
      .init_triple_i  (su_triple),
      .init_dom_i     (su_dom),
      .visit_gnt_i    (visit_gnt[s]),
      .cell_rsp_i     (cell_rsp[s]),
      .cell_rsp_data_i(cell_rsp_data_i),
      .idx_gnt_i      (idx_gnt[s]),
      .res_i          (res_hit_slot[s]),
      .res_take_i     (res_take),
      .res_data_i     (res_for_slot),
      .check_gnt_i    (check_gnt[s]),
      .check_holds_i  (check_holds),
      .done_gnt_i     (done_gnt[s]),
      .free_o         (free[s]),
      .want_visit_o   (want_visit[s]),
      .want_idx_o     (want_idx[s]),
      .want_check_o   (want_check[s]),
      .want_done_o    (want_done[s]),
      .fetching_o     (fetching[s]),
      .waiting_cell_o (waiting_cell[s]),
      .ray_o          (slot_ray[s*RAY_W +: RAY_W]),
      .cell_id_o      (slot_cell_id[s*ID_W +: ID_W]),
      .idx_addr_o     (slot_idx_addr[s*32 +: 32]),
      .exit_acc_o     (slot_exit_acc[s*ACC_W +: ACC_W]),
      .triple_o       (slot_triple[s*TRIPLE_W +: TRIPLE_W]),
      .dom_o          (slot_dom[s*DIR_W +: DIR_W]),
      .has_hit_o      (has_hit[s]),
      .best_o         (slot_best[s*RES_REC_W +: RES_REC_W]),
      .cells_o        (slot_cells[s*32 +: 32]),
      .tests_o        (slot_tests[s*32 +: 32])
    );
    // ray_id is the most significant field of isect_ray_t.
    assign slot_ray_id[s*32 +: 32] = slot_ray[s*RAY_W + RAY_W - 32 +: 32];
  end

  // ---- Results -------------------------------------------------------------------------
  rt_pkg::grid_res_t  done_rec;
  rt_pkg::isect_res_t done_best;
  assign done_best = slot_best[done_idx*RES_REC_W +: RES_REC_W];
  always_comb begin
    done_rec.ray_id  = slot_ray_id[done_idx*32 +: 32];
    done_rec.cells   = slot_cells[done_idx*32 +: 32];
    done_rec.tests   = slot_tests[done_idx*32 +: 32];
    done_rec.hit     = has_hit[done_idx];
    done_rec.prim_id = done_best.prim_id;
    done_rec.t_num   = done_best.t_num;
    done_rec.det     = done_best.det;
    done_rec.u_num   = done_best.u_num;
    done_rec.v_num   = done_best.v_num;
  end

  rt_fifo #(.Width(rt_pkg::GRID_RESULT_W), .Depth(2)) u_res_q (
    .clk_i, .rst_ni,
    .in_valid_i (done_go),
    .in_ready_o (resq_ready),
    .in_data_i  (done_rec),
    .out_valid_o(res_valid_o),
    .out_ready_i(res_ready_i),
    .out_data_o (res_data_o)
  );

`ifdef RT_ASSERT_ON
  // Output streams: valid never drops and data holds until taken.
  a_res_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      res_valid_o && !res_ready_i |=> res_valid_o && $stable(res_data_o));
  a_visit_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      visit_valid_o && !visit_ready_i |=> visit_valid_o && $stable(visit_data_o));
  a_cell_req_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      cell_req_valid_o && !cell_req_ready_i |=> cell_req_valid_o && $stable({cell_req_addr_o, cell_req_tag_o}));
  a_idx_req_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      idx_req_valid_o && !idx_req_ready_i |=> idx_req_valid_o && $stable({idx_req_addr_o, idx_req_tag_o}));
  a_tri_req_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_req_valid_o && !tri_req_ready_i |=> tri_req_valid_o && $stable({tri_req_addr_o, tri_req_tag_o}));
  // Input stream (the producer's duty).
  a_ray_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      ray_valid_i && !ray_ready_o |=> ray_valid_i && $stable(ray_data_i));
  // Responses: credits guarantee room, tags name a slot that waits for them.
  a_idx_buf_room : assert property (@(posedge clk_i) disable iff (!rst_ni)
      idx_rsp_valid_i |-> idxbuf_ready);
  a_isect_ready : assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_rsp_valid_i |-> isect_req_ready);
  a_cell_rsp_slot : assert property (@(posedge clk_i) disable iff (!rst_ni)
      cell_rsp_valid_i |-> waiting_cell[cell_rsp_tag_i]);
  a_tri_rsp_slot : assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_rsp_valid_i |-> fetching[tri_rsp_tag_i]);
  a_cfg_slots : assert property (@(posedge clk_i) disable iff (!rst_ni)
      cfg_slots_i != '0 && cfg_slots_i <= CfgSlotsW'(N));
  a_credit_range : assert property (@(posedge clk_i) disable iff (!rst_ni)
      credit_q <= CREDIT_W'(IdxBufDepth));
  if (N > 256) begin : g_slots_check
    $error("rt_grid: RaysInFlight must lie in 1..256 (the setup carries an 8-bit slot)");
  end
`endif

endmodule
