// rt_rr_arb: round-robin arbiter over N requesters.
//
// Grants the first requester at or after the priority pointer, cyclically
// (combinational). When the grant is used (ack_i), the pointer moves to the
// requester after the granted one, so a requester that keeps asking is served
// at least once every N grants. Without ack_i the pointer stays. The grant
// depends only on req_i and the pointer register.
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
  logic [N-1:0]    upper;  // requesters at or after the pointer

  always_comb begin
    for (int k = 0; k < N; k++) begin
      upper[k] = req_i[k] && (IdxW'(k) >= ptr_q);
    end
  end

  // The lowest requester at or after the pointer, else the lowest overall.
  always_comb begin
    valid_o = 1'b0;
    idx_o   = '0;
    for (int k = N - 1; k >= 0; k--) begin
      if (req_i[k]) begin
        valid_o = 1'b1;
        idx_o   = IdxW'(k);
      end
    end
    for (int k = N - 1; k >= 0; k--) begin
      if (upper[k]) idx_o = IdxW'(k);
    end
  end

  always_comb begin
    gnt_o = '0;
    gnt_o[idx_o] = valid_o;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      ptr_q <= '0;
    end else if (ack_i && valid_o) begin
      ptr_q <= (idx_o == LAST) ? '0 : idx_o + 1'b1;
    end
  end

endmodule
