// rt_exit_test: does the closest hit lie within the current cell or leaf?
// Both units compare the exit parameter of the region, over the unit's
// per-ray denominator, with the hit's t = t_num / (dominant * det):
//   holds = !(exit * dominant * det < t_num * denominator)
// (rt_grid: exit = the exit accumulator N_exit, denominator = the triple,
// fx::GridDda::holds; rt_octree: exit = min t1 over the active axes, >= 0,
// denominator = common, fx::hitWithin). Unsigned operands.
//
// Formed only in a cycle with valid_i (a simulator then skips the wide
// multiplications in the other cycles); holds_o is 0 otherwise.
//
// Latency: 0 cycles (combinational). Throughput: one test per cycle.
module rt_exit_test #(
  parameter int unsigned ExitW = 8,  // width of the exit parameter
  parameter int unsigned DenW  = 8   // width of the denominator
) (
  input  logic                        valid_i,
  input  logic [ExitW-1:0]            exit_i,
  input  logic [rt_pkg::DIR_W-1:0]    dom_i,    // dominant |d|
  input  logic [DenW-1:0]             den_i,
  input  logic [rt_pkg::T_NUM_W-1:0]  t_num_i,  // the closest hit
  input  logic [rt_pkg::DET_ABS_W-1:0] det_i,
  output logic                        holds_o
);

  localparam int LHS_W = ExitW + rt_pkg::DIR_W + rt_pkg::DET_ABS_W;
  localparam int RHS_W = rt_pkg::T_NUM_W + DenW;
  localparam int CHK_W = (LHS_W > RHS_W) ? LHS_W : RHS_W;

  always_comb begin
    logic [CHK_W-1:0] lhs, rhs;
    lhs     = '0;
    rhs     = '0;
    holds_o = 1'b0;
    if (valid_i) begin
      lhs     = CHK_W'(exit_i) * CHK_W'(dom_i) * CHK_W'(det_i);
      rhs     = CHK_W'(t_num_i) * CHK_W'(den_i);
      holds_o = !(lhs < rhs);
    end
  end

endmodule
