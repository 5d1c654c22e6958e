// rt_octree: the octree stepping unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseOctree (sw/golden/octree.h): for every ray the
// same nodes in the same order (Revelles' parametric walk in exact integers),
// every triangle of every visited leaf tested (index-list order), the closest
// hit by fx::closerResult, and the same stop rule (stop once the closest hit
// so far lies within the current leaf, fx::hitWithin, or when the walk leaves
// the root). docs/octree-unit.md, "Micro-architecture of rt_octree", specifies
// it cycle by cycle; the SystemC model (systemc/octree/) implements the same text.
//
//   ray_*      rays in (valid/ready); accepted while a usable slot is free
//   u_setup    per-ray setup, multiplications only (2 stages)
//   u_slots    RaysInFlight slots (rt_octree_slots): walk state, stacks, steps
//   visit_*    one record per node entered (round robin over slots in ENTER)
//   node port  one child-group read per interior node entered, and one per
//              refill of a group lost to a pop (round robin over slots)
//   idx port   one index-list read per test (round robin over slots), credit-
//              limited by the index buffer (IdxBufDepth)
//   tri port   one triangle read per index response, in index-response order
//   u_isect    rt_isect; a triangle response enters it in the cycle it arrives
//   closest    one isect result per cycle updates its slot's closest hit
//   check      one exit test per cycle (round robin over slots with a hit)
//   res_*      one record per ray
//
// The records read by slot index are kept here in arrays (the ray, the closest
// hit, the node and test counters, the setup's dominant and common, the child
// group); rt_octree_slots keeps the walks.
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credit-based: index responses land in the index buffer, which is never
// overfilled; child groups and triangles are consumed in their cycle).
// Responses per port must come in request order; the tag is the slot.
//
// Latency:    >= 3 (setup) + per interior node ENTER, GROUP_REQ, the read,
//             DESCEND (L + 4 cycles at memory latency L); per leaf ENTER,
//             the reads and ISECT_LATENCY if it holds triangles, CHECK.
// Throughput: per cycle at most one ray accepted, one node entered, one child
//             group read, one index read, one triangle read, one intersection
//             test, one closest-hit update, one exit test and one result; any
//             number of DESCEND and advance steps (one per slot).
module rt_octree #(
  parameter int unsigned RaysInFlight = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth  = 64,  // index responses buffered (credits)
  parameter int unsigned SlotW = (RaysInFlight > 1) ? $clog2(RaysInFlight) : 1,  // derived
  parameter int unsigned CfgSlotsW = $clog2(RaysInFlight + 1)                     // derived
) (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,

  // Configuration, static while rays are in flight.
  input  logic [CfgSlotsW-1:0]                   cfg_slots_i,  // slots to use, 1..RaysInFlight
  input  rt_pkg::octree_node_t                   cfg_root_i,   // node 0 (the root's record)

  // Rays in.
  input  logic                                   ray_valid_i,
  output logic                                   ray_ready_o,
  input  rt_pkg::isect_ray_t                     ray_data_i,

  // One result per ray, in any order.
  output logic                                   res_valid_o,
  input  logic                                   res_ready_i,
  output rt_pkg::octree_res_t                    res_data_o,

  // One record per node entered, in visiting order per ray.
  output logic                                   visit_valid_o,
  input  logic                                   visit_ready_i,
  output rt_pkg::octree_visit_t                  visit_data_o,

  // Child-group reads: the eight records first .. first+7, element 0 least significant.
  output logic                                   node_req_valid_o,
  input  logic                                   node_req_ready_i,
  output logic [rt_pkg::MEM_ADDR_W-1:0]          node_req_addr_o,
  output logic [SlotW-1:0]                       node_req_tag_o,
  input  logic                                   node_rsp_valid_i,
  input  rt_pkg::octree_node_t [rt_pkg::OCTREE_CHILDREN-1:0] node_rsp_data_i,
  input  logic [SlotW-1:0]                       node_rsp_tag_i,

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

  // Performance: a ray-triangle pair enters rt_isect this cycle; some slot is
  // in ENTER (the unit has a node step to take).
  output logic                                   perf_isect_fire_o,
  output logic                                   perf_step_ready_o
);

  localparam int N         = RaysInFlight;
  localparam int NP1       = RaysInFlight + 1;
  localparam int P         = rt_pkg::POS_W;
  localparam int ADDR_W    = rt_pkg::MEM_ADDR_W;
  localparam int T_W       = rt_pkg::OCTREE_T_W;
  localparam int COM_W     = rt_pkg::OCTREE_COMMON_W;
  localparam int DIR_W     = rt_pkg::DIR_W;
  localparam int T_NUM_W   = rt_pkg::T_NUM_W;
  localparam int DET_W     = rt_pkg::DET_ABS_W;
  localparam int MEMREQ_W  = ADDR_W + SlotW;
  localparam int IDXBUF_W  = 32 + SlotW;
  localparam int CREDIT_W  = $clog2(IdxBufDepth + 1);
  // Exit test: min(t1) * dominant * det  vs  t_num * common.
  localparam int LHS_W     = T_W + DIR_W + DET_W;
  localparam int RHS_W     = T_NUM_W + COM_W;
  localparam int CHK_W     = (LHS_W > RHS_W) ? LHS_W : RHS_W;
  // Closest hit: t_num * det of the other.
  localparam int CLO_W     = T_NUM_W + DET_W;

  // A child group as stored per slot: octree_node_t [7:0] as plain bits
  // (Yosys 0.23 reads a two-dimensional packed array only inside a struct, and
  // a package type only outside one).
  typedef struct packed {
    logic [rt_pkg::OCTREE_CHILDREN-1:0][rt_pkg::OCTREE_NODE_W-1:0] node;
  } group_t;

  // ---- Per-slot signals ---------------------------------------------------------
  logic [N-1:0]        free, usable, want_visit, want_node, want_idx, want_check, want_done;
  logic [N-1:0]        fetching, waiting_node;
  logic                visit_at_root;
  logic [2:0]          visit_sel;
  logic [31:0]         visit_node_id;
  logic [T_W-1:0]      check_exit;

  // ---- Records kept by slot index -------------------------------------------------
  // The ray as two records: its id (for the visit and result records) and its
  // geometry (for rt_isect, where the slot index takes the id's place).
  typedef struct packed {
    logic [2:0][P-1:0]     org;
    logic [2:0][DIR_W-1:0] dir;
  } ray_geom_t;
  logic [31:0]         ray_id_q [N];
  ray_geom_t           geom_q [N];
  rt_pkg::isect_res_t  best_q [N];
  logic [N-1:0]        has_hit_q;
  logic [31:0]         nodes_q [N];
  logic [31:0]         tests_q [N];
  logic [DIR_W-1:0]    dom_q [N];
  logic [COM_W-1:0]    common_q [N];
  group_t              group_q [N];

  // ---- Ray input and slot allocation --------------------------------------------
  // The lowest free usable slot takes the ray (a fixed-priority arbiter: an
  // rt_rr_arb whose pointer never moves); ray_ready_o depends on slot state only.
  logic [SlotW-1:0] alloc_idx;
  logic [N-1:0]     unused_alloc_gnt;
  logic             ray_fire;

  assign usable = N'((NP1'(1) << cfg_slots_i) - 1'b1);

  rt_rr_arb #(.N(N)) u_alloc_arb (
    .clk_i, .rst_ni, .req_i(free & usable), .ack_i(1'b0),
    .valid_o(ray_ready_o), .gnt_o(unused_alloc_gnt), .idx_o(alloc_idx));

  assign ray_fire = ray_valid_i && ray_ready_o;

  // ---- Setup ---------------------------------------------------------------------
  logic                 su_valid, su_enter;
  logic [SlotW-1:0]     su_slot;
  rt_pkg::isect_ray_t   su_ray;
  logic [2:0]           su_mirror, su_active;
  logic [3*(P+1)-1:0]   su_origin;
  logic [3*T_W-1:0]     su_t0, su_t1;
  logic [COM_W-1:0]     su_common;
  logic [DIR_W-1:0]     su_dom;

  rt_octree_setup #(.SlotW(SlotW)) u_setup (
    .clk_i,
    .rst_ni,
    .valid_i  (ray_fire),
    .slot_i   (alloc_idx),
    .ray_i    (ray_data_i),
    .valid_o  (su_valid),
    .slot_o   (su_slot),
    .ray_o    (su_ray),
    .mirror_o (su_mirror),
    .active_o (su_active),
    .origin_o (su_origin),
    .t0_o     (su_t0),
    .t1_o     (su_t1),
    .common_o (su_common),
    .dom_o    (su_dom),
    .enter_o  (su_enter)
  );

  ray_geom_t su_geom;
  assign su_geom.org = su_ray.org;
  assign su_geom.dir = su_ray.dir;

  // ---- Arbiters -------------------------------------------------------------------
  logic             visit_any, node_any, idx_any, check_any, done_any;
  logic [SlotW-1:0] visit_idx, node_idx, idx_idx, check_idx, done_idx;
  logic [N-1:0]     unused_visit_gnt, unused_node_gnt, unused_idx_gnt, unused_check_gnt, unused_done_gnt;
  logic             visit_go, node_go, idx_go, done_go;
  logic             nodeq_ready, visitq_ready, idxq_ready, resq_ready;
  logic [CREDIT_W-1:0] credit_q;
  logic             idxbuf_pop;

  rt_rr_arb #(.N(N)) u_visit_arb (
    .clk_i, .rst_ni, .req_i(want_visit), .ack_i(visit_go),
    .valid_o(visit_any), .gnt_o(unused_visit_gnt), .idx_o(visit_idx));
  rt_rr_arb #(.N(N)) u_node_arb (
    .clk_i, .rst_ni, .req_i(want_node), .ack_i(node_go),
    .valid_o(node_any), .gnt_o(unused_node_gnt), .idx_o(node_idx));
  rt_rr_arb #(.N(N)) u_idx_arb (
    .clk_i, .rst_ni, .req_i(want_idx), .ack_i(idx_go),
    .valid_o(idx_any), .gnt_o(unused_idx_gnt), .idx_o(idx_idx));
  rt_rr_arb #(.N(N)) u_check_arb (
    .clk_i, .rst_ni, .req_i(want_check), .ack_i(check_any),
    .valid_o(check_any), .gnt_o(unused_check_gnt), .idx_o(check_idx));
  rt_rr_arb #(.N(N)) u_done_arb (
    .clk_i, .rst_ni, .req_i(want_done), .ack_i(done_go),
    .valid_o(done_any), .gnt_o(unused_done_gnt), .idx_o(done_idx));

  // A visit needs room for its record; a group read room in the node request FIFO.
  assign visit_go  = visit_any && visitq_ready;
  assign node_go   = node_any && nodeq_ready;
  // An index read needs a credit: a place in the index buffer for its response.
  assign idx_go    = idx_any && idxq_ready && (credit_q != '0);
  assign done_go   = done_any && resq_ready;

  assign perf_step_ready_o = |want_visit;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      credit_q <= CREDIT_W'(IdxBufDepth);
    end else if (idx_go && !idxbuf_pop) begin
      credit_q <= credit_q - 1'b1;
    end else if (idxbuf_pop && !idx_go) begin
      credit_q <= credit_q + 1'b1;
    end
  end

  // ---- Visits: the granted slot's node, and its record ------------------------------
  // The current node's record is the root's at depth 0, else entry `sel` of
  // the slot's child group (its parent's children).
  rt_pkg::octree_node_t  visit_rec;
  rt_pkg::octree_visit_t visit_out;
  group_t                visit_group, group_in;
  // (The whole element first: Yosys 0.23 takes no field of an array element.)
  assign visit_group = group_q[visit_idx];
  assign visit_rec   = visit_at_root ? cfg_root_i : visit_group.node[visit_sel];
  assign visit_out.ray_id  = ray_id_q[visit_idx];
  assign visit_out.node_id = visit_node_id;

  rt_fifo #(.Width(rt_pkg::OCTREE_VISIT_W), .Depth(4)) u_visit_q (
    .clk_i, .rst_ni,
    .in_valid_i (visit_go),
    .in_ready_o (visitq_ready),
    .in_data_i  (visit_out),
    .out_valid_o(visit_valid_o),
    .out_ready_i(visit_ready_i),
    .out_data_o (visit_data_o)
  );

  // ---- Child-group reads --------------------------------------------------------------
  // Addresses as wires of their own: Yosys 0.23 drops a size cast inside a concatenation.
  logic [ADDR_W-1:0] node_addr, idx_addr, tri_addr;

  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_node_q (
    .clk_i, .rst_ni,
    .in_valid_i (node_go),
    .in_ready_o (nodeq_ready),
    .in_data_i  ({node_addr, node_idx}),
    .out_valid_o(node_req_valid_o),
    .out_ready_i(node_req_ready_i),
    .out_data_o ({node_req_addr_o, node_req_tag_o})
  );

  assign group_in = node_rsp_data_i;

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
  // id stays in ray_q. rt_isect's results are always taken (res_ready_i = 1),
  // so its req_ready_o is always 1 and a triangle response enters at once.
  rt_pkg::isect_ray_t isect_ray;
  ray_geom_t          tri_geom;
  logic               isect_req_ready, isect_res_valid;
  rt_pkg::isect_res_t isect_res;

  assign tri_geom = geom_q[tri_rsp_tag_i];
  always_comb begin
    isect_ray.ray_id = 32'(tri_rsp_tag_i);
    isect_ray.org    = tri_geom.org;
    isect_ray.dir    = tri_geom.dir;
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
  // The products are formed only when a hit meets a slot that has one (a
  // simulator then skips the wide multiplications in the other cycles).
  logic [SlotW-1:0]   res_slot;
  rt_pkg::isect_res_t res_best;
  logic               res_take;
  logic [CLO_W-1:0]   clo_new, clo_old;

  assign res_slot = isect_res.ray_id[SlotW-1:0];
  always_comb begin
    clo_new  = '0;
    clo_old  = '0;
    res_take = 1'b0;
    res_best = '0;
    if (isect_res_valid && isect_res.hit) begin
      res_best = best_q[res_slot];  // (the whole element: Yosys 0.23 takes no field of one)
      if (!has_hit_q[res_slot]) begin
        res_take = 1'b1;
      end else begin
        clo_new  = CLO_W'(isect_res.t_num) * CLO_W'(res_best.det);
        clo_old  = CLO_W'(res_best.t_num) * CLO_W'(isect_res.det);
        res_take = clo_new < clo_old || (clo_new == clo_old && isect_res.prim_id < res_best.prim_id);
      end
    end
  end

  // ---- Exit test: does the closest hit lie within the leaf? ------------------------
  // fx::hitWithin: !(min(t1) * dominant * det < t_num * common), min over the
  // active axes; the leaf's t1 are >= 0 (it was entered). Formed only in a
  // cycle with a check grant.
  rt_pkg::isect_res_t chk_best;
  logic [CHK_W-1:0]   chk_lhs, chk_rhs;
  logic               check_holds;
  always_comb begin
    chk_lhs     = '0;
    chk_rhs     = '0;
    check_holds = 1'b0;
    chk_best    = '0;
    if (check_any) begin
      chk_best    = best_q[check_idx];
      chk_lhs     = CHK_W'(check_exit) * CHK_W'(dom_q[check_idx]) * CHK_W'(chk_best.det);
      chk_rhs     = CHK_W'(chk_best.t_num) * CHK_W'(common_q[check_idx]);
      check_holds = !(chk_lhs < chk_rhs);
    end
  end

  // ---- Slots -------------------------------------------------------------------------
  rt_octree_slots #(.N(N), .SlotW(SlotW)) u_slots (
    .clk_i,
    .rst_ni,
    .free_o           (free),
    .alloc_i          (ray_fire),
    .alloc_slot_i     (alloc_idx),
    .init_i           (su_valid),
    .init_slot_i      (su_slot),
    .init_enter_i     (su_enter),
    .init_mirror_i    (su_mirror),
    .init_active_i    (su_active),
    .init_origin_i    (su_origin),
    .init_t0_i        (su_t0),
    .init_t1_i        (su_t1),
    .want_visit_o     (want_visit),
    .visit_go_i       (visit_go),
    .visit_slot_i     (visit_idx),
    .visit_rec_i      (visit_rec),
    .visit_at_root_o  (visit_at_root),
    .visit_sel_o      (visit_sel),
    .visit_node_id_o  (visit_node_id),
    .want_node_o      (want_node),
    .node_go_i        (node_go),
    .node_slot_i      (node_idx),
    .node_addr_o      (node_addr),
    .waiting_node_o   (waiting_node),
    .node_rsp_valid_i (node_rsp_valid_i),
    .node_rsp_slot_i  (node_rsp_tag_i),
    .want_idx_o       (want_idx),
    .idx_go_i         (idx_go),
    .idx_slot_i       (idx_idx),
    .idx_addr_o       (idx_addr),
    .fetching_o       (fetching),
    .res_valid_i      (isect_res_valid),
    .res_slot_i       (res_slot),
    .hit_i            (has_hit_q),
    .want_check_o     (want_check),
    .check_go_i       (check_any),
    .check_slot_i     (check_idx),
    .check_exit_o     (check_exit),
    .check_holds_i    (check_holds),
    .want_done_o      (want_done),
    .done_go_i        (done_go),
    .done_slot_i      (done_idx)
  );

  // ---- The records kept by slot index ---------------------------------------------------
  // No reset: each is written (at the slot's setup) before it is read.
  always_ff @(posedge clk_i) begin
    if (su_valid) begin
      ray_id_q[su_slot] <= su_ray.ray_id;
      geom_q[su_slot]   <= su_geom;
      dom_q[su_slot]    <= su_dom;
      common_q[su_slot] <= su_common;
      nodes_q[su_slot]  <= '0;
      tests_q[su_slot]  <= '0;
      best_q[su_slot]   <= '0;
    end
    if (visit_go) begin
      nodes_q[visit_idx] <= nodes_q[visit_idx] + 1'b1;
      if (visit_rec.leaf) tests_q[visit_idx] <= tests_q[visit_idx] + 32'(visit_rec.count);
    end
    if (node_rsp_valid_i) group_q[node_rsp_tag_i] <= group_in;
    if (res_take) best_q[res_slot] <= isect_res;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      has_hit_q <= '0;
    end else begin
      if (su_valid) has_hit_q[su_slot] <= 1'b0;
      if (res_take) has_hit_q[res_slot] <= 1'b1;
    end
  end

  // ---- Results -------------------------------------------------------------------------
  // The record is assembled only in a cycle with a done grant.
  rt_pkg::octree_res_t done_rec;
  rt_pkg::isect_res_t  done_best;
  always_comb begin
    done_rec  = '0;
    done_best = '0;
    if (done_any) begin
      done_best        = best_q[done_idx];
      done_rec.ray_id  = ray_id_q[done_idx];
      done_rec.nodes   = nodes_q[done_idx];
      done_rec.tests   = tests_q[done_idx];
      done_rec.hit     = has_hit_q[done_idx];
      done_rec.prim_id = done_best.prim_id;
      done_rec.t_num   = done_best.t_num;
      done_rec.det     = done_best.det;
      done_rec.u_num   = done_best.u_num;
      done_rec.v_num   = done_best.v_num;
    end
  end

  rt_fifo #(.Width(rt_pkg::OCTREE_RESULT_W), .Depth(2)) u_res_q (
    .clk_i, .rst_ni,
    .in_valid_i (done_go),
    .in_ready_o (resq_ready),
    .in_data_i  (done_rec),
    .out_valid_o(res_valid_o),
    .out_ready_i(res_ready_i),
    .out_data_o (res_data_o)
  );

