// rt_grid_setup: per-ray setup of the integer DDA (fx::GridDda::setup), bit exact.
//
// Multiplications only, in three register stages (GRID_SETUP_LATENCY), one
// multiplication deep each (issue #23: stage 2 once chained two):
//   stage 1  X[a] = o[a] * R[a] (scaled origin), |D[a]| = |d[a]| * R[a],
//            step direction and activity, dominant = max |d[a]|
//   stage 2  cell[a] = min(X[a] >> P, R[a]-1), dist[a] to the next boundary,
//            pair[a] = product of the other stepping axes' |D| (1 if none),
//            z * Ry + y
//   stage 3  acc[a] = dist[a] * pair[a], triple = pair[x] * |D[x]| (x
//            stepping), cell id = (z * Ry + y) * Rx + x
// The outputs are the stage-3 registers; rt_setup_front carries the ray and
// computes |d|, the step directions and the dominant. A ray with no stepping
// axis (all-zero direction) gets active = 0; the slot then ends it after its
// first cell.
//
// Each stage computes in the block that loads its registers (local variables
// of an always_ff, i.e. the combinational logic in front of enabled flops), so
// a simulator evaluates the arithmetic only in the cycle a ray passes.
//
// Latency:    a ray accepted at edge t (valid_i high in the cycle before t) is on
//             valid_o after edge t+2; the slot loads it at edge t+3.
// Throughput: one ray per cycle; the pipeline never stalls (the slot is
//             reserved when the ray is accepted).
module rt_grid_setup #(
  parameter int unsigned SlotW = 5  // width of the slot index carried along
) (
`include "rt_setup_ports.svh"

  input  logic [3*rt_pkg::GRID_RESOLUTION_W-1:0] cfg_res_i,     // {Rz, Ry, Rx}
  output logic [3*rt_pkg::CELL_INDEX_W-1:0]      cell_o,        // {z, y, x}
  output logic [3*rt_pkg::CELL_INDEX_W-1:0]      cell_id_o,
  output logic [2:0]                             active_o,      // axis steps
  output logic [2:0]                             neg_o,         // axis steps by -1
  output logic [3*rt_pkg::GRID_ACC_W-1:0]        acc_o,         // {z, y, x}
  output logic [3*rt_pkg::GRID_PAIR_W-1:0]       pair_o,        // {z, y, x}
  output logic [rt_pkg::GRID_TRIPLE_W-1:0]       triple_o
);

  localparam int POS_W    = rt_pkg::POS_W;
  localparam int DIR_W    = rt_pkg::DIR_W;
  localparam int RES_W    = rt_pkg::GRID_RESOLUTION_W;
  localparam int CELL_W   = rt_pkg::CELL_INDEX_W;
  localparam int GPOS_W   = rt_pkg::GRID_POS_W;
  localparam int GDIR_W   = rt_pkg::GRID_DIR_W;
  localparam int PAIR_W   = rt_pkg::GRID_PAIR_W;
  localparam int TRIPLE_W = rt_pkg::GRID_TRIPLE_W;
  localparam int ACC_W    = rt_pkg::GRID_ACC_W;
  localparam int DIST_W   = POS_W + 1;
  localparam int ID_W     = 3 * CELL_W;

  // ---- The shared front: valid, slot and ray through both stages, |d|,
  // activity, step direction, dominant ---------------------------------------------
  logic [3*DIR_W-1:0] mag;
  logic               s1_valid, s2_valid;
  logic [2:0]         s1_active, s1_neg;

  // The ray in, and valid, slot, ray, active, neg and dom out, by name.
  rt_setup_front #(.SlotW(SlotW), .Latency(rt_pkg::GRID_SETUP_LATENCY)) u_front (
    .*,
    .mag_o       (mag),
    .s1_valid_o  (s1_valid),
    .s1_active_o (s1_active),
    .s1_neg_o    (s1_neg),
    .s2_valid_o  (s2_valid)
  );

  // ---- Stage 1: scaled origin and direction ------------------------------------
  logic [3*GPOS_W-1:0]  s1_x_q;
  logic [3*GDIR_W-1:0]  s1_absd_q;

  always_ff @(posedge clk_i) begin
    if (valid_i) begin : b_stage1
      logic [RES_W-1:0] r;
      for (int a = 0; a < 3; a++) begin
        r = cfg_res_i[a*RES_W +: RES_W];
        s1_x_q[a*GPOS_W +: GPOS_W]    <= GPOS_W'(ray_i.org[a]) * GPOS_W'(r);
        s1_absd_q[a*GDIR_W +: GDIR_W] <= GDIR_W'(mag[a*DIR_W +: DIR_W]) * GDIR_W'(r);
      end
    end
  end

  // ---- Stage 2 ---------------------------------------------------------------
  logic [3*CELL_W-1:0]  s2_cell_q;
  logic [ID_W-1:0]      s2_zy_q;   // z * Ry + y
  logic [3*DIST_W-1:0]  s2_dist_q;
  logic [3*PAIR_W-1:0]  s2_pair_q;
  logic [GDIR_W-1:0]    s2_mx_q;   // |D[x]|, 1 if x does not step

  always_ff @(posedge clk_i) begin
    if (s1_valid) begin : b_stage2
      logic [3*GDIR_W-1:0] m;     // |D| masked to 1 on axes that do not step
      logic [3*CELL_W-1:0] cel;
      logic [GPOS_W-1:0]   xs, lower;
      logic [RES_W-1:0]    r, c;
      for (int a = 0; a < 3; a++) begin
        m[a*GDIR_W +: GDIR_W] = s1_active[a] ? s1_absd_q[a*GDIR_W +: GDIR_W] : GDIR_W'(1);
      end
      s2_pair_q[0*PAIR_W +: PAIR_W] <= PAIR_W'(m[1*GDIR_W +: GDIR_W]) * PAIR_W'(m[2*GDIR_W +: GDIR_W]);
      s2_pair_q[1*PAIR_W +: PAIR_W] <= PAIR_W'(m[0*GDIR_W +: GDIR_W]) * PAIR_W'(m[2*GDIR_W +: GDIR_W]);
      s2_pair_q[2*PAIR_W +: PAIR_W] <= PAIR_W'(m[0*GDIR_W +: GDIR_W]) * PAIR_W'(m[1*GDIR_W +: GDIR_W]);
      s2_mx_q <= m[0 +: GDIR_W];
      for (int a = 0; a < 3; a++) begin
        xs = s1_x_q[a*GPOS_W +: GPOS_W];
        r  = cfg_res_i[a*RES_W +: RES_W];
        c  = RES_W'(xs >> POS_W);
        if (c > r - 1'b1) c = r - 1'b1;
        cel[a*CELL_W +: CELL_W] = CELL_W'(c);
        lower = GPOS_W'(c) << POS_W;
        // Distance to the boundary crossed next: upper - X stepping up, else X - lower.
        if (s1_active[a] && !s1_neg[a]) begin
          s2_dist_q[a*DIST_W +: DIST_W] <= DIST_W'(lower + (GPOS_W'(1) << POS_W) - xs);
        end else begin
          s2_dist_q[a*DIST_W +: DIST_W] <= DIST_W'(xs - lower);
        end
      end
      s2_cell_q    <= cel;
      s2_zy_q      <= ID_W'(cel[2*CELL_W +: CELL_W]) * ID_W'(cfg_res_i[RES_W +: RES_W]) + ID_W'(cel[CELL_W +: CELL_W]);
    end
  end

  // ---- Stage 3 ---------------------------------------------------------------
  logic [3*CELL_W-1:0]  s3_cell_q;
  logic [ID_W-1:0]      s3_cell_id_q;
  logic [3*ACC_W-1:0]   s3_acc_q;
  logic [3*PAIR_W-1:0]  s3_pair_q;
  logic [TRIPLE_W-1:0]  s3_triple_q;

  always_ff @(posedge clk_i) begin
    if (s2_valid) begin
      for (int a = 0; a < 3; a++) begin
        s3_acc_q[a*ACC_W +: ACC_W] <= ACC_W'(s2_dist_q[a*DIST_W +: DIST_W]) * ACC_W'(s2_pair_q[a*PAIR_W +: PAIR_W]);
      end
      s3_cell_q    <= s2_cell_q;
      s3_cell_id_q <= s2_zy_q * ID_W'(cfg_res_i[0 +: RES_W]) + ID_W'(s2_cell_q[0 +: CELL_W]);
      s3_pair_q    <= s2_pair_q;
      s3_triple_q  <= TRIPLE_W'(s2_pair_q[0 +: PAIR_W]) * TRIPLE_W'(s2_mx_q);
    end
  end

  assign cell_o    = s3_cell_q;
  assign cell_id_o = s3_cell_id_q;
  assign acc_o     = s3_acc_q;
  assign pair_o    = s3_pair_q;
  assign triple_o  = s3_triple_q;

endmodule
