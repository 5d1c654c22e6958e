// rt_fifo: synchronous FIFO with valid/ready on both sides.
//
// Depth entries of Width bits in a register array. in_ready_o = !full and
// out_valid_o = !empty come straight from the occupancy register, so neither
// depends on the other side's valid or ready; out_data_o is the head entry and
// holds while out_valid_o && !out_ready_i. A full FIFO does not accept a push
// in the cycle it is popped (no combinational ready path).
//
// Latency:    an item pushed at edge t is on out_valid_o after edge t (1 cycle).
// Throughput: one push and one pop per cycle; Depth >= 2 sustains one item per
//             cycle through the FIFO.
module rt_fifo #(
  parameter int unsigned Width = 8,
  parameter int unsigned Depth = 2
) (
  input  logic             clk_i,
  input  logic             rst_ni,

  input  logic             in_valid_i,
  output logic             in_ready_o,
  input  logic [Width-1:0] in_data_i,

  output logic             out_valid_o,
  input  logic             out_ready_i,
  output logic [Width-1:0] out_data_o
);

  localparam int PTR_W = (Depth > 1) ? $clog2(Depth) : 1;
  localparam int CNT_W = $clog2(Depth + 1);
  localparam logic [PTR_W-1:0] LAST = PTR_W'(Depth - 1);
  localparam logic [CNT_W-1:0] FULL = CNT_W'(Depth);

  logic [Width-1:0] mem_q [Depth];
  logic [PTR_W-1:0] wr_ptr_q, rd_ptr_q;
  logic [CNT_W-1:0] count_q;
  logic             in_fire, out_fire;

  assign in_ready_o  = (count_q != FULL);
  assign out_valid_o = (count_q != '0);
  assign out_data_o  = mem_q[rd_ptr_q];
  assign in_fire     = in_valid_i && in_ready_o;
  assign out_fire    = out_valid_o && out_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_ptr_q <= '0;
      rd_ptr_q <= '0;
      count_q  <= '0;
    end else begin
      if (in_fire) wr_ptr_q <= (wr_ptr_q == LAST) ? '0 : wr_ptr_q + 1'b1;
      if (out_fire) rd_ptr_q <= (rd_ptr_q == LAST) ? '0 : rd_ptr_q + 1'b1;
      if (in_fire && !out_fire) begin
        count_q <= count_q + 1'b1;
      end else if (out_fire && !in_fire) begin
        count_q <= count_q - 1'b1;
      end
    end
  end

  // The storage has no reset: an entry is read only after it is written.
  always_ff @(posedge clk_i) begin
    if (in_fire) mem_q[wr_ptr_q] <= in_data_i;
  end

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // Output stream: valid never drops and data holds until taken. The data is
  // mem_q[rd_ptr_q], so it holds when the read pointer does and no write lands
  // on the head entry while it is valid: checked on the pointers, so that a
  // simulator samples no data word in every evaluation.
  `RT_ASSERT(a_out_hold, out_valid_o && !out_ready_i |=> out_valid_o && $stable(rd_ptr_q))
  `RT_CHECK_IF(a_head_kept, in_fire && out_valid_o, wr_ptr_q != rd_ptr_q)
  `RT_CHECK(a_count_range, count_q <= FULL)
`endif

endmodule
