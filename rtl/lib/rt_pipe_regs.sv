// rt_pipe_regs: Stages pipeline registers (rt_pipe_reg) in a row, for a
// valid-qualified word that rides beside a pipeline of that depth (a resumed
// walk's record beside the ray's setup). Each word loads only with its valid
// bit, so data_o holds the last word that came through.
//
// Latency: Stages cycles. Throughput: one word per cycle; it never stalls.
module rt_pipe_regs #(
  parameter int unsigned Width  = 1,
  parameter int unsigned Stages = 1   // >= 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  input  logic [Width-1:0] data_i,
  output logic             valid_o,
  output logic [Width-1:0] data_o
);

  logic             valid [Stages + 1];
  logic [Width-1:0] data  [Stages + 1];
  assign valid[0] = valid_i;
  assign data[0]  = data_i;
  for (genvar s = 0; s < Stages; s++) begin : g_stage
    rt_pipe_reg #(.Width(Width)) u_reg (
      .clk_i, .rst_ni, .valid_i(valid[s]), .data_i(data[s]), .valid_o(valid[s+1]), .data_o(data[s+1]));
  end
  assign valid_o = valid[Stages];
  assign data_o  = data[Stages];

endmodule
