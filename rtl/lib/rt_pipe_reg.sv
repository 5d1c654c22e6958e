// rt_pipe_reg: one pipeline register for a valid-qualified word. The valid bit
// has the asynchronous reset; the word has none and loads only with valid_i
// (enabled flops: a simulator copies it only in a cycle a word passes), so
// data_o holds the last word that passed.
//
// Latency: 1 cycle. Throughput: one word per cycle; it never stalls.
module rt_pipe_reg #(
  parameter int unsigned Width = 1
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             valid_i,
  input  logic [Width-1:0] data_i,
  output logic             valid_o,
  output logic [Width-1:0] data_o
);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_o <= 1'b0;
    end else begin
      valid_o <= valid_i;
    end
  end

  always_ff @(posedge clk_i) begin
    if (valid_i) data_o <= data_i;
  end

endmodule
