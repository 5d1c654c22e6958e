// rt_grid_slot: the state of one ray in flight in rt_grid, and its DDA step.
//
// State machine (docs/grid-unit.md, "Slot state machine"):
//   FREE  -alloc_i->  SETUP  -init_i->  VISIT  -visit_gnt_i->  WAIT_CELL
//   WAIT_CELL -cell_rsp_i-> FETCH (count > 0) | CHECK (count = 0)
//   FETCH: one index request per idx_gnt_i; -> CHECK once every result is in
//   CHECK without a hit: steps on its own (no arbitration) -> VISIT | DONE
//   CHECK with a hit: waits for check_gnt_i; holds -> DONE, else steps
//   DONE -done_gnt_i-> FREE
// A step (fx::GridDda::advance) is additions and comparisons only: the axis
// with the smallest accumulator among the stepping axes (ties to the lowest),
// its cell coordinate +-1, its accumulator + pair << P, the cell id + stride.
// Leaving the grid on that axis ends the ray (DONE).
//
// Latency: every transition takes one clock edge. Throughput: one cell per
// slot per (memory round trips + 3) cycles; the slots work concurrently.
module rt_grid_slot (
  input  logic                                   clk_i,
  input  logic                                   rst_ni,
  input  logic [3*rt_pkg::GRID_RESOLUTION_W-1:0] cfg_res_i,     // {Rz, Ry, Rx}
  input  logic [3*rt_pkg::CELL_INDEX_W-1:0]      stride_x_i,    // 1
  input  logic [3*rt_pkg::CELL_INDEX_W-1:0]      stride_y_i,    // Rx
  input  logic [3*rt_pkg::CELL_INDEX_W-1:0]      stride_z_i,    // Rx * Ry

  // Allocation (a ray was accepted for this slot) and setup results.
  input  logic                                   alloc_i,
  input  logic                                   init_i,
  input  rt_pkg::isect_ray_t                     init_ray_i,
  input  logic [3*rt_pkg::CELL_INDEX_W-1:0]      init_cell_i,
  input  logic [3*rt_pkg::CELL_INDEX_W-1:0]      init_cell_id_i,
  input  logic [2:0]                             init_active_i,
  input  logic [2:0]                             init_neg_i,
  input  logic [3*rt_pkg::GRID_ACC_W-1:0]        init_acc_i,
  input  logic [3*rt_pkg::GRID_PAIR_W-1:0]       init_pair_i,
  input  logic [rt_pkg::GRID_TRIPLE_W-1:0]       init_triple_i,
  input  logic [rt_pkg::DIR_W-1:0]               init_dom_i,

  // Grants and responses addressed to this slot.
  input  logic                                   visit_gnt_i,
  input  logic                                   cell_rsp_i,
  input  rt_pkg::grid_cell_t                     cell_rsp_data_i,
  input  logic                                   idx_gnt_i,
  input  logic                                   res_i,         // an isect result of this ray
  input  logic                                   res_take_i,    // ... and it is the new closest
  input  rt_pkg::isect_res_t                     res_data_i,
  input  logic                                   check_gnt_i,
  input  logic                                   check_holds_i,
  input  logic                                   done_gnt_i,

  // Requests and state.
  output logic                                   free_o,
  output logic                                   want_visit_o,
  output logic                                   want_idx_o,
  output logic                                   want_check_o,
  output logic                                   want_done_o,
  output logic                                   fetching_o,    // in FETCH (results may arrive)
  output logic                                   waiting_cell_o,
  output rt_pkg::isect_ray_t                     ray_o,
  output logic [3*rt_pkg::CELL_INDEX_W-1:0]      cell_id_o,
  output logic [31:0]                            idx_addr_o,    // first + issued
  output logic [rt_pkg::GRID_ACC_W-1:0]          exit_acc_o,    // N of the next crossing
  output logic [rt_pkg::GRID_TRIPLE_W-1:0]       triple_o,
  output logic [rt_pkg::DIR_W-1:0]               dom_o,
  output logic                                   has_hit_o,
  output rt_pkg::isect_res_t                     best_o,
  output logic [31:0]                            cells_o,
  output logic [31:0]                            tests_o
);

  localparam int RES_W  = rt_pkg::GRID_RESOLUTION_W;
  localparam int CELL_W = rt_pkg::CELL_INDEX_W;
  localparam int ID_W   = 3 * CELL_W;
  localparam int ACC_W  = rt_pkg::GRID_ACC_W;
  localparam int PAIR_W = rt_pkg::GRID_PAIR_W;
  localparam int POS_W  = rt_pkg::POS_W;

  typedef enum logic [2:0] {
    FREE      = 3'd0,
    SETUP     = 3'd1,
    VISIT     = 3'd2,
    WAIT_CELL = 3'd3,
    FETCH     = 3'd4,
    CHECK     = 3'd5,
    DONE      = 3'd6
  } slot_state_e;

  slot_state_e        state_q, state_d;
  rt_pkg::isect_ray_t ray_q;
  logic [3*CELL_W-1:0] cell_q, cell_d;
  logic [ID_W-1:0]    cell_id_q, cell_id_d;
  logic [2:0]         active_q, neg_q;
  logic [3*ACC_W-1:0] acc_q, acc_d;
  logic [3*PAIR_W-1:0] pair_q;
  logic [rt_pkg::GRID_TRIPLE_W-1:0] triple_q;
  logic [rt_pkg::DIR_W-1:0] dom_q;
  logic [31:0]        first_q, count_q, issued_q, received_q;
  logic [31:0]        cells_q, tests_q;
  logic               has_hit_q;
  rt_pkg::isect_res_t best_q;

  // ---- The DDA step: next axis, exit accumulator, next cell ------------------
  logic [1:0]       axis;       // argmin of acc over the stepping axes
  logic             any_active;
  logic             leaves;     // the step leaves the grid
  logic [ACC_W-1:0] acc_x, acc_y, acc_z, exit_acc;

  assign acc_x = acc_q[0 +: ACC_W];
  assign acc_y = acc_q[ACC_W +: ACC_W];
  assign acc_z = acc_q[2*ACC_W +: ACC_W];
  assign any_active = |active_q;

  // Strict < keeps the lowest axis on exact ties, as fx::GridDda::nextAxis().
  always_comb begin
    axis = 2'd0;
    exit_acc = acc_x;
    if (!active_q[0] || (active_q[1] && acc_y < acc_x)) begin
      axis = 2'd1;
      exit_acc = acc_y;
    end
    if (!active_q[axis] || (active_q[2] && acc_z < exit_acc)) begin
      if (active_q[2]) begin
        axis = 2'd2;
        exit_acc = acc_z;
      end
    end
  end

  logic [CELL_W-1:0] coord;
  logic [RES_W-1:0]  res_a;
  logic [ID_W-1:0]   stride_a;
  always_comb begin
    coord    = cell_q[axis*CELL_W +: CELL_W];
    res_a    = cfg_res_i[axis*RES_W +: RES_W];
    stride_a = (axis == 2'd0) ? stride_x_i : ((axis == 2'd1) ? stride_y_i : stride_z_i);
    leaves   = !any_active || (neg_q[axis] ? (coord == '0) : (RES_W'(coord) == res_a - 1'b1));
    cell_d   = cell_q;
    cell_d[axis*CELL_W +: CELL_W] = neg_q[axis] ? coord - 1'b1 : coord + 1'b1;
    cell_id_d = neg_q[axis] ? cell_id_q - stride_a : cell_id_q + stride_a;
    acc_d    = acc_q;
    acc_d[axis*ACC_W +: ACC_W] = exit_acc + (ACC_W'(pair_q[axis*PAIR_W +: PAIR_W]) << POS_W);
  end

  // A CHECK that ends in a step this cycle, and one that ends the ray.
  logic check_step, check_stop;
  always_comb begin
    check_step = 1'b0;
    check_stop = 1'b0;
    if (state_q == CHECK) begin
      if (!has_hit_q) begin
        check_step = !leaves;
        check_stop = leaves;
      end else if (check_gnt_i) begin
        check_step = !check_holds_i && !leaves;
        check_stop = check_holds_i || leaves;
      end
    end
  end

  // ---- Next state -------------------------------------------------------------
  always_comb begin
    state_d = state_q;
    unique case (state_q)
      FREE:      if (alloc_i) state_d = SETUP;
      SETUP:     if (init_i) state_d = VISIT;
      VISIT:     if (visit_gnt_i) state_d = WAIT_CELL;
      WAIT_CELL: if (cell_rsp_i) state_d = (cell_rsp_data_i.count == '0) ? CHECK : FETCH;
      FETCH:     if (received_q == count_q) state_d = CHECK;
      CHECK:     begin
                   if (check_step) state_d = VISIT;
                   if (check_stop) state_d = DONE;
                 end
      DONE:      if (done_gnt_i) state_d = FREE;
      default:   state_d = FREE;
    endcase
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= FREE;
    end else begin
      state_q <= state_d;
    end
  end

  // Datapath registers: no reset, each written before it is read.
  always_ff @(posedge clk_i) begin
    if (init_i) begin
      ray_q      <= init_ray_i;
      cell_q     <= init_cell_i;
      cell_id_q  <= init_cell_id_i;
      active_q   <= init_active_i;
      neg_q      <= init_neg_i;
      acc_q      <= init_acc_i;
      pair_q     <= init_pair_i;
      triple_q   <= init_triple_i;
      dom_q      <= init_dom_i;
      cells_q    <= '0;
      tests_q    <= '0;
      has_hit_q  <= 1'b0;
      best_q     <= '0;
    end
    if (check_step) begin
      cell_q    <= cell_d;
      cell_id_q <= cell_id_d;
      acc_q     <= acc_d;
    end
    if (visit_gnt_i) cells_q <= cells_q + 1'b1;
    if (state_q == WAIT_CELL && cell_rsp_i) begin
      first_q    <= cell_rsp_data_i.first;
      count_q    <= cell_rsp_data_i.count;
      tests_q    <= tests_q + cell_rsp_data_i.count;
      issued_q   <= '0;
      received_q <= '0;
    end
    if (idx_gnt_i) issued_q <= issued_q + 1'b1;
    if (res_i) received_q <= received_q + 1'b1;
    if (res_i && res_take_i) begin
      has_hit_q <= 1'b1;
      best_q    <= res_data_i;
    end
  end

  assign free_o         = (state_q == FREE);
  assign want_visit_o   = (state_q == VISIT);
  assign want_idx_o     = (state_q == FETCH) && (issued_q != count_q);
  assign want_check_o   = (state_q == CHECK) && has_hit_q;
  assign want_done_o    = (state_q == DONE);
  assign fetching_o     = (state_q == FETCH);
  assign waiting_cell_o = (state_q == WAIT_CELL);
  assign ray_o          = ray_q;
  assign cell_id_o      = cell_id_q;
  assign idx_addr_o     = first_q + issued_q;
  assign exit_acc_o     = exit_acc;
  assign triple_o       = triple_q;
  assign dom_o          = dom_q;
  assign has_hit_o      = has_hit_q;
  assign best_o         = best_q;
  assign cells_o        = cells_q;
  assign tests_o        = tests_q;

`ifdef RT_ASSERT_ON
  a_alloc_free : assert property (@(posedge clk_i) disable iff (!rst_ni) alloc_i |-> state_q == FREE);
  a_init_setup : assert property (@(posedge clk_i) disable iff (!rst_ni) init_i |-> state_q == SETUP);
  a_cell_wait  : assert property (@(posedge clk_i) disable iff (!rst_ni) cell_rsp_i |-> state_q == WAIT_CELL);
  a_res_fetch  : assert property (@(posedge clk_i) disable iff (!rst_ni)
      res_i |-> state_q == FETCH && received_q != issued_q);
  a_idx_fetch  : assert property (@(posedge clk_i) disable iff (!rst_ni) idx_gnt_i |-> want_idx_o);
`endif

endmodule
