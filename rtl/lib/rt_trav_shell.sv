// rt_trav_shell: what every traversal unit (rt_grid, rt_octree, rt_bvh) does the
// same way around its own walk, which sits beside it (the unit's slots module).
//
//   ray_*      rays in (valid/ready); the lowest free usable slot takes a ray
//              (a fixed-priority arbiter: an rt_rr_arb whose pointer never
//              moves), so ray_ready_o depends on slot state only
//   records    per slot, written at the unit's init: the ray's id, geometry,
//              segment end and any-hit flag, its dominant |d| and the unit's
//              exit-test denominator; the closest hit so far and whether there
//              is one (before the first, the record holds the segment end as a
//              pseudo hit {t_num = t_max, det = 2^SEG_FRAC_W}: fx::walkBound)
//   node port  the walk's reads (grid cells, octree child groups): round robin
//              over the slots that want one, through a 2-entry request FIFO;
//              the response goes to the walk, registered when RegRsp
//   visit_*    one record {ray id, visit_id} per region entered (round robin,
//              4-entry FIFO)
//   idx port   one index-list read per test (round robin), credit-limited by
//              the index buffer (IdxBufDepth entries, the credits)
//   tri port   one primitive read per index response, in index-response order:
//              the entry's kind bit (bit 31) says which table (tri_req_quadric_o)
//   u_isect    rt_isect; the slot index travels in the ray id field; a
//              triangle response enters it in the cycle it arrives, or in the
//              next one when RegRsp (registered at the boundary)
//   u_quadric  rt_quadric (Quadrics only): a quadric response enters it as a
//              triangle's enters rt_isect, with its slot's ray
//   closest    one result per cycle updates its slot's closest hit
//              (rt_closest_hit, three stages: the walk sees the result and its
//              verdict CLOSEST_HIT_LATENCY cycles after it leaves its
//              pipeline); rt_isect's result goes first, and rt_quadric's
//              waits in its pipeline meanwhile (its stages squeeze out the
//              bubble the triangle left: one primitive a cycle enters the two,
//              so rt_quadric is always ready; docs/quadrics.md, "In the
//              traversal units")
//   check      one exit test started per cycle (round robin over the slots
//              that want one and are not under test; rt_exit_test, pipelined,
//              with the walk's exit parameter against the record: the closest
//              hit, or the segment end), its answer EXIT_TEST_LATENCY cycles
//              after the grant. A slot is tested when bound (a hit, or a
//              segment end); an any-hit ray with a hit holds without the
//              arithmetic (its walk ends after the region of its hit)
//   res_*      one record per ray: {ray id, regions entered, tests issued,
//              ray-quadric tests of them, hit, the closest hit} (round robin,
//              2-entry FIFO); with a suspended walk's record beside it
//              (res_suspend, res_walk: the treelet schedule)
//   resume     a resumed ray's init loads the closest hit its walk carried
//              (init_resume, init_hit) instead of the segment end
//
// The walk sees only grants (go, slot index), the responses, the results and
// the closest-hit state; it gives want vectors, addresses, the visit id, the
// tests to count and the exit parameter. Those ports (rt_walk_ports.svh) have
// one name at both ends, so a unit's top joins the two with `.*`.
//
// Memory ports: requests are valid/ready (a 2-entry FIFO holds each port's
// request stream); responses have no ready: the unit always accepts them
// (credits: index responses land in the index buffer, which is never
// overfilled; node and triangle responses are consumed in their cycle, or
// registered and consumed in the next one). Responses per port come in request
// order; the tag is the slot.
//
// Latency: 0 cycles from a want to its grant; each FIFO 1 cycle; the triangle
// response 0 (RegRsp = 0) or 1 cycle to rt_isect, then ISECT_LATENCY, then
// CLOSEST_HIT_LATENCY to the walk (the closest-hit verdict); an exit test EXIT_TEST_LATENCY
// cycles from its grant to its answer.
// Throughput: per cycle at most one ray accepted, one node read, one visit
// record, one index read, one primitive read, one intersection test (of
// either kind), one closest-hit update, one exit test and one result.
module rt_trav_shell #(
  parameter int unsigned N           = 32,  // ray slots, 1..256
  parameter int unsigned IdxBufDepth = 64,  // index responses buffered (credits)
  parameter int unsigned NodeRspW    = 64,  // width of a node response
  parameter bit          RegRsp      = 1'b0,// register node and triangle responses at the boundary
  parameter int unsigned VisitIdW    = 32,  // width of the region id of a visit record
  parameter int unsigned ExitW       = 8,   // width of the exit parameter
  parameter int unsigned DenW        = 8,   // width of the exit test's denominator
  parameter int unsigned RunPorts    = 1,   // index runs the walk may start in a cycle
  parameter int unsigned Quadrics    = 0,   // 1: rt_quadric beside rt_isect (scenes with spheres and cones)
  parameter int unsigned WalkPartW   = 0,   // a suspended walk's part of its record (0: the unit suspends none)
  parameter int unsigned SlotW     = (N > 1) ? $clog2(N) : 1,  // derived
  parameter int unsigned WalkPortW = (WalkPartW > 0) ? WalkPartW : 1,  // derived
  parameter int unsigned CfgSlotsW = $clog2(N + 1),            // derived
  parameter int unsigned ResW      = rt_pkg::ISECT_RES_W + 96  // derived: {ray id, count, tests, quadric tests, hit, hit record}
) (
  // ---- The unit's ports ----
`include "rt_trav_ports.svh"

  // ---- The walk's side ----
`define RT_WALK_PORTS_OF_SHELL
`include "rt_walk_ports.svh"

  output logic [ResW-1:0]               res_data_o,
  output logic [32+VisitIdW-1:0]        visit_data_o
);

  localparam int ADDR_W   = rt_pkg::MEM_ADDR_W;
  localparam int P        = rt_pkg::POS_W;
  localparam int DIR_W    = rt_pkg::DIR_W;
  localparam int MEMREQ_W = ADDR_W + SlotW;
  localparam int PRIMREQ_W = 1 + MEMREQ_W;  // {quadric, address, slot}
  localparam int IDXBUF_W = 32 + SlotW;
  localparam int CREDIT_W = $clog2(IdxBufDepth + 1);
  localparam int NP1      = N + 1;

  // The ray's geometry, for rt_isect (where the slot index takes the id's place).
  typedef struct packed {
    logic [2:0][P-1:0]     org;
    logic [2:0][DIR_W-1:0] dir;
  } ray_geom_t;

  // A closest hit as kept per slot (isect_res_t without ray id and hit).
  typedef struct packed {
    logic [31:0]                   prim_id;
    logic [rt_pkg::T_NUM_W-1:0]    t_num;
    logic [rt_pkg::DET_ABS_W-1:0]  det;
    logic [rt_pkg::BARY_W-1:0]     u_num;
    logic [rt_pkg::BARY_W-1:0]     v_num;
  } best_t;

  localparam int GEOM_W = 3 * P + 3 * DIR_W;
  localparam int BEST_W = 32 + rt_pkg::T_NUM_W + rt_pkg::DET_ABS_W + 2 * rt_pkg::BARY_W;

  // ---- Records kept by slot index (no reset: written at init, before read) ----
  // Plain vectors, read into the struct types: Yosys 0.23 keeps only one
  // element's flops of an unpacked array of a packed struct.
  logic [31:0]      ray_id_q [N];
  logic [GEOM_W-1:0] geom_q  [N];
  logic [DIR_W-1:0] dom_q    [N];
  logic [DenW-1:0]  den_q    [N];
  logic [BEST_W-1:0] best_q  [N];
  logic [rt_pkg::SEG_END_W-1:0] seg_q [N];
  logic [N-1:0]     has_hit_q, bounded_q, any_hit_q;
  logic [31:0]      visits_q [N];   // regions entered
  logic [31:0]      tests_q  [N];   // tests issued
  logic [31:0]      qtests_q [N];   // of them ray-quadric (Quadrics only)

  function automatic logic [N-1:0] onehot(input logic valid, input logic [SlotW-1:0] s);
    onehot = valid ? (N'(1) << s) : '0;
  endfunction

  // ---- Ray input and slot allocation --------------------------------------------
  // A slot is FREE, then in SETUP from its allocation to its init (the walk's
  // setup latency), then the walk's until its done grant.
  logic [N-1:0] free_q, setup_q, usable, unused_alloc_gnt;

  assign usable = N'((NP1'(1) << cfg_slots_i) - 1'b1);

  rt_rr_arb #(.N(N)) u_alloc_arb (
    .clk_i, .rst_ni, .req_i(free_q & usable), .ack_i(1'b0),
    .valid_o(ray_ready_o), .gnt_o(unused_alloc_gnt), .idx_o(alloc_slot));

  assign alloc = ray_valid_i && ray_ready_o;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      free_q  <= '1;
      setup_q <= '0;
    end else begin
      free_q  <= (free_q & ~onehot(alloc, alloc_slot)) | onehot(done_go, done_slot);
      setup_q <= (setup_q & ~onehot(init, init_slot)) | onehot(alloc, alloc_slot);
    end
  end

  // ---- Index runs: their reads and results, counted per slot ----------------------
  // A run with triangles asks for index reads (iss_q) from its start to its
  // last grant; rt_idx_count counts the reads issued and the results in.
  logic [N-1:0] iss_q;     // slots with index reads left to issue
  logic         idx_go;    // an index read of idx_slot is granted
  logic         idx_last;  // the index grant is its run's last read
  logic [N-1:0] run_reads;

  rt_idx_count #(.N(N), .Starts(RunPorts), .SlotW(SlotW)) u_idx_count (
    .clk_i,
    .rst_ni,
    .start_i       (run_start),
    .start_slot_i  (run_slot),
    .start_count_i (run_count),
    .idx_go_i      (idx_go),
    .idx_slot_i    (idx_slot),
    .idx_issued_o  (idx_issued),
    .idx_last_o    (idx_last),
    .res_valid_i   (isect_valid),
    .res_slot_i    (isect_slot),
    .res_last_o    (res_last)
  );

  always_comb begin
    run_reads = '0;
    for (int p = 0; p < RunPorts; p++) begin
      run_reads = run_reads | onehot(run_start[p] && run_count[p*32 +: 32] != '0, run_slot[p*SlotW +: SlotW]);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      iss_q <= '0;
    end else begin
      iss_q <= (iss_q & ~onehot(idx_last, idx_slot)) | run_reads;
    end
  end

  // ---- Arbiters -------------------------------------------------------------------
  logic         node_any, visit_any, idx_any, done_any;
  logic         check_grant;         // a slot's exit test starts (rt_exit_test, below)
  logic [SlotW-1:0] check_grant_slot;
  logic [N-1:0] testing_q;           // slots whose exit test is in flight
  // The arbiters' one-hot grants are not needed: the walk takes indices.
  logic [N-1:0] unused_node_gnt, unused_visit_gnt, unused_idx_gnt, unused_check_gnt, unused_done_gnt;
  logic         nodeq_ready, visitq_ready, idxq_ready, resq_ready;
  logic [CREDIT_W-1:0] credit_q;
  logic         idxbuf_pop;

  rt_rr_arb #(.N(N)) u_node_arb (
    .clk_i, .rst_ni, .req_i(want_node), .ack_i(node_go),
    .valid_o(node_any), .gnt_o(unused_node_gnt), .idx_o(node_slot));
  rt_rr_arb #(.N(N)) u_visit_arb (
    .clk_i, .rst_ni, .req_i(want_visit), .ack_i(visit_go),
    .valid_o(visit_any), .gnt_o(unused_visit_gnt), .idx_o(visit_slot));
  rt_rr_arb #(.N(N)) u_idx_arb (
    .clk_i, .rst_ni, .req_i(iss_q), .ack_i(idx_go),
    .valid_o(idx_any), .gnt_o(unused_idx_gnt), .idx_o(idx_slot));
  rt_rr_arb #(.N(N)) u_check_arb (
    .clk_i, .rst_ni, .req_i(want_check & ~testing_q), .ack_i(check_grant),
    .valid_o(check_grant), .gnt_o(unused_check_gnt), .idx_o(check_grant_slot));
  rt_rr_arb #(.N(N)) u_done_arb (
    .clk_i, .rst_ni, .req_i(want_done), .ack_i(done_go),
    .valid_o(done_any), .gnt_o(unused_done_gnt), .idx_o(done_slot));

  // A node read needs room in its request FIFO, a visit room in the visit FIFO.
  assign node_go  = node_any && nodeq_ready;
  assign visit_go = visit_any && visitq_ready;
  // An index read needs a credit: a place in the index buffer for its response.
  assign idx_go   = idx_any && idxq_ready && (credit_q != '0);
  assign done_go  = done_any && resq_ready;

  assign perf_step_ready_o = (want_visit != '0);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      credit_q <= CREDIT_W'(IdxBufDepth);
    end else if (idx_go && !idxbuf_pop) begin
      credit_q <= credit_q - 1'b1;
    end else if (idxbuf_pop && !idx_go) begin
      credit_q <= credit_q + 1'b1;
    end
  end

  // ---- Node and primitive responses: in their cycle, or registered ---------------------
  logic               tri_valid;
  logic [SlotW-1:0]   tri_slot;
  rt_pkg::isect_tri_t tri_data;
  logic                   quad_valid;  // a quadric response (Quadrics only)
  logic [SlotW-1:0]       quad_slot;
  rt_pkg::isect_quadric_t quad_data;

  if (RegRsp) begin : g_reg_rsp
    // A node or triangle response arriving in cycle c is used in cycle c+1.
    rt_pipe_reg #(.Width(SlotW + NodeRspW)) u_node_rsp (
      .clk_i, .rst_ni, .valid_i(node_rsp_valid_i), .data_i({node_rsp_tag_i, node_rsp_data_i}),
      .valid_o(node_valid), .data_o({node_tag, node_data}));
    rt_pipe_reg #(.Width(SlotW + rt_pkg::ISECT_TRI_W)) u_tri_rsp (
      .clk_i, .rst_ni, .valid_i(tri_rsp_valid_i), .data_i({tri_rsp_tag_i, tri_rsp_data_i}),
      .valid_o(tri_valid), .data_o({tri_slot, tri_data}));
  end else begin : g_direct_rsp
    assign {node_valid, node_tag, node_data} = {node_rsp_valid_i, node_rsp_tag_i, node_rsp_data_i};
    assign {tri_valid, tri_slot, tri_data}         = {tri_rsp_valid_i, tri_rsp_tag_i, tri_rsp_data_i};
  end

  if (Quadrics != 0 && RegRsp) begin : g_reg_quadric_rsp
    rt_pipe_reg #(.Width(SlotW + rt_pkg::ISECT_QUADRIC_W)) u_quadric_rsp (
      .clk_i, .rst_ni, .valid_i(quadric_rsp_valid_i), .data_i({quadric_rsp_tag_i, quadric_rsp_data_i}),
      .valid_o(quad_valid), .data_o({quad_slot, quad_data}));
  end else if (Quadrics != 0) begin : g_direct_quadric_rsp
    assign {quad_valid, quad_slot, quad_data} = {quadric_rsp_valid_i, quadric_rsp_tag_i, quadric_rsp_data_i};
  end else begin : g_no_quadric_rsp
    // A unit without rt_quadric takes no quadric response (its image lists none).
    logic unused_quadric_rsp;
    assign unused_quadric_rsp = ^{quadric_rsp_valid_i, quadric_rsp_tag_i, quadric_rsp_data_i};
    assign {quad_valid, quad_slot, quad_data} = '0;
  end

  // ---- Node reads and visit records ----------------------------------------------------
  // The visit record as a wire of its own: Yosys 0.23 drops a size cast inside
  // a concatenation, and takes no field of an array element.
  logic [31:0]          visit_ray_id;
  logic [32+VisitIdW-1:0] visit_rec;
  assign visit_ray_id = ray_id_q[visit_slot];
  assign visit_rec    = {visit_ray_id, visit_id};

  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_node_q (
    .clk_i, .rst_ni,
    .in_valid_i (node_go),
    .in_ready_o (nodeq_ready),
    .in_data_i  ({node_addr, node_slot}),
    .out_valid_o(node_req_valid_o),
    .out_ready_i(node_req_ready_i),
    .out_data_o ({node_req_addr_o, node_req_tag_o})
  );

  rt_fifo #(.Width(32 + VisitIdW), .Depth(4)) u_visit_q (
    .clk_i, .rst_ni,
    .in_valid_i (visit_go),
    .in_ready_o (visitq_ready),
    .in_data_i  (visit_rec),
    .out_valid_o(visit_valid_o),
    .out_ready_i(visit_ready_i),
    .out_data_o (visit_data_o)
  );

  // ---- Index reads, index buffer, primitive reads -------------------------------------
  logic [ADDR_W-1:0]   tri_addr;
  logic                tri_quadric;  // the entry's kind bit: the quadric table
  logic                idxbuf_valid, idxbuf_ready, triq_ready;
  logic [IDXBUF_W-1:0] idxbuf_data;

  rt_fifo #(.Width(MEMREQ_W), .Depth(2)) u_idx_q (
    .clk_i, .rst_ni,
    .in_valid_i (idx_go),
    .in_ready_o (idxq_ready),
    .in_data_i  ({idx_addr, idx_slot}),
    .out_valid_o(idx_req_valid_o),
    .out_ready_i(idx_req_ready_i),
    .out_data_o ({idx_req_addr_o, idx_req_tag_o})
  );

  rt_fifo #(.Width(IDXBUF_W), .Depth(IdxBufDepth)) u_idx_buf (
    .clk_i, .rst_ni,
    .in_valid_i (idx_rsp_valid_i),
    .in_ready_o (idxbuf_ready),
    .in_data_i  ({idx_rsp_data_i, idx_rsp_tag_i}),
    .out_valid_o(idxbuf_valid),
    .out_ready_i(triq_ready),
    .out_data_o (idxbuf_data)
  );
  assign idxbuf_pop  = idxbuf_valid && triq_ready;
  assign tri_addr    = ADDR_W'(idxbuf_data[IDXBUF_W-1 -: 32]);
  assign tri_quadric = idxbuf_data[IDXBUF_W-1];

  rt_fifo #(.Width(PRIMREQ_W), .Depth(2)) u_tri_q (
    .clk_i, .rst_ni,
    .in_valid_i (idxbuf_valid),
    .in_ready_o (triq_ready),
    .in_data_i  ({tri_quadric, tri_addr, idxbuf_data[SlotW-1:0]}),
    .out_valid_o(tri_req_valid_o),
    .out_ready_i(tri_req_ready_i),
    .out_data_o ({tri_req_quadric_o, tri_req_addr_o, tri_req_tag_o})
  );

  // ---- Intersection: the primitive and its slot's ray ------------------------------------
  // The slot index travels in the ray id field through rt_isect and
  // rt_quadric; the real ray id stays in ray_id_q. rt_isect's results are
  // always taken (res_ready_i = 1), so its req_ready_o is always 1 and a
  // triangle enters at once. One primitive a cycle: one slot's ray read.
  rt_pkg::isect_ray_t isect_ray;
  ray_geom_t          prim_geom;
  logic [SlotW-1:0]   prim_slot;
  logic               isect_req_ready, isect_res_valid;
  rt_pkg::isect_res_t isect_res;

  assign prim_slot = quad_valid ? quad_slot : tri_slot;
  assign prim_geom = geom_q[prim_slot];
  always_comb begin
    isect_ray.ray_id  = 32'(prim_slot);
    isect_ray.org     = prim_geom.org;
    isect_ray.dir     = prim_geom.dir;
    isect_ray.t_max   = seg_q[prim_slot];
    isect_ray.any_hit = any_hit_q[prim_slot];
  end

  rt_isect u_isect (
    .clk_i,
    .rst_ni,
    .req_valid_i (tri_valid),
    .req_ready_o (isect_req_ready),
    .req_ray_i   (isect_ray),
    .req_tri_i   (tri_data),
    .res_valid_o (isect_res_valid),
    .res_ready_i (1'b1),
    .res_data_o  (isect_res)
  );

  // rt_quadric beside it. Its result waits while rt_isect's goes to the
  // closest hit (a triangle's result never waits: its response cannot).
  logic               quadric_req_ready, quadric_res_valid;
  rt_pkg::isect_res_t quadric_res;
  if (Quadrics != 0) begin : g_quadric
    rt_quadric u_quadric (
      .clk_i,
      .rst_ni,
      .req_valid_i   (quad_valid),
      .req_ready_o   (quadric_req_ready),
      .req_ray_i     (isect_ray),
      .req_quadric_i (quad_data),
      .res_valid_o   (quadric_res_valid),
      .res_ready_i   (!isect_res_valid),
      .res_data_o    (quadric_res)
    );
  end else begin : g_no_quadric
    assign {quadric_req_ready, quadric_res_valid, quadric_res} = '0;
    logic unused_quad_data;  // no quadric response comes (the tied-off one above)
    assign unused_quad_data = ^quad_data;
  end
  assign perf_isect_fire_o = (tri_valid && isect_req_ready) || quad_valid;

  // The result of this cycle: rt_isect's, else rt_quadric's.
  logic               prim_res_valid;
  rt_pkg::isect_res_t prim_res;
  assign prim_res_valid = isect_res_valid || quadric_res_valid;
  assign prim_res       = isect_res_valid ? isect_res : quadric_res;

  // ---- Closest hit: three stages (rt_closest_hit) ------------------------------------
  // A result leaving rt_isect meets its slot's record here; it reaches the
  // walk (isect_valid, isect_slot, isect_hit) CLOSEST_HIT_LATENCY
  // cycles later, with its verdict (take), in the cycle the record takes it.
  logic [SlotW-1:0]            res_slot;
  logic                        take;        // the result becomes the slot's closest hit
  logic [31:0]                 take_prim;
  logic [rt_pkg::T_NUM_W-1:0]  take_t_num;
  logic [rt_pkg::DET_ABS_W-1:0] take_det;
  logic [2*rt_pkg::BARY_W-1:0] take_bary;
  best_t res_best, res_new;
  assign res_slot = prim_res.ray_id[SlotW-1:0];
  // (The whole element first: Yosys 0.23 takes no field of an array element.)
  assign res_best = best_q[res_slot];

  rt_closest_hit #(.SlotW(SlotW), .PayloadW(2 * rt_pkg::BARY_W)) u_closest (
    .clk_i,
    .rst_ni,
    .valid_i      (prim_res_valid),
    .slot_i       (res_slot),
    .hit_i        (prim_res.hit),
    .prim_id_i    (prim_res.prim_id),
    .t_num_i      (prim_res.t_num),
    .det_i        (prim_res.det),
    .payload_i    ({prim_res.u_num, prim_res.v_num}),
    .has_best_i   (has_hit_q[res_slot]),
    .best_prim_i  (res_best.prim_id),
    .best_t_num_i (res_best.t_num),
    .best_det_i   (res_best.det),
    .valid_o      (isect_valid),
    .slot_o       (isect_slot),
    .hit_o        (isect_hit),
    .take_o       (take),
    .prim_id_o    (take_prim),
    .t_num_o      (take_t_num),
    .det_o        (take_det),
    .payload_o    (take_bary)
  );
  always_comb begin
    res_new.prim_id = take_prim;
    res_new.t_num   = take_t_num;
    res_new.det     = take_det;
    {res_new.u_num, res_new.v_num} = take_bary;
  end
  assign bound = has_hit_q | bounded_q;

  // ---- Exit tests, pipelined ---------------------------------------------------------
  // The grant is registered (cycle t+1 reads the slot's exit parameter and its
  // record into rt_exit_test), so no path runs from the arbiter into the
  // arithmetic. The slot stays in its walk's CHECK state meanwhile, with no
  // result in flight (it tests after its last result), so its record holds
  // still; testing_q keeps it from asking again until its answer.
  logic             sel_valid;
  logic [SlotW-1:0] sel_slot;
  best_t            sel_best;
  rt_pipe_reg #(.Width(SlotW)) u_check_grant (
    .clk_i, .rst_ni, .valid_i(check_grant), .data_i(check_grant_slot),
    .valid_o(sel_valid), .data_o(sel_slot));
  assign check_sel = sel_slot;
  assign sel_best    = best_q[sel_slot];

  rt_exit_test #(.ExitW(ExitW), .DenW(DenW), .TagW(SlotW)) u_exit (
    .clk_i,
    .rst_ni,
    .valid_i   (sel_valid),
    .tag_i     (sel_slot),
    .settled_i (any_hit_q[sel_slot] && has_hit_q[sel_slot]),
    .exit_i    (check_exit),
    .dom_i     (dom_q[sel_slot]),
    .den_i     (den_q[sel_slot]),
    .t_num_i   (sel_best.t_num),
    .det_i     (sel_best.det),
    .valid_o   (check_go),
    .tag_o     (check_slot),
    .holds_o   (check_holds)
  );

  // ---- The records kept by slot index ---------------------------------------------------
  ray_geom_t init_geom;
  best_t     init_best;  // the segment end as a pseudo hit
  assign init_geom.org = init_ray.org;
  assign init_geom.dir = init_ray.dir;
  always_comb begin
    init_best         = '0;
    init_best.t_num   = rt_pkg::T_NUM_W'(init_ray.t_max);
    init_best.det     = rt_pkg::DET_ABS_W'(1) << rt_pkg::SEG_FRAC_W;
  end

  // A resumed walk's closest hit so far, if it has one, replaces the segment end.
  logic init_has_hit;
  assign init_has_hit = init_resume && init_hit[BEST_W];

  always_ff @(posedge clk_i) begin
    if (init) begin
      ray_id_q[init_slot] <= init_ray.ray_id;
      geom_q[init_slot]   <= init_geom;
      dom_q[init_slot]    <= init_dom;
      den_q[init_slot]    <= init_den;
      best_q[init_slot]   <= init_has_hit ? init_hit[BEST_W-1:0] : init_best;
      seg_q[init_slot]    <= init_ray.t_max;
    end
    if (take) best_q[isect_slot] <= res_new;
  end

  // The counts of the result record: regions entered, tests issued (the
  // runs' primitives; the run ports name different slots in one cycle), and
  // of them the quadrics (as each enters rt_quadric).
  always_ff @(posedge clk_i) begin
    if (init) begin
      visits_q[init_slot] <= '0;
      tests_q[init_slot]  <= '0;
      qtests_q[init_slot] <= '0;
    end
    if (quad_valid) qtests_q[quad_slot] <= qtests_q[quad_slot] + 1'b1;
    if (visit_go) visits_q[visit_slot] <= visits_q[visit_slot] + 1'b1;
    for (int p = 0; p < RunPorts; p++) begin
      if (run_start[p]) begin
        tests_q[run_slot[p*SlotW +: SlotW]] <= tests_q[run_slot[p*SlotW +: SlotW]] + run_count[p*32 +: 32];
      end
    end
  end

  // (testing_q: the slots whose exit test is in flight, above.)
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      has_hit_q <= '0;
      bounded_q <= '0;
      any_hit_q <= '0;
      testing_q <= '0;
    end else begin
      testing_q <= (testing_q | (N'(check_grant) << check_grant_slot)) & ~(N'(check_go) << check_slot);
      if (init) begin
        has_hit_q[init_slot] <= init_has_hit;
        bounded_q[init_slot] <= init_ray.t_max != '1;
        any_hit_q[init_slot] <= init_ray.any_hit;
      end
      if (take) has_hit_q[isect_slot] <= 1'b1;
    end
  end

  // ---- Results -------------------------------------------------------------------------
  // The record is assembled only in a cycle with a done grant.
  logic [ResW-1:0] done_rec;
  best_t           done_best;
  logic [31:0]     done_ray_id, done_visits, done_tests, done_qtests;
  logic            done_hit;
  always_comb begin
    done_best   = '0;
    done_ray_id = '0;
    done_hit    = 1'b0;
    if (done_any) begin
      done_ray_id = ray_id_q[done_slot];
      done_hit    = has_hit_q[done_slot];
      if (done_hit) done_best = best_q[done_slot];  // (not the segment end)
    end
  end
  assign done_visits = visits_q[done_slot];
  assign done_tests  = tests_q[done_slot];
  assign done_qtests = (Quadrics != 0) ? qtests_q[done_slot] : '0;
  assign done_rec    = {done_ray_id, done_visits, done_tests, done_qtests, done_hit, done_best};

  // A suspended walk's part rides with its result (none in a unit that
  // suspends no walk: the FIFO holds the record only).
  localparam int SUS_W = (WalkPartW > 0) ? 1 + WalkPartW : 0;
  localparam int RESQ_W = ResW + SUS_W;
  logic [RESQ_W-1:0] resq_in, resq_out;
  if (WalkPartW > 0) begin : g_suspension
    logic               out_suspend;
    logic [WalkPartW-1:0] out_walk;
    assign resq_in = {done_rec, done_suspend, done_suspend ? done_walk : '0};
    assign {res_data_o, out_suspend, out_walk} = resq_out;
    assign res_suspend = out_suspend;
    // The walk record: the result's {hit, closest hit}, then the walk's part.
    assign res_walk    = out_suspend ? {res_data_o[BEST_W:0], out_walk} : '0;
  end else begin : g_no_suspension
    assign resq_in     = done_rec;
    assign res_data_o  = resq_out;
    assign res_suspend = 1'b0;
    assign res_walk    = '0;
    logic unused_walk;
    assign unused_walk = ^{done_suspend, done_walk};
  end

  rt_fifo #(.Width(RESQ_W), .Depth(2)) u_res_q (
    .clk_i, .rst_ni,
    .in_valid_i (done_go),
    .in_ready_o (resq_ready),
    .in_data_i  (resq_in),
    .out_valid_o(res_valid_o),
    .out_ready_i(res_ready_i),
    .out_data_o (resq_out)
  );

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Output streams (results, visits, the three request ports) come straight
  // from rt_fifo instances, whose a_out_hold checks that valid never drops and
  // data holds until taken; they are not checked twice here.
  // Input stream (the producer's duty).
  `RT_ASSERT(a_ray_hold, ray_valid_i && !ray_ready_o |=> ray_valid_i && $stable(ray_data_i))
  // Responses: credits guarantee room, triangles and results name a slot that
  // expects them.
  `RT_CHECK_IF(a_idx_buf_room, idx_rsp_valid_i, idxbuf_ready)
  `RT_CHECK_IF(a_isect_ready, tri_valid, isect_req_ready)
  `RT_CHECK_IF(a_tri_rsp_slot, tri_valid, fetching[tri_slot])
  `RT_CHECK_IF(a_res_slot, prim_res_valid, fetching[res_slot])
  // One primitive response a cycle (one port), and rt_quadric always takes it
  // (the bubble of each triangle that goes before it makes the room).
  `RT_CHECK(a_one_primitive, !(tri_valid && quad_valid))
  `RT_CHECK_IF(a_quadric_ready, quad_valid, quadric_req_ready)
  `RT_CHECK_IF(a_quadric_rsp_slot, quad_valid, fetching[quad_slot])
  `RT_CHECK_IF(a_init_setup, init, setup_q[init_slot])
  `RT_CHECK(a_cfg_slots, cfg_slots_i != '0 && cfg_slots_i <= CfgSlotsW'(N))
  `RT_CHECK(a_credit_range, credit_q <= CREDIT_W'(IdxBufDepth))
  `RT_ASSERT_STATIC(g_exit_latency_check, rt_pkg::EXIT_TEST_LATENCY == 1 + 4,
                    "rt_trav_shell: the registered grant and rt_exit_test's 4 stages differ from rt_pkg::EXIT_TEST_LATENCY")
  `RT_ASSERT_STATIC(g_hit_width_check, `RT_WALK_HIT_W == 1 + BEST_W,
                    "rt_trav_shell: a walk record's closest hit is not {hit, the kept record}")
  `RT_ASSERT_STATIC(g_slots_check, N <= 256,
                    "rt_trav_shell: RaysInFlight must lie in 1..256 (the setup carries an 8-bit slot)")
`endif

endmodule