`ifdef RT_ASSERT_ON
  // The state of the slots the responses name.
  logic node_rsp_waiting, tri_rsp_fetching, res_fetching;
  assign node_rsp_waiting = waiting_node[node_rsp_tag_i];
  assign tri_rsp_fetching = fetching[tri_rsp_tag_i];
  assign res_fetching     = fetching[res_slot];

  // Output streams (results, visits, the three request ports) come straight
  // from rt_fifo instances, whose a_out_hold checks that valid never drops and
  // data holds until taken; they are not checked twice here.
  // Input stream (the producer's duty).
  a_ray_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      ray_valid_i && !ray_ready_o |=> ray_valid_i && $stable(ray_data_i));
  // Responses: credits guarantee room, tags name a slot that waits for them.
  a_idx_buf_room : assert property (@(posedge clk_i) disable iff (!rst_ni)
      idx_rsp_valid_i |-> idxbuf_ready);
  a_isect_ready : assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_rsp_valid_i |-> isect_req_ready);
  a_node_rsp_slot : assert property (@(posedge clk_i) disable iff (!rst_ni)
      node_rsp_valid_i |-> node_rsp_waiting);
  a_tri_rsp_slot : assert property (@(posedge clk_i) disable iff (!rst_ni)
      tri_rsp_valid_i |-> tri_rsp_fetching);
  a_res_slot : assert property (@(posedge clk_i) disable iff (!rst_ni)
      isect_res_valid |-> res_fetching);
  a_cfg_slots : assert property (@(posedge clk_i) disable iff (!rst_ni)
      cfg_slots_i != '0 && cfg_slots_i <= CfgSlotsW'(N));
  a_credit_range : assert property (@(posedge clk_i) disable iff (!rst_ni)
      credit_q <= CREDIT_W'(IdxBufDepth));
  if (N > 256) begin : g_slots_check
    $error("rt_octree: RaysInFlight must lie in 1..256");
  end
`endif

endmodule
