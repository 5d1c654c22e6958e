// rt_exit_test: does the closest hit lie within the current cell or leaf?
// Both units compare the exit parameter of the region, over the unit's
// per-ray denominator, with the hit's t = t_num / (dominant * det):
//   holds = settled || !(exit * dominant * det < t_num * denominator)
// (rt_grid: exit = the exit accumulator N_exit, denominator = the triple,
// fx::GridDda::holds; rt_octree: exit = min t1 over the active axes, >= 0,
// denominator = common, fx::hitWithin; settled: an any-hit ray that has its
// hit, which holds without the arithmetic). Unsigned operands.
//
// Pipelined, at most one wide multiply a stage: the operands are registered,
// then exit x dominant and t_num x denominator are formed, then the first
// product x det, then the comparison, whose answer leaves a register with the
// test's tag. Every stage loads only with a test in it (enabled flops: a
// simulator skips the wide multiplications in the other cycles), and a
// settled test carries no operands.
//
// Latency: 4 cycles (valid_i in cycle t, valid_o in cycle t+4).
// Throughput: one test per cycle.
module rt_exit_test #(
  parameter int unsigned ExitW = 8,  // width of the exit parameter
  parameter int unsigned DenW  = 8,  // width of the denominator
  parameter int unsigned TagW  = 1   // what travels with a test (the slot)
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  input  logic                         valid_i,
  input  logic [TagW-1:0]              tag_i,
  input  logic                         settled_i,
  input  logic [ExitW-1:0]             exit_i,
  input  logic [rt_pkg::DIR_W-1:0]     dom_i,    // dominant |d|
  input  logic [DenW-1:0]              den_i,
  input  logic [rt_pkg::T_NUM_W-1:0]   t_num_i,  // the closest hit
  input  logic [rt_pkg::DET_ABS_W-1:0] det_i,
  output logic                         valid_o,
  output logic [TagW-1:0]              tag_o,
  output logic                         holds_o
);

  localparam int DIR_W = rt_pkg::DIR_W;
  localparam int DET_W = rt_pkg::DET_ABS_W;
  localparam int TN_W  = rt_pkg::T_NUM_W;
  localparam int XD_W  = ExitW + DIR_W;                  // exit x dominant
  localparam int LHS_W = XD_W + DET_W;                   // ... x det
  localparam int RHS_W = TN_W + DenW;                    // t_num x denominator
  localparam int CHK_W = (LHS_W > RHS_W) ? LHS_W : RHS_W;

  // The valid bits (reset) of the four stages, their tags, and whether the
  // test is settled (stages 1 to 3; stage 4 holds the answer).
  logic [3:0]      v_q;
  logic [TagW-1:0] tag_q [4];
  logic [2:0]      settled_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      v_q <= '0;
    end else begin
      v_q <= {v_q[2:0], valid_i};
    end
  end
  always_ff @(posedge clk_i) begin
    if (valid_i) begin
      tag_q[0]     <= tag_i;
      settled_q[0] <= settled_i;
    end
    for (int s = 1; s < 4; s++) begin
      if (v_q[s-1]) tag_q[s] <= tag_q[s-1];
    end
    for (int s = 1; s < 3; s++) begin
      if (v_q[s-1]) settled_q[s] <= settled_q[s-1];
    end
  end

  // Stage 1: the operands.
  logic [ExitW-1:0] exit_q;
  logic [DIR_W-1:0] dom_q;
  logic [DenW-1:0]  den_q;
  logic [TN_W-1:0]  t_num_q;
  logic [DET_W-1:0] det1_q;
  always_ff @(posedge clk_i) begin
    if (valid_i && !settled_i) begin
      exit_q  <= exit_i;
      dom_q   <= dom_i;
      den_q   <= den_i;
      t_num_q <= t_num_i;
      det1_q  <= det_i;
    end
  end

  // Stage 2: exit x dominant, t_num x denominator.
  logic [XD_W-1:0]  xd_q;
  logic [RHS_W-1:0] rhs2_q;
  logic [DET_W-1:0] det2_q;
  always_ff @(posedge clk_i) begin
    if (v_q[0] && !settled_q[0]) begin
      xd_q   <= XD_W'(exit_q) * XD_W'(dom_q);
      rhs2_q <= RHS_W'(t_num_q) * RHS_W'(den_q);
      det2_q <= det1_q;
    end
  end

  // Stage 3: (exit x dominant) x det.
  logic [LHS_W-1:0] lhs_q;
  logic [RHS_W-1:0] rhs3_q;
  always_ff @(posedge clk_i) begin
    if (v_q[1] && !settled_q[1]) begin
      lhs_q  <= LHS_W'(xd_q) * LHS_W'(det2_q);
      rhs3_q <= rhs2_q;
    end
  end

  // Stage 4: the comparison.
  logic holds_q;
  always_ff @(posedge clk_i) begin
    if (v_q[2]) holds_q <= settled_q[2] || !(CHK_W'(lhs_q) < CHK_W'(rhs3_q));
  end

  assign valid_o = v_q[3];
  assign tag_o   = tag_q[3];
  assign holds_o = holds_q;

endmodule
