// rt_closest_hit: does a new intersection result replace its ray's closest hit
// so far? fx::closerResult: t1 < t2 as t_num1 * det2 < t_num2 * det1 (the
// parameters t = t_num / (DIR_MAX * det) over positive dets), exact ties to the
// lower prim id; a hit always replaces "no hit yet", a miss never replaces.
//
// Three stages, so that no cycle holds the record's read and a product, nor a
// whole T_NUM_W x DET_ABS_W product and a compare (issue #23; issue #35: the
// read of the 32-slot record file into the products was the traversal units'
// STA critical path):
//   R  (the result's cycle) the result and its slot's record as read in this
//      cycle are registered; the record as the result in stage Y leaves it
//      when that result is of the same slot and taken (write-through: the
//      owner writes the record at the end of this cycle)
//   X  the four half products of each cross product, the det split in halves,
//      against the registered record, and against the result now in stage Y
//      when it is of the same slot (forwarding: that result may become the
//      record at the end of this cycle); registered
//   Y  each difference of cross products as one sum of half products, its sign
//      and zero test; the verdict against the result ahead when it was taken
//      (take_o of the last cycle), else against the record. valid_o, slot_o and
//      the result leave here with take_o, and the owner writes the record in
//      this cycle.
// Between R and Y the slot's record may change only by the two results ahead
// (one result per cycle): the one in Y during R (written through) and the one
// in Y during X (forwarded).
//
// The products load only when they are used (enabled flops: a simulator
// skips the wide multiplications in the other cycles).
//
// Latency: rt_pkg::CLOSEST_HIT_LATENCY (= 2) cycles. Throughput: one
// comparison per cycle, back to back on one slot included.
module rt_closest_hit #(
  parameter int unsigned SlotW    = 5,  // width of the slot index carried along
  parameter int unsigned PayloadW = 1   // the rest of the result, carried along
) (
  input  logic                         clk_i,
  input  logic                         rst_ni,
  // Stage R: a result for slot slot_i,
  input  logic                         valid_i,
  input  logic [SlotW-1:0]             slot_i,
  input  logic                         hit_i,         // a hit,
  input  logic [31:0]                  prim_id_i,     // its triangle,
  input  logic [rt_pkg::T_NUM_W-1:0]   t_num_i,       // its t_num
  input  logic [rt_pkg::DET_ABS_W-1:0] det_i,         // and its det
  input  logic [PayloadW-1:0]          payload_i,
  // and that slot's record as it is in this cycle.
  input  logic                         has_best_i,    // the record holds a hit:
  input  logic [31:0]                  best_prim_i,   // its triangle,
  input  logic [rt_pkg::T_NUM_W-1:0]   best_t_num_i,  // t_num
  input  logic [rt_pkg::DET_ABS_W-1:0] best_det_i,    // and det
  // Stage Y: the result, and whether it becomes the slot's record.
  output logic                         valid_o,
  output logic [SlotW-1:0]             slot_o,
  output logic                         hit_o,         // the result is a hit
  output logic                         take_o,
  output logic [31:0]                  prim_id_o,
  output logic [rt_pkg::T_NUM_W-1:0]   t_num_o,
  output logic [rt_pkg::DET_ABS_W-1:0] det_o,
  output logic [PayloadW-1:0]          payload_o
);

  localparam int T_W   = rt_pkg::T_NUM_W;
  localparam int D_W   = rt_pkg::DET_ABS_W;
  localparam int LO_W  = D_W / 2;          // a det's low half
  localparam int HI_W  = D_W - LO_W;       // and its high half
  localparam int PLO_W = T_W + LO_W;
  localparam int PHI_W = T_W + HI_W;
  localparam int DIF_W = T_W + D_W + 1;    // a difference of cross products, signed

  // ---- Stage R ---------------------------------------------------------------
  // The result, and its slot's record as the end of this cycle leaves it.
  logic                valid_x, hit_x;
  logic [SlotW-1:0]    slot_x;
  logic [31:0]         prim_x;
  logic [T_W-1:0]      t_num_x;
  logic [D_W-1:0]      det_x;
  logic [PayloadW-1:0] payload_x;
  logic                write_through;
  logic                has_best_x;
  logic [31:0]         best_prim_x;
  logic [T_W-1:0]      best_t_num_x;
  logic [D_W-1:0]      best_det_x;

  rt_pipe_reg #(.Width(SlotW + 1 + 32 + T_W + D_W + PayloadW)) u_result_x (
    .clk_i, .rst_ni, .valid_i,
    .data_i ({slot_i, hit_i, prim_id_i, t_num_i, det_i, payload_i}),
    .valid_o(valid_x),
    .data_o ({slot_x, hit_x, prim_x, t_num_x, det_x, payload_x}));

  assign write_through = take_o && slot_o == slot_i;
  always_ff @(posedge clk_i) begin
    if (valid_i) begin
      has_best_x   <= has_best_i || write_through;
      best_prim_x  <= write_through ? prim_id_o : best_prim_i;
      best_t_num_x <= write_through ? t_num_o   : best_t_num_i;
      best_det_x   <= write_through ? det_o     : best_det_i;
    end
  end

  // ---- Stage X ---------------------------------------------------------------
  // Two comparisons: REC against the slot's record, AHEAD against the result
  // now in stage Y when it is a hit of the same slot.
  localparam int REC = 0, AHEAD = 1;
  logic       same_slot, has_best_q, same_slot_q;
  logic [1:0] use_cmp, closer;  // per comparison

  assign same_slot         = valid_o && slot_o == slot_x && hit_o;
  assign use_cmp[REC]      = valid_x && hit_x && has_best_x;
  assign use_cmp[AHEAD]    = valid_x && hit_x && same_slot;

  rt_pipe_reg #(.Width(SlotW + 1 + 32 + T_W + D_W + PayloadW)) u_result (
    .clk_i, .rst_ni,
    .valid_i(valid_x),
    .data_i ({slot_x, hit_x, prim_x, t_num_x, det_x, payload_x}),
    .valid_o,
    .data_o ({slot_o, hit_o, prim_id_o, t_num_o, det_o, payload_o}));

  always_ff @(posedge clk_i) begin
    if (valid_x) begin
      has_best_q  <= has_best_x;
      same_slot_q <= same_slot;
    end
  end

  for (genvar c = 0; c < 2; c++) begin : g_cmp
    logic [T_W-1:0]   old_t;    // the hit compared with
    logic [D_W-1:0]   old_det;
    logic [31:0]      old_prim;
    // new.t * old.det and old.t * new.det, each as {t * det.lo, t * det.hi}.
    logic [PLO_W-1:0] new_lo_q, old_lo_q;
    logic [PHI_W-1:0] new_hi_q, old_hi_q;
    logic             prim_lt_q;
    logic [DIF_W-1:0] dif;  // (stage Y) new.t * old.det - old.t * new.det

    assign old_t    = (c == REC) ? best_t_num_x : t_num_o;
    assign old_det  = (c == REC) ? best_det_x   : det_o;
    assign old_prim = (c == REC) ? best_prim_x  : prim_id_o;

    always_ff @(posedge clk_i) begin
      if (use_cmp[c]) begin
        new_lo_q  <= PLO_W'(t_num_x) * PLO_W'(old_det[LO_W-1:0]);
        new_hi_q  <= PHI_W'(t_num_x) * PHI_W'(old_det[D_W-1:LO_W]);
        old_lo_q  <= PLO_W'(old_t) * PLO_W'(det_x[LO_W-1:0]);
        old_hi_q  <= PHI_W'(old_t) * PHI_W'(det_x[D_W-1:LO_W]);
        prim_lt_q <= prim_x < old_prim;
      end
    end

    assign dif       = DIF_W'(new_lo_q) + (DIF_W'(new_hi_q) << LO_W) - DIF_W'(old_lo_q) - (DIF_W'(old_hi_q) << LO_W);
    assign closer[c] = dif[DIF_W-1] || (dif == '0 && prim_lt_q);
  end

  // ---- Stage Y ---------------------------------------------------------------
  logic ahead_took_q;  // the result ahead of this one became the record

  always_comb begin
    take_o = 1'b0;
    if (valid_o && hit_o) begin
      if (same_slot_q && ahead_took_q) take_o = closer[AHEAD];
      else if (has_best_q)             take_o = closer[REC];
      else                             take_o = 1'b1;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) ahead_took_q <= 1'b0;
    else         ahead_took_q <= take_o;
  end

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  `RT_ASSERT_STATIC(g_latency_check, rt_pkg::CLOSEST_HIT_LATENCY == 2,
                    "rt_closest_hit: its stages differ from rt_pkg::CLOSEST_HIT_LATENCY")
`endif

endmodule
