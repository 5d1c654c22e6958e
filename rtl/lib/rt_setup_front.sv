// rt_setup_front: what the per-ray setups of every traversal unit share
// (rt_grid_setup; rt_mirror_pairs, the octree's and the BVH's): the
// three-stage pipeline that carries the ray and its slot, and the direction's
// arithmetic of stage 1, |d[a]|, the active axes (d[a] != 0), the negative
// ones and the dominant max |d[a]|.
//
// The unit's own stage arithmetic sits beside it, one multiplication deep per
// stage: stage 1 loads with valid_i (from ray_i and mag_o), stage 2 with
// s1_valid_o (from the unit's stage-1 registers and s1_active_o /
// s1_neg_o), stage 3 with s2_valid_o. Every stage's word loads only in the
// cycle a ray passes (enabled flops; stages 2 and 3 are rt_pipe_regs).
//
// Latency:    a ray accepted at edge t (valid_i high in the cycle before t) is
//             on valid_o after edge t+2; the slot loads it at edge t+3.
// Throughput: one ray per cycle; the pipeline never stalls (the slot is
//             reserved when the ray is accepted).
module rt_setup_front #(
  parameter int unsigned SlotW   = 5,  // width of the slot index carried along
  parameter int unsigned Latency = 3   // the unit's rt_pkg::<UNIT>_SETUP_LATENCY, checked against the stages here
) (
`include "rt_setup_ports.svh"

  output logic [3*rt_pkg::DIR_W-1:0] mag_o,        // |d| of ray_i {z, y, x}, for stage 1

  output logic                       s1_valid_o,   // stage 1 holds a ray
  output logic [2:0]                 s1_active_o,  // its axes with d != 0
  output logic [2:0]                 s1_neg_o,     // its axes with d < 0
  output logic                       s2_valid_o,   // stage 2 holds a ray

  output logic [2:0]                 active_o,     // stage 3's
  output logic [2:0]                 neg_o
);

  localparam int DIR_W = rt_pkg::DIR_W;

  // (Each component as a variable of its own: Yosys 0.23 reads no bit of an
  // element of a struct's packed array.)
  always_comb begin
    logic [DIR_W-1:0] d;
    for (int a = 0; a < 3; a++) begin
      d = ray_i.dir[a];
      mag_o[a*DIR_W +: DIR_W] = d[DIR_W-1] ? DIR_W'(-d) : d;
    end
  end

  // ---- Every stage: the ray, its slot and its direction's figures ----------------------
  // (The ray as plain bits: Yosys 0.23 reads no package type inside a struct.)
  typedef struct packed {
    logic [SlotW-1:0]               slot;
    logic [rt_pkg::ISECT_RAY_W-1:0] ray;
    logic [2:0]                     active;
    logic [2:0]                     neg;
    logic [DIR_W-1:0]               dom;
  } stage_t;
  localparam int STAGE_W = SlotW + rt_pkg::ISECT_RAY_W + 6 + DIR_W;  // (Yosys 0.23 takes no $bits of a type)

  stage_t s1_q, s2_q, s3_q;

  // Stage 1: the valid bit and the slot in an rt_pipe_reg; the ray and its
  // figures worked out inside an enabled flop rather than in an always_comb
  // feeding the register (the same gates): a simulator then evaluates them for
  // each ray that passes, not at every change of ray_i. (Plain variables:
  // Yosys 0.23 writes no bit of a struct's field.)
  logic [SlotW-1:0]                              s1_slot;
  logic [rt_pkg::ISECT_RAY_W + 6 + DIR_W - 1:0] s1_rest_q;  // {ray, active, neg, dom}
  rt_pipe_reg #(.Width(SlotW)) u_stage1 (
    .clk_i,
    .rst_ni,
    .valid_i,
    .data_i  (slot_i),
    .valid_o (s1_valid_o),
    .data_o  (s1_slot)
  );
  assign s1_q = {s1_slot, s1_rest_q};

  always_ff @(posedge clk_i) begin
    if (valid_i) begin : b_stage1
      logic [DIR_W-1:0] d, mag, dom;
      logic [2:0]       active, neg;
      dom = '0;
      for (int a = 0; a < 3; a++) begin
        d         = ray_i.dir[a];
        mag       = mag_o[a*DIR_W +: DIR_W];
        active[a] = (d != '0);
        neg[a]    = d[DIR_W-1];
        if (mag > dom) dom = mag;
      end
      s1_rest_q <= {ray_i, active, neg, dom};
    end
  end

  rt_pipe_reg #(.Width(STAGE_W)) u_stage2 (
    .clk_i,
    .rst_ni,
    .valid_i (s1_valid_o),
    .data_i  (s1_q),
    .valid_o (s2_valid_o),
    .data_o  (s2_q)
  );

  rt_pipe_reg #(.Width(STAGE_W)) u_stage3 (
    .clk_i,
    .rst_ni,
    .valid_i (s2_valid_o),
    .data_i  (s2_q),
    .valid_o,
    .data_o  (s3_q)
  );

  assign s1_active_o = s1_q.active;
  assign s1_neg_o    = s1_q.neg;
  assign {slot_o, ray_o, active_o, neg_o, dom_o} = s3_q;

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  `RT_ASSERT_STATIC(g_setup_latency_check, Latency == 3,
                    "rt_setup_front: its three stages differ from the unit's rt_pkg::<UNIT>_SETUP_LATENCY")
`endif

endmodule
