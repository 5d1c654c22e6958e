// rt_rr_arb: round-robin arbiter over N requesters.
//
// Grants the first requester at or after the priority pointer, cyclically
// (combinational). When the grant is used (ack_i), the pointer moves to the
// requester after the granted one, so a requester that keeps asking is served
// at least once every N grants. Without ack_i the pointer stays. The grant
// depends only on req_i and the pointer register.
//
// Written as vector operations (mask what was served, isolate the lowest set
// bit, encode it with one OR-reduction per index bit) rather than a loop over
// the requesters: the same function, but a few word operations per cycle in a
// simulator. The pointer is kept as the mask it implies (served_q: the
// positions up to the last grant), and the lowest requester is isolated in the
// masked and the whole request vector side by side, so the grant is one
// isolation and a select deep (issue #23: the arbiters lead the paths that
// start at a grant).
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

  logic [N-1:0] served_q;  // positions at or before the last used grant
  logic [N-1:0] upper;     // requesters after it
  logic [N-1:0] gnt_upper, gnt_any;

  // The lowest requester after the last grant, else the lowest overall.
  assign upper     = req_i & ~served_q;
  assign gnt_upper = upper & (~upper + N'(1));
  assign gnt_any   = req_i & (~req_i + N'(1));
  assign gnt_o     = (upper != '0) ? gnt_upper : gnt_any;
  assign valid_o   = (req_i != '0);

  // One-hot to index: bit b of the index is set when the grant lies at a
  // position whose bit b is set.
  for (genvar b = 0; b < IdxW; b++) begin : g_enc
    logic [N-1:0] pos_has_b;
    for (genvar k = 0; k < N; k++) begin : g_pos
      assign pos_has_b[k] = ((k >> b) & 1) == 1;
    end
    assign idx_o[b] = (gnt_o & pos_has_b) != '0;
  end

  // After the last position every requester counts as "after" again (the
  // mask is all ones, upper is empty): the pointer wrapped to 0.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      served_q <= '0;
    end else if (ack_i && valid_o) begin
      served_q <= gnt_o | (gnt_o - N'(1));
    end
  end

endmodule
