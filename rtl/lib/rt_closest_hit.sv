// rt_closest_hit: does a new intersection result replace a ray's closest hit
// so far? fx::closerResult: t1 < t2 as t_num1 * det2 < t_num2 * det1 (the
// parameters t = t_num / (DIR_MAX * det) over positive dets), exact ties to the
// lower prim id; a hit always replaces "no hit yet", a miss never replaces.
//
// The products are formed only when a hit meets a record that holds one (a
// simulator then skips the wide multiplications in the other cycles).
//
// Latency: 0 cycles (combinational). Throughput: one comparison per cycle.
module rt_closest_hit (
  input  logic                         valid_i,       // a result is offered this cycle
  input  logic                         hit_i,         // the new result: a hit,
  input  logic [31:0]                  prim_id_i,     // its triangle,
  input  logic [rt_pkg::T_NUM_W-1:0]   t_num_i,       // its t_num
  input  logic [rt_pkg::DET_ABS_W-1:0] det_i,         // and its det
  input  logic                         has_best_i,    // the record holds a hit:
  input  logic [31:0]                  best_prim_i,   // its triangle,
  input  logic [rt_pkg::T_NUM_W-1:0]   best_t_num_i,  // t_num
  input  logic [rt_pkg::DET_ABS_W-1:0] best_det_i,    // and det
  output logic                         take_o         // the new result becomes the record
);

  localparam int CLO_W = rt_pkg::T_NUM_W + rt_pkg::DET_ABS_W;

  always_comb begin
    logic [CLO_W-1:0] clo_new, clo_old;
    clo_new = '0;
    clo_old = '0;
    take_o  = 1'b0;
    if (valid_i && hit_i) begin
      if (!has_best_i) begin
        take_o = 1'b1;
      end else begin
        clo_new = CLO_W'(t_num_i) * CLO_W'(best_det_i);
        clo_old = CLO_W'(best_t_num_i) * CLO_W'(det_i);
        take_o  = clo_new < clo_old || (clo_new == clo_old && prim_id_i < best_prim_i);
      end
    end
  end

endmodule
