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
//   u_slots    RaysInFlight ray slots (rt_grid_slots): state machines, DDA
//              frontiers, cell queues, counters, closest hits, exit tests
//   cell port  cell-table reads, prefetched: each slot reads up to CellQueue
//              cells ahead of the one it is in (round robin over slots); the
//              DDA steps at the grant, one step per cycle
//   visit_*    one record per cell entered (round robin over slots whose next
//              cell has been requested); res_* one record per ray
//   idx port   one index-list read per test (round robin over slots), credit-
//              limited by the index buffer (IdxBufDepth)
//   tri port   one triangle read per index response, in index-response order
//   u_isect    rt_isect; a triangle response enters it in the cycle after it arrives
//   closest    one isect result per cycle updates its slot's closest hit
//   check      one exit test per cycle (round robin over slots with a hit)
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based: index responses land in the index buffer, which is never
// overfilled; cell and triangle responses are registered at the boundary and
// consumed in the next cycle). Responses per port must come in request order;
// the tag is the slot. A cell read past the cell where a ray stops (a
// prefetch) is read and dropped.
//
// Latency:    >= 3 (setup) + per cell: cell read (hidden by the prefetch once
//             the ray is under way) + (index and triangle reads + ISECT_LATENCY
//             if the cell holds triangles) + 1 (visit) cycles per ray.
// Throughput: per cycle at most one ray accepted, one cell read (one DDA
//             step), one visit record, one index read, one triangle read, one
//             intersection test, one exit test and one result.
module rt_grid #(
  parameter int unsigned RaysInFlight = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth  = 64,  // index responses buffered (credits)
  parameter int unsigned CellQueue    = 2,   // cells per slot read and not finished (power of 2, >= 2)
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

  // Performance: a ray-triangle pair enters rt_isect this cycle; some slot
  // can enter a cell this cycle (in VISIT, its next cell read issued).
  output logic                                   perf_isect_fire_o,
  output logic                                   perf_step_ready_o
);

  localparam int N         = RaysInFlight;
  localparam int ADDR_W    = rt_pkg::MEM_ADDR_W;
  localparam int CELL_W    = rt_pkg::CELL_INDEX_W;
  localparam int ID_W      = 3 * CELL_W;
  localparam int ACC_W     = rt_pkg::GRID_ACC_W;
  localparam int PAIR_W    = rt_pkg::GRID_PAIR_W;
  localparam int TRIPLE_W  = rt_pkg::GRID_TRIPLE_W;
  localparam int DIR_W     = rt_pkg::DIR_W;
  localparam int MEMREQ_W  = ADDR_W + SlotW;
  localparam int IDXBUF_W  = 32 + SlotW;
  localparam int CREDIT_W  = $clog2(IdxBufDepth + 1);
  localparam int NP1       = RaysInFlight + 1;

  // ---- Ray input and slot allocation --------------------------------------------
  // The lowest free usable slot takes the ray (a fixed-priority arbiter: an
  // rt_rr_arb whose pointer never moves); ray_ready_o depends on slot state only.
  logic [N-1:0]     free, usable, unused_alloc_gnt;
  logic [SlotW-1:0] alloc_idx;
  logic             ray_fire;

  assign usable = N'((NP1'(1) << cfg_slots_i) - 1'b1);

  rt_rr_arb #(.N(N)) u_alloc_arb (
    .clk_i, .rst_ni, .req_i(free & usable), .ack_i(1'b0),
    .valid_o(ray_ready_o), .gnt_o(unused_alloc_gnt), .idx_o(alloc_idx));

  assign ray_fire = ray_valid_i && ray_ready_o;

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

  // ---- Arbiters -------------------------------------------------------------------
  logic [N-1:0]     want_cell, want_visit, want_idx, want_check, want_done;
  logic             cell_any, visit_any, idx_any, check_any, done_any;
  logic [SlotW-1:0] cell_idx, visit_idx, idx_idx, check_idx, done_idx;
  // The arbiters' one-hot grants are not needed: the slots take indices.
  logic [N-1:0]     unused_cell_gnt, unused_visit_gnt, unused_idx_gnt, unused_check_gnt, unused_done_gnt;
  logic             cell_go, visit_go, idx_go, done_go;
  logic             cellq_ready, visitq_ready, idxq_ready, resq_ready;
  logic [CREDIT_W-1:0] credit_q;
  logic             idxbuf_pop;

  rt_rr_arb #(.N(N)) u_cell_arb (
    .clk_i, .rst_ni, .req_i(want_cell), .ack_i(cell_go),
    .valid_o(cell_any), .gnt_o(unused_cell_gnt), .idx_o(cell_idx));
  rt_rr_arb #(.N(N)) u_visit_arb (
    .clk_i, .rst_ni, .req_i(want_visit), .ack_i(visit_go),
    .valid_o(visit_any), .gnt_o(unused_visit_gnt), .idx_o(visit_idx));
  rt_rr_arb #(.N(N)) u_idx_arb (
    .clk_i, .rst_ni, .req_i(want_idx), .ack_i(idx_go),
    .valid_o(idx_any), .gnt_o(unused_idx_gnt), .idx_o(idx_idx));
  rt_rr_arb #(.N(N)) u_check_arb (
    .clk_i, .rst_ni, .req_i(want_check), .ack_i(check_any),
    .valid_o(check_any), .gnt_o(unused_check_gnt), .idx_o(check_idx));
  rt_rr_arb #(.N(N)) u_done_arb (
    .clk_i, .rst_ni, .req_i(want_done), .ack_i(done_go),
    .valid_o(done_any), .gnt_o(unused_done_gnt), .idx_o(done_idx));

  // A cell read needs room in the cell request FIFO, a visit room in the visit FIFO.
  assign cell_go  = cell_any && cellq_ready;
  assign visit_go = visit_any && visitq_ready;
  // An index read needs a credit: a place in the index buffer for its response.
  assign idx_go   = idx_any && idxq_ready && (credit_q != '0);
  assign done_go  = done_any && resq_ready;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      credit_q <= CREDIT_W'(IdxBufDepth);
    end else if (idx_go && !idxbuf_pop) begin
      credit_q <= credit_q - 1'b1;
    end else if (idxbuf_pop && !idx_go) begin
      credit_q <= credit_q + 1'b1;
    end
  end

  // ---- Memory responses, registered at the unit's boundary -------------------------
  // A cell or triangle response arriving in cycle c is used in cycle c+1.
  logic                cell_rsp_valid_q, tri_rsp_valid_q;
  logic [SlotW-1:0]    cell_rsp_tag_q, tri_rsp_tag_q;
  rt_pkg::grid_cell_t  cell_rsp_data_q;
  rt_pkg::isect_tri_t  tri_rsp_data_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      cell_rsp_valid_q <= 1'b0;
      tri_rsp_valid_q  <= 1'b0;
    end else begin
      cell_rsp_valid_q <= cell_rsp_valid_i;
      tri_rsp_valid_q  <= tri_rsp_valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (cell_rsp_valid_i) begin
      cell_rsp_tag_q  <= cell_rsp_tag_i;
      cell_rsp_data_q <= cell_rsp_data_i;
    end
    if (tri_rsp_valid_i) begin
      tri_rsp_tag_q  <= tri_rsp_tag_i;
      tri_rsp_data_q <= tri_rsp_data_i;
    end
  end

  // ---- Slots ---------------------------------------------------------------------
  logic [ID_W-1:0]     cell_cell_id, visit_cell_id;
  logic [31:0]         visit_ray_id;
  logic [ADDR_W-1:0]   idx_addr;
  rt_pkg::isect_ray_t  isect_ray;
  logic                isect_req_ready, isect_res_valid;
  rt_pkg::isect_res_t  isect_res;
  rt_pkg::grid_res_t   done_rec;

  rt_grid_slots #(.N(N), .CellQueue(CellQueue), .SlotW(SlotW)) u_slots (
    .clk_i,
    .rst_ni,
    .cfg_res_i,
    .free_o          (free),
    .alloc_i         (ray_fire),
    .alloc_slot_i    (alloc_idx),
    .init_i          (su_valid),
    .init_slot_i     (su_slot),
    .init_ray_i      (su_ray),
    .init_cell_i     (su_cell),
    .init_cell_id_i  (su_cell_id),
    .init_active_i   (su_active),
    .init_neg_i      (su_neg),
    .init_acc_i      (su_acc),
    .init_pair_i     (su_pair),
    .init_triple_i   (su_triple),
    .init_dom_i      (su_dom),
    .want_cell_o     (want_cell),
    .cell_go_i       (cell_go),
    .cell_slot_i     (cell_idx),
    .cell_id_o       (cell_cell_id),
    .cell_rsp_valid_i(cell_rsp_valid_q),
    .cell_rsp_tag_i  (cell_rsp_tag_q),
    .cell_rsp_data_i (cell_rsp_data_q),
    .want_visit_o    (want_visit),
    .visit_go_i      (visit_go),
    .visit_slot_i    (visit_idx),
    .visit_ray_id_o  (visit_ray_id),
    .visit_cell_id_o (visit_cell_id),
    .want_idx_o      (want_idx),
    .idx_go_i        (idx_go),
    .idx_slot_i      (idx_idx),
    .idx_addr_o      (idx_addr),
    .tri_valid_i     (tri_rsp_valid_q),
    .tri_slot_i      (tri_rsp_tag_q),
    .tri_ray_o       (isect_ray),
    .res_valid_i     (isect_res_valid),
    .res_data_i      (isect_res),
    .want_check_o    (want_check),
    .check_go_i      (check_any),
    .check_slot_i    (check_idx),
    .want_done_o     (want_done),
    .done_go_i       (done_go),
    .done_slot_i     (done_idx),
    .done_rec_o      (done_rec),
    .step_ready_o    (perf_step_ready_o)
  );

  // ---- Cell reads and visit records -------------------------------------------------
  // Addresses as wires of their own: Yosys 0.23 drops a size cast inside a concatenation.
  logic [ADDR_W-1:0] cell_addr, tri_addr;
  rt_pkg::grid_visit_t visit_rec;
  assign cell_addr         = ADDR_W'(cell_cell_id);
  assign visit_rec.ray_id  = visit_ray_id;
  assign visit_rec.cell_id = visit_cell_id;

  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_cell_q (
    .clk_i, .rst_ni,
    .in_valid_i (cell_go),
    .in_ready_o (cellq_ready),
    .in_data_i  ({cell_addr, cell_idx}),
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
  // The slot index travels in the ray id field through rt_isect (the slots
  // store each ray with ray_id = slot index); the real ray id stays in the
  // slot. rt_isect's results are always taken (res_ready_i = 1), so its
  // req_ready_o is always 1 and a registered triangle response enters at once.
  rt_isect u_isect (
    .clk_i,
    .rst_ni,
    .req_valid_i (tri_rsp_valid_q),
    .req_ready_o (isect_req_ready),
    .req_ray_i   (isect_ray),
    .req_tri_i   (tri_rsp_data_q),
    .res_valid_o (isect_res_valid),
    .res_ready_i (1'b1),
    .res_data_o  (isect_res)
  );
  assign perf_isect_fire_o = tri_rsp_valid_q && isect_req_ready;

  // ---- Results -------------------------------------------------------------------------
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
  // Output streams (results, visits, the three request ports) come straight
  // from rt_fifo instances, whose a_out_hold checks that valid never drops and
  // data holds until taken; they are not checked twice here.
  // Input stream (the producer's duty).
  a_ray_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      ray_valid_i && !ray_ready_o |=> ray_valid_i && $stable(ray_data_i));
  // Responses: credits guarantee room (rt_grid_slots checks the slots' side).
  a_idx_buf_room : assert property (@(posedge clk_i) disable iff (!rst_ni)
      idx_rsp_valid_i |-> idxbuf_ready);
  a_isect_ready : assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_rsp_valid_q |-> isect_req_ready);
  a_cfg_slots : assert property (@(posedge clk_i) disable iff (!rst_ni)
      cfg_slots_i != '0 && cfg_slots_i <= CfgSlotsW'(N));
  a_credit_range : assert property (@(posedge clk_i) disable iff (!rst_ni)
      credit_q <= CREDIT_W'(IdxBufDepth));
  if (N > 256) begin : g_slots_check
    $error("rt_grid: RaysInFlight must lie in 1..256 (the setup carries an 8-bit slot)");
  end
`endif

endmodule
