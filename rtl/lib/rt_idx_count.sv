// rt_idx_count: each ray slot's counters of its current triangle list (a grid
// cell, an octree leaf): how many triangles it lists, how many index reads are
// issued and how many intersection results are in. A start loads the count and
// clears both counters; an index grant and a result each count one.
//
// The registers have no reset: a slot's counters are read only after its
// start. Starts apply in port order (a later one wins); events of one cycle
// name different slots.
//
// Latency: 0 cycles from the registers to the outputs; every update takes one
// clock edge. Throughput: per cycle Starts starts, one index grant, one result.
module rt_idx_count #(
  parameter int unsigned N      = 32,                       // ray slots
  parameter int unsigned Starts = 1,                        // start ports
  parameter int unsigned SlotW  = (N > 1) ? $clog2(N) : 1   // derived
) (
  input  logic                    clk_i,
  input  logic                    rst_ni,              // assertions only

  input  logic [Starts-1:0]       start_i,             // a slot enters a list of
  input  logic [Starts*SlotW-1:0] start_slot_i,
  input  logic [Starts*32-1:0]    start_count_i,       // this many triangles

  input  logic                    idx_go_i,            // an index read is granted
  input  logic [SlotW-1:0]        idx_slot_i,
  output logic [31:0]             idx_issued_o,        // reads issued before it
  output logic                    idx_last_o,          // it is the list's last

  input  logic                    res_valid_i,         // a result comes in
  input  logic [SlotW-1:0]        res_slot_i,
  output logic                    res_last_o           // it completes the list
);

  logic [31:0] count_q [N], issued_q [N], received_q [N];

  always_ff @(posedge clk_i) begin
    for (int p = 0; p < Starts; p++) begin
      if (start_i[p]) begin
        count_q[start_slot_i[p*SlotW +: SlotW]]    <= start_count_i[p*32 +: 32];
        issued_q[start_slot_i[p*SlotW +: SlotW]]   <= '0;
        received_q[start_slot_i[p*SlotW +: SlotW]] <= '0;
      end
    end
    if (idx_go_i) issued_q[idx_slot_i] <= issued_q[idx_slot_i] + 1'b1;
    if (res_valid_i) received_q[res_slot_i] <= received_q[res_slot_i] + 1'b1;
  end

  assign idx_issued_o = issued_q[idx_slot_i];
  assign idx_last_o   = idx_go_i && (issued_q[idx_slot_i] + 1'b1 == count_q[idx_slot_i]);
  assign res_last_o   = res_valid_i && (received_q[res_slot_i] + 1'b1 == count_q[res_slot_i]);

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  // A result answers an index read (fewer results in than reads issued).
  `RT_CHECK_IF(a_res_expected, res_valid_i, received_q[res_slot_i] != issued_q[res_slot_i])
`endif

endmodule
