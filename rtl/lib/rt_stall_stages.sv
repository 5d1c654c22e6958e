// rt_stall_stages: the stage control of a fixed-latency pipeline with
// backpressure (rt_isect, rt_quadric): a valid bit per register stage and the
// ready chain. The pipeline's data registers load under stage_load_o and are
// not reset.
//
//   stage_load_o[s]  register stage s loads a valid item this cycle
//   req_ready_o      stage 0 may load
//   res_valid_o      the last stage holds a result
//
// Stage s may load when some stage at or after it is empty, or the result is
// taken this cycle: the closed form of "the next stage is empty or advancing",
// with no combinational loop through a vector. Bubbles are squeezed out during
// an output stall, and a full pipeline whose result is taken accepts a request
// in the same cycle (II = 1).
//
// With RT_ASSERT_ON it checks both streams: valid and ready never X; an
// offered request stays, unchanged, until taken (the producer's duty; its bits
// on req_data_i); a result not taken stays, unchanged (res_data_i); a full
// pipeline whose result is taken accepts. The data ports feed the checks only.
// (Parameters are `int`: Icarus 11, the second opinion on rt_isect, reads no `int unsigned` one.)
module rt_stall_stages #(
  parameter int Stages = 2,  // register stages, >= 2
  parameter int ReqW   = 1,  // the request's bits (checks only)
  parameter int ResW   = 1   // the result's bits (checks only)
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              req_valid_i,
  output logic              req_ready_o,
  input  logic [ReqW-1:0]   req_data_i,
  output logic              res_valid_o,
  input  logic              res_ready_i,
  input  logic [ResW-1:0]   res_data_i,
  output logic [Stages-1:0] stage_load_o
);

  logic [Stages-1:0] valid_q, valid_in, stage_ready;

  assign valid_in = {valid_q[Stages-2:0], req_valid_i};
  for (genvar s = 0; s < Stages; s++) begin : g_ready
    assign stage_ready[s] = res_ready_i || !(&valid_q[Stages-1:s]);
  end
  assign stage_load_o = valid_in & stage_ready;
  assign req_ready_o  = stage_ready[0];
  assign res_valid_o  = valid_q[Stages-1];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else begin
      valid_q <= (valid_q & ~stage_ready) | stage_load_o;
    end
  end

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  `RT_ASSERT_STATIC(g_stages_check, Stages >= 2, "rt_stall_stages: a pipeline of at least two stages")
  `RT_ASSERT_KNOWN(a_res_valid_known, res_valid_o)
  `RT_ASSERT_KNOWN(a_req_ready_known, req_ready_o)
  `RT_ASSERT_KNOWN(a_req_valid_known, req_valid_i)
  // Checked against copies taken in a stall only: $stable would make a
  // simulator copy the wide records in every evaluation.
  logic            res_stall_q, req_stall_q;
  logic [ResW-1:0] res_held_q;
  logic [ReqW-1:0] req_held_q;
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      res_stall_q <= 1'b0;
      req_stall_q <= 1'b0;
    end else begin
      res_stall_q <= res_valid_o && !res_ready_i;
      req_stall_q <= req_valid_i && !req_ready_o;
      if (res_valid_o && !res_ready_i) res_held_q <= res_data_i;
      if (req_valid_i && !req_ready_o) req_held_q <= req_data_i;
    end
  end
  `RT_CHECK_IF(a_res_hold, res_stall_q, res_valid_o && res_data_i == res_held_q)
  `RT_CHECK_IF(a_req_hold, req_stall_q, req_valid_i && req_data_i == req_held_q)
  `RT_CHECK_IF(a_full_throughput, res_ready_i, req_ready_o)
`else
  logic unused_data;  // the data ports feed the checks only
  assign unused_data = ^{req_data_i, res_data_i};
`endif

endmodule
