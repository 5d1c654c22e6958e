// rt_rr_arb: round-robin arbiter over N requesters.
//
// Grants the first requester at or after the priority pointer, cyclically
// (combinational). When the grant is used (ack_i), the pointer moves to the
// requester after the granted one, so a requester that keeps asking is served
// at least once every N grants. Without ack_i the pointer stays. The grant
// depends only on req_i and the pointer register.
//
// Written as vector operations (mask below the pointer, isolate the lowest set
// bit, encode it with one OR-reduction per index bit) rather than a loop over
// the requesters: the same function, but a few word operations per cycle in a
// simulator.
//
// Latency: 0 cycles (grant in the request cycle). Throughput: one grant per cycle.
module rt_rr_arb #(
  parameter int unsigned N    = 4,
  parameter int unsigned IdxW = (N > 1) ? $clog2(N) : 1  // derived: do not override
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic [N-1:0]    req_i,
  input  logic            ack_i,      // the grant is used this cycle
  output logic            valid_o,    // some requester is granted
  output logic [N-1:0]    gnt_o,      // one-hot grant
  output logic [IdxW-1:0] idx_o       // index of the granted requester
);

  localparam logic [IdxW-1:0] LAST = IdxW'(N - 1);

  logic [IdxW-1:0] ptr_q;
  logic [N-1:0]    below;   // positions before the pointer
  logic [N-1:0]    upper;   // requesters at or after the pointer
  logic [N-1:0]    pick;

  // The lowest requester at or after the pointer, else the lowest overall.
  assign below   = (N'(1) << ptr_q) - N'(1);
  assign upper   = req_i & ~below;
  assign pick    = (upper != '0) ? upper : req_i;
  assign gnt_o   = pick & (~pick + N'(1));
  assign valid_o = (req_i != '0);

  // One-hot to index: bit b of the index is set when the grant lies at a
  // position whose bit b is set.
  for (genvar b = 0; b < IdxW; b++) begin : g_enc
    logic [N-1:0] pos_has_b;
    for (genvar k = 0; k < N; k++) begin : g_pos
      assign pos_has_b[k] = ((k >> b) & 1) == 1;
    end
    assign idx_o[b] = (gnt_o & pos_has_b) != '0;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ptr_q <= '0;
    end else if (ack_i && valid_o) begin
      ptr_q <= (idx_o == LAST) ? '0 : idx_o + 1'b1;
    end
  end

endmodule
