// rt_grid: the integer-DDA uniform-grid traversal unit, feeding rt_isect from memory.
//
// Bit-exact with fx::traverseGrid (sw/golden/grid.h): for every ray the same
// cells in the same order, every triangle of every visited cell tested (index
// list order, duplicates across cells included), the closest hit by
// fx::closerResult, and the same stop rule (stop once the closest hit so far
// lies within the current cell, or when the ray leaves the grid).
// docs/grid-unit.md specifies the micro-architecture cycle by cycle.
//
//   u_shell    rt_trav_shell: ray input and slot allocation, the arbiters and
//              FIFOs of every port, the index and triangle path to rt_isect,
//              the per-slot ray and closest hit, the exit test, the counts,
//              the results (the node port reads cells, registered:
//              RegRsp = 1)
//   u_setup    rt_grid_setup: per-ray setup, multiplications only
//              (GRID_SETUP_LATENCY stages)
//   the walk   RaysInFlight ray slots (below): state machines, DDA
//              frontiers, cell queues, the exit accumulators
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
// Latency:    >= 1 + GRID_SETUP_LATENCY (setup) + per cell: cell read (hidden by the prefetch once
//             the ray is under way) + (index and triangle reads + ISECT_LATENCY
//             if the cell holds triangles) + 1 (visit) cycles per ray.
// Throughput: per cycle at most one ray accepted, one cell read (one DDA
//             step), one visit record, one index read, one triangle read, one
//             intersection test, one exit test and one result.
//
// The walk: the ray slots — per-slot state machines, DDA registers and cell
// queues — updated by the unit's events, each addressed to one slot by index.
// The ray, its closest hit, the exit test and the counts are its
// rt_trav_shell's (joined by name: the ports of rt_walk_ports.svh): the slots
// take the exit-test state (bound, and isect_hit: a slot with no hit yet is
// bound after a hit, which becomes its record) and the exit test's answer,
// and give the exit accumulator of the cell.
//
// Slot state machine (docs/grid-unit.md, "Slot state machine"):
//   FREE -alloc-> SETUP -init-> VISIT -visit grant-> WAIT_CELL | FETCH | (cell done)
//   WAIT_CELL -its cell arrives-> FETCH | (cell done)
//   FETCH: one index read per index grant; (cell done) with its last result
//   (cell done): bound (a hit so far, or a segment end) -> CHECK; else the
//                last cell -> DONE; else the next cell -> VISIT
//   CHECK -check grant-> DONE if the bound lies in the cell (or an any-hit ray
//                        has its hit), or it is the last, else the next cell -> VISIT
//   DONE -result grant (no cell read outstanding)-> FREE
//
// Cell prefetch. Each slot reads its cells ahead of the traversal: the DDA
// registers hold the frontier, the next cell not yet requested; while the slot
// has fewer than CellQueue cells requested and not finished, and the frontier
// is in the grid, it asks for a cell read. On the grant the frontier's id
// enters the slot's cell queue; in the next cycle the DDA steps (one shared
// stepper: one grant per cycle) and the entry takes the cell's exit
// accumulator (N of the crossing that leaves it) and whether it is the last
// cell; in the one after, the next step is prepared. A slot thus reads at most
// one cell every three cycles. Responses fill the queue in order. The head of the
// queue is the cell the ray is entering (VISIT) or in; its visit record is
// written only when the ray really enters it, and a cell read past the cell
// where the ray stops is simply dropped. A slot ends only when none of its
// cell reads is outstanding, so a response never meets the slot's next ray.
//
// Storage: one-hot state vectors and thermometer-coded queue counts (N bits
// each, reset), per-slot registers as arrays written by index (no reset;
// written before read). Every update is addressed by an event's slot index, so
// no logic runs per slot per cycle.
//
// Latency: every transition takes one clock edge. Throughput: per cycle one
// allocation, one init, one cell grant (one DDA step), one cell response, one
// visit, one index grant, one isect result, one check grant, one result.
`include "rt_walk_core.svh"
module rt_grid #(
  `RT_WALK_UNIT_PARAMS,
  parameter int unsigned CellQueue    = 2,   // cells per slot read and not finished (power of 2, >= 2)
  parameter int unsigned NodeRspW = rt_pkg::GRID_CELL_W  // derived: a node response's bits
) (
`include "rt_trav_ports.svh"

  // Configuration, static while rays are in flight.
  input  logic [3*rt_pkg::GRID_RESOLUTION_W-1:0] cfg_res_i,    // {Rz, Ry, Rx}, each 1..256

  // One result per ray, one record per cell entered.
  output rt_pkg::grid_res_t                        res_data_o,
  output rt_pkg::grid_visit_t                      visit_data_o
);

  // The figures of the walk's ports toward its shell, and the shell, with
  // the slot core's events and checks (rt_walk_core.svh).
  localparam int unsigned VisitIdW  = 3 * rt_pkg::CELL_INDEX_W;
  localparam int unsigned ExitW     = rt_pkg::GRID_ACC_W;
  localparam int unsigned DenW      = rt_pkg::GRID_TRIPLE_W;
  localparam int unsigned RunPorts  = 2;
  localparam int unsigned WalkPartW = 0;     // walks are not set aside
  localparam int unsigned QW        = (CellQueue > 1) ? $clog2(CellQueue) : 1;
  localparam bit          RegRsp    = 1'b1;  // the shell registers node responses
`define RT_WALK_CORE_BODY
`include "rt_walk_core.svh"

  // ---- The walk ----------------------------------------------------------------------
  localparam int RES_W    = rt_pkg::GRID_RESOLUTION_W;
  localparam int CELL_W   = rt_pkg::CELL_INDEX_W;
  localparam int ID_W     = 3 * CELL_W;
  localparam int ACC_W    = rt_pkg::GRID_ACC_W;
  localparam int PAIR_W   = rt_pkg::GRID_PAIR_W;
  localparam int POS_W    = rt_pkg::POS_W;
  localparam int ADDR_W   = rt_pkg::MEM_ADDR_W;
  localparam int D        = CellQueue;
  localparam int NE       = (2 ** SlotW) * D;   // entries addressed {slot, entry}
  localparam int QW1      = QW + 1;

  // ---- State vectors (bit s = slot s) -------------------------------------------
  logic [N-1:0]   visit_q, wait_q, fetch_q, check_q, done_q;
  logic [N-1:0]   front_q;   // the frontier lies in the grid (cells left to request)
  logic [D*N-1:0] qc_q;      // bit j*N+s: slot s has more than j cells queued
  logic [D*N-1:0] oc_q;      // bit j*N+s: more than j of its cell reads outstanding
  logic [QW*N-1:0] hd_q;     // bit b*N+s: bit b of slot s's queue head entry

  // ---- Per-slot registers (arrays, no reset) ----------------------------------------
  logic [3*CELL_W-1:0] fcell_q [N];   // frontier cell {z, y, x}
  logic [ID_W-1:0]     fid_q   [N];   // frontier cell id
  logic [3*ACC_W-1:0]  facc_q  [N];   // frontier accumulators N[a]
  logic [3*PAIR_W-1:0] pair_q  [N];
  logic [2:0]          act_q   [N];
  logic [2:0]          neg_q   [N];
  logic [31:0]         first_q [N];   // the current cell's (its counters: u_idx_count)
  // Cell queue entries, index {slot, entry}.
  logic [ID_W-1:0]     ecid_q  [NE];  // cell id
  logic [ACC_W-1:0]    eexit_q [NE];  // exit accumulator of the cell
  logic                elast_q [NE];  // the ray leaves the grid after this cell
  logic [31:0]         efirst_q[NE];  // cell table entry, once the response is in
  logic [31:0]         ecount_q[NE];

  // ---- The ray's setup (rt_grid_setup) ---------------------------------------------------
  logic [3*CELL_W-1:0] init_cell, init_cell_id;
  logic [2:0]          init_active, init_neg;
  logic [3*ACC_W-1:0]  init_acc;
  logic [3*PAIR_W-1:0] init_pair;

  rt_grid_setup #(.SlotW(SlotW)) u_setup (
    `RT_WALK_SETUP_PORTS,
    .cfg_res_i,
    .cell_o    (init_cell),
    .cell_id_o (init_cell_id),
    .active_o  (init_active),
    .neg_o     (init_neg),
    .acc_o     (init_acc),
    .pair_o    (init_pair),
    .triple_o  (init_den)
  );

  // The cell read (the shell's node port).
  rt_pkg::grid_cell_t cell_rsp;
  assign cell_rsp = node_data;

  // Registered configuration: the stepper runs at least three cycles after a
  // ray's acceptance, and the configuration is static while rays are in flight.
  logic [3*RES_W-1:0]  cfg_q;
  logic [ID_W-1:0]     stride_y_q, stride_z_q;
  always_ff @(posedge clk_i) begin
    cfg_q      <= cfg_res_i;
    stride_y_q <= ID_W'(cfg_res_i[0 +: RES_W]);
    stride_z_q <= ID_W'(cfg_res_i[0 +: RES_W]) * ID_W'(cfg_res_i[RES_W +: RES_W]);
  end

  // ---- Per-slot lookups in the coded vectors ------------------------------------------
  // Queue count / outstanding reads (thermometer code) and queue head of slot s.
  function automatic logic [QW:0] therm(input logic [D*N-1:0] t, input logic [SlotW-1:0] s);
    therm = '0;
    for (int j = 0; j < D; j++) begin
      if (t[j*N + 32'(s)]) therm = QW1'(j + 1);
    end
  endfunction

  function automatic logic [QW-1:0] head(input logic [QW*N-1:0] h, input logic [SlotW-1:0] s);
    for (int b = 0; b < QW; b++) head[b] = h[b*N + 32'(s)];
  endfunction

  // ---- The frontier's next DDA step, prepared ahead (fx::GridDda::nextAxis/advance) ----
  // Axis = argmin of N over the stepping axes, exact ties to the lowest; the
  // exit accumulator is N[axis]; the ray leaves if the coordinate is 0 stepping
  // down or R-1 stepping up (or no axis steps); else coordinate +-1, cell id
  // +- stride, N[axis] += pair[axis] << P. A slot keeps its next step worked
  // out (step_q): from the setup's values at init, and from the stepped
  // frontier two cycles after a cell grant (prep_q). The grant only queues the
  // frontier's cell; in the next cycle (stepping_q) the frontier moves to the
  // prepared cell, read from step_q at a registered slot index, so neither
  // arithmetic nor a macro read follows the cell arbiter (issue #35: the
  // grant's read of step_q was rt_grid's STA critical path). The slot asks
  // for no cell while it steps and prepares.
  typedef struct packed {
    logic [1:0]        axis;
    logic [ACC_W-1:0]  exit_acc;  // N[axis]: the exit accumulator of the frontier cell
    logic              leaves;    // the ray leaves the grid after the frontier cell
    logic [CELL_W-1:0] coord;     // the next cell's coordinate on axis
    logic [ID_W-1:0]   id;        // the next cell's id
    logic [ACC_W-1:0]  acc;       // N[axis] after the step
  } step_t;
  localparam int STEP_W = 2 + ACC_W + 1 + CELL_W + ID_W + ACC_W;  // (Yosys 0.23 takes no $bits of a type)

  // The next step of a frontier (cell, id, N, pair, axes), by the configuration
  // in cfg_q / stride_*_q.
  function automatic logic [STEP_W-1:0] next_step(input logic [3*CELL_W-1:0] cel, input logic [ID_W-1:0] id,
                                                  input logic [3*ACC_W-1:0] acc, input logic [3*PAIR_W-1:0] pair,
                                                  input logic [2:0] act, input logic [2:0] neg);
    // (Plain vectors: Yosys 0.23 sizes no struct or unpacked array in a function.)
    // Every axis's candidates are formed side by side, and the three
    // comparisons at once; the axis then only selects (issue #23: a chained
    // second comparison and a per-axis test after the selection were this
    // preparation's depth).
    logic [1:0]          axis;
    logic                first_y, lt10, lt20, lt21;
    logic [2:0]          edge_hit;
    logic [3*CELL_W-1:0] next_cel;
    logic [3*ID_W-1:0]   next_id;
    logic [3*ACC_W-1:0]  next_acc;
    logic [CELL_W-1:0]   c;
    logic [ID_W-1:0]     stride;
    for (int a = 0; a < 3; a++) begin
      stride = (a == 0) ? ID_W'(1) : ((a == 1) ? stride_y_q : stride_z_q);
      c      = cel[a*CELL_W +: CELL_W];
      next_id[a*ID_W +: ID_W]       = neg[a] ? id - stride : id + stride;
      next_acc[a*ACC_W +: ACC_W]    = acc[a*ACC_W +: ACC_W] + (ACC_W'(pair[a*PAIR_W +: PAIR_W]) << POS_W);
      next_cel[a*CELL_W +: CELL_W]  = neg[a] ? c - 1'b1 : c + 1'b1;
      edge_hit[a] = neg[a] ? (c == '0) : (RES_W'(c) == cfg_q[a*RES_W +: RES_W] - 1'b1);
    end
    lt10 = acc[ACC_W +: ACC_W] < acc[0 +: ACC_W];
    lt20 = acc[2*ACC_W +: ACC_W] < acc[0 +: ACC_W];
    lt21 = acc[2*ACC_W +: ACC_W] < acc[ACC_W +: ACC_W];
    // Strict < keeps the lowest axis on exact ties, as fx::GridDda::nextAxis().
    first_y = !act[0] || (act[1] && lt10);
    axis    = first_y ? 2'd1 : 2'd0;
    if (act[2] && (first_y ? (!act[1] || lt21) : (!act[0] || lt20))) axis = 2'd2;
    next_step = {axis, acc[axis*ACC_W +: ACC_W], (act == '0) || edge_hit[axis], next_cel[axis*CELL_W +: CELL_W],
                 next_id[axis*ID_W +: ID_W], next_acc[axis*ACC_W +: ACC_W]};
  endfunction

  logic [STEP_W-1:0] step_q [N];  // each slot's next step
  logic              stepping_q;  // a slot was granted a cell in the previous cycle:
  logic [SlotW-1:0]  step_slot_q; // its frontier steps in this one,
  logic [QW-1:0]     step_push_q; // and its new queue entry takes the cell's exit
  logic              prep_q;      // a slot's frontier stepped in the previous cycle:
  logic [SlotW-1:0]  prep_slot_q; // its next step is prepared in this one

  // (stepping_q and prep_q are reset with the state vectors, below.)
  always_ff @(posedge clk_i) begin
    if (node_go) begin
      step_slot_q <= node_slot;
      step_push_q <= g_push;
    end
    if (stepping_q) prep_slot_q <= step_slot_q;
  end

  always_ff @(posedge clk_i) begin : p_step
    if (init) begin
      step_q[init_slot] <= next_step(init_cell, init_cell_id, init_acc, init_pair, init_active,
                                       init_neg);
    end
    if (prep_q) begin
      step_q[prep_slot_q] <= next_step(fcell_q[prep_slot_q], fid_q[prep_slot_q], facc_q[prep_slot_q],
                                       pair_q[prep_slot_q], act_q[prep_slot_q], neg_q[prep_slot_q]);
    end
  end

  // The step of the slot granted a cell in the previous cycle: the prepared
  // one, into the frontier's registers.
  step_t               st;
  logic [ACC_W-1:0]    st_exit;
  logic                st_leaves;
  logic [3*CELL_W-1:0] st_cell;
  logic [3*ACC_W-1:0]  st_acc;
  always_comb begin : b_step
    st      = '0;
    st_cell = '0;
    st_acc  = '0;
    if (stepping_q) begin
      st      = step_q[step_slot_q];
      st_cell = fcell_q[step_slot_q];
      st_acc  = facc_q[step_slot_q];
      st_cell[st.axis*CELL_W +: CELL_W] = st.coord;
      st_acc[st.axis*ACC_W +: ACC_W]    = st.acc;
    end
  end
  assign st_exit   = st.exit_acc;
  assign st_leaves = st.leaves;

  // ---- The exit accumulator of the tested slot's cell (rt_trav_shell tests it) ------
  // The slot stays in CHECK with the same head cell until the answer.
  logic [SlotW-1:0] r_slot;
  logic [QW-1:0]    k_hd;
  logic             hit, holds;
  assign r_slot       = isect_slot;
  assign hit          = isect_hit;
  assign holds        = check_holds;
  assign k_hd         = head(hd_q, check_slot);
  assign check_exit = eexit_q[{check_sel, head(hd_q, check_sel)}];

  // ---- This cycle's events, per slot index --------------------------------------------
  // Cell grant g: the new entry goes behind the queued ones.
  logic [QW-1:0] g_push;
  // Cell response t: it fills the oldest entry still waiting for its data.
  logic [QW:0]   t_cnt, t_out;
  logic [QW-1:0] t_fill;
  // Visit v: the head entry, and whether its data is still outstanding.
  logic [QW:0]   v_cnt, v_out;
  logic [QW-1:0] v_hd;
  logic          v_pending;
  // Starts of a cell (its data is in): at the visit grant, or a WAIT_CELL slot's response.
  logic          stv, stw;
  rt_pkg::grid_cell_t v_data;
  // Cells done (every result in) and what follows: a check, the end, or the next cell.
  logic          cv, cw, cr;
  logic          last_v, last_t, last_r, last_k;
  logic [N-1:0]  check_set, done_set, pop_set, fetch_set;

  always_comb begin
    g_push    = head(hd_q, node_slot) + QW'(therm(qc_q, node_slot));
    t_cnt     = therm(qc_q, node_tag);
    t_out     = therm(oc_q, node_tag);
    t_fill    = head(hd_q, node_tag) + QW'(t_cnt - t_out);
    v_cnt     = therm(qc_q, visit_slot);
    v_out     = therm(oc_q, visit_slot);
    v_hd      = head(hd_q, visit_slot);
    v_pending = (v_cnt == v_out);
    stv       = visit_go && (!v_pending || (node_valid && node_tag == visit_slot));
    stw       = node_valid && wait_q[node_tag];
    v_data    = v_pending ? cell_rsp : {efirst_q[{visit_slot, v_hd}], ecount_q[{visit_slot, v_hd}]};
    cv        = stv && (v_data.count == '0);
    cw        = stw && (cell_rsp.count == '0);
    cr        = res_last;
    last_v    = elast_q[{visit_slot, v_hd}];
    last_t    = elast_q[{node_tag, head(hd_q, node_tag)}];
    last_r    = elast_q[{r_slot, head(hd_q, r_slot)}];
    last_k    = elast_q[{check_slot, k_hd}];

    fetch_set = onehot(stv && !cv, visit_slot) | onehot(stw && !cw, node_tag);
    // Bound (a hit so far, or a segment end): CHECK. None: DONE after the last cell, else the next cell.
    check_set = onehot(cv && bound[visit_slot], visit_slot) |
                onehot(cw && bound[node_tag], node_tag) |
                onehot(cr && (bound[r_slot] || hit), r_slot);
    done_set  = onehot(cv && !bound[visit_slot] && last_v, visit_slot) |
                onehot(cw && !bound[node_tag] && last_t, node_tag) |
                onehot(cr && !(bound[r_slot] || hit) && last_r, r_slot) |
                onehot(check_go && (holds || last_k), check_slot);
    pop_set   = onehot(cv && !bound[visit_slot] && !last_v, visit_slot) |
                onehot(cw && !bound[node_tag] && !last_t, node_tag) |
                onehot(cr && !(bound[r_slot] || hit) && !last_r, r_slot) |
                onehot(check_go && !(holds || last_k), check_slot);
  end

  // ---- State vectors ----------------------------------------------------------------
  // The walk's own (the shell's are the slot core's: rt_walk_core.svh).
  logic [N-1:0] res_oh;
  assign res_oh   = onehot(cr, r_slot);

  // Thermometer counts: +1 where only inc, -1 where only dec.
  logic [N-1:0] q_inc, q_dec, o_inc, o_dec;
  logic [D*N-1:0] qc_d, oc_d;
  assign q_inc = node_oh & ~pop_set;
  assign q_dec = pop_set & ~node_oh;
  assign o_inc = node_oh & ~rsp_oh;
  assign o_dec = rsp_oh & ~node_oh;
  for (genvar j = 0; j < D; j++) begin : g_therm
    logic [N-1:0] q_below, q_above, o_below, o_above;
    assign q_below = (j == 0) ? '1 : qc_q[(j > 0 ? j - 1 : 0)*N +: N];
    assign q_above = (j == D - 1) ? '0 : qc_q[(j < D - 1 ? j + 1 : j)*N +: N];
    assign o_below = (j == 0) ? '1 : oc_q[(j > 0 ? j - 1 : 0)*N +: N];
    assign o_above = (j == D - 1) ? '0 : oc_q[(j < D - 1 ? j + 1 : j)*N +: N];
    assign qc_d[j*N +: N] = ((q_inc & q_below) | (q_dec & q_above) | (~q_inc & ~q_dec & qc_q[j*N +: N]))
                            & ~init_oh;
    assign oc_d[j*N +: N] = (o_inc & o_below) | (o_dec & o_above) | (~o_inc & ~o_dec & oc_q[j*N +: N]);
  end

  // Queue heads: +1 (mod CellQueue) per pop, bit-sliced; 0 at init.
  logic [QW*N-1:0] hd_d;
  always_comb begin : b_head
    logic [N-1:0] carry;
    carry = pop_set;
    for (int b = 0; b < QW; b++) begin
      hd_d[b*N +: N] = (hd_q[b*N +: N] ^ carry) & ~init_oh;
      carry          = carry & hd_q[b*N +: N];
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      visit_q <= '0;
      wait_q  <= '0;
      fetch_q <= '0;
      check_q <= '0;
      done_q  <= '0;
      front_q <= '0;
      qc_q    <= '0;
      oc_q    <= '0;
      hd_q    <= '0;
      stepping_q <= 1'b0;
      prep_q     <= 1'b0;
    end else begin
      stepping_q <= node_go;
      prep_q     <= stepping_q;
      visit_q <= (visit_q & ~visit_oh) | init_oh | pop_set;
      wait_q  <= (wait_q & ~onehot(stw, node_tag)) | (visit_oh & ~onehot(stv, visit_slot));
      fetch_q <= (fetch_q & ~res_oh) | fetch_set;
      check_q <= (check_q & ~check_oh) | check_set;
      done_q  <= (done_q & ~done_oh) | done_set;
      front_q <= (front_q & ~onehot(stepping_q && st_leaves, step_slot_q)) | init_oh;
      qc_q    <= qc_d;
      oc_q    <= oc_d;
      hd_q    <= hd_d;
    end
  end

  // ---- Per-slot registers ---------------------------------------------------------------
  always_ff @(posedge clk_i) begin
    if (init) begin
      fcell_q[init_slot]  <= init_cell;
      fid_q[init_slot]    <= init_cell_id;
      facc_q[init_slot]   <= init_acc;
      pair_q[init_slot]   <= init_pair;
      act_q[init_slot]    <= init_active;
      neg_q[init_slot]    <= init_neg;
    end
    if (node_go) ecid_q[{node_slot, g_push}] <= fid_q[node_slot];
    if (stepping_q) begin
      eexit_q[{step_slot_q, step_push_q}] <= st_exit;
      elast_q[{step_slot_q, step_push_q}] <= st_leaves;
      if (!st_leaves) begin
        fcell_q[step_slot_q] <= st_cell;
        fid_q[step_slot_q]   <= st.id;
        facc_q[step_slot_q]  <= st_acc;
      end
    end
    if (node_valid) begin
      efirst_q[{node_tag, t_fill}] <= cell_rsp.first;
      ecount_q[{node_tag, t_fill}] <= cell_rsp.count;
    end
    if (stv) first_q[visit_slot] <= v_data.first;
    if (stw) first_q[node_tag]   <= cell_rsp.first;
  end

  // ---- Outputs ----------------------------------------------------------------------------
  assign want_node     = (visit_q | wait_q | fetch_q | check_q) & front_q & ~qc_q[(D-1)*N +: N]
                           & ~onehot(stepping_q, step_slot_q) & ~onehot(prep_q, prep_slot_q);  // (stepping, preparing)
  assign want_visit    = visit_q & qc_q[0 +: N];
  assign want_check    = check_q;
  assign want_done     = done_q & ~oc_q[0 +: N];
  assign fetching      = fetch_q;
  assign node_addr     = ADDR_W'(fid_q[node_slot]);
  assign visit_id      = ecid_q[{visit_slot, v_hd}];
  assign idx_addr      = ADDR_W'(first_q[idx_slot] + idx_issued);
  // A cell's triangles are counted when its data is in: at its visit, or at
  // the response a WAIT_CELL slot waits for (two slots in one cycle).
  assign run_start     = {stw, stv};
  assign run_slot      = {node_tag, visit_slot};
  assign run_count     = {cell_rsp.count, v_data.count};

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Events name slots in the right state.
  // Responses: a cell response answers an outstanding read of its slot (the
  // head's, for a slot waiting in WAIT_CELL); results arrive for a slot in
  // FETCH (the shell's u_idx_count checks that it expects them, and the
  // triangles' slots).
  `RT_CHECK_IF(a_cell_rsp_slot, node_valid, t_out != '0)
  `RT_CHECK_IF(a_cell_rsp_head, node_valid && wait_q[node_tag], t_cnt == t_out)
  // The entry whose exit the step writes has no data yet (the response comes
  // through the request FIFO and the registered boundary: two cycles at least),
  // so nothing reads its exit or last flag before the step writes them.
  `RT_CHECK_IF(a_step_before_rsp, stepping_q && node_valid && node_tag == step_slot_q,
               t_fill != step_push_q)
  // No slot is in two of the walk's states (parity catches any slot in two;
  // the shell keeps FREE and SETUP).
  `RT_CHECK(a_states, (visit_q | wait_q | fetch_q | check_q | done_q) ==
                      (visit_q ^ wait_q ^ fetch_q ^ check_q ^ done_q))
  `RT_ASSERT_STATIC(g_queue_check, CellQueue >= 2 && (CellQueue & (CellQueue - 1)) == 0,
                    "rt_grid_slots: CellQueue must be a power of two >= 2")
`endif

endmodule
