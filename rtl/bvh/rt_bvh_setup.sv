// rt_bvh_setup: per-ray setup of the BVH walk (fx::BvhRaySetup::setup), bit
// exact.
//
// Multiplications only, in three register stages (BVH_SETUP_LATENCY, one
// multiplication deep each): rt_mirror_pairs's mirrored origin o', pair
// products and common denominator C, the octree's setup's too.
// rt_setup_front carries the ray through the stages and computes |d|, the
// active axes (d != 0), the negative ones (mirror) and the dominant max |d|.
//
// Latency:    a ray accepted at edge t (valid_i high in the cycle before t) is on
//             valid_o after edge t+2; the slot loads it at edge t+3.
// Throughput: one ray per cycle; the pipeline never stalls (the slot is
//             reserved when the ray is accepted).
module rt_bvh_setup #(
  parameter int unsigned SlotW = 5  // width of the slot index carried along
) (
`include "rt_setup_ports.svh"

  output logic [2:0]                                  mirror_o,  // bit a: axis a mirrored (d < 0)
  output logic [2:0]                                  active_o,  // bit a: axis a crosses planes (d != 0)
  output logic [3*(rt_pkg::POS_W+1)-1:0]              origin_o,  // o' {z, y, x}
  output logic [3*2*(rt_pkg::DIR_W-1)-1:0]            pair_o,    // {z, y, x}, unsigned each
  output logic [rt_pkg::BVH_COMMON_W-1:0]             common_o
);

  localparam int P      = rt_pkg::POS_W;
  localparam int DIR_W  = rt_pkg::DIR_W;
  localparam int MAG_W  = DIR_W - 1;             // |d| <= DIR_MAX < 2^(D-1)
  localparam int PAIR_W = 2 * MAG_W;
  localparam int COM_W  = rt_pkg::BVH_COMMON_W;
  localparam int ORG_W  = P + 1;

  // ---- The shared front ---------------------------------------------------------
  logic [3*DIR_W-1:0] mag;
  logic               s1_valid, s2_valid;
  logic [2:0]         s1_active, unused_s1_neg;

  rt_setup_front #(.SlotW(SlotW), .Latency(rt_pkg::BVH_SETUP_LATENCY)) u_front (
    .*,
    .mag_o       (mag),
    .s1_valid_o  (s1_valid),
    .s1_active_o (s1_active),
    .s1_neg_o    (unused_s1_neg),
    .s2_valid_o  (s2_valid),
    .active_o    (active_o),
    .neg_o       (mirror_o)
  );

  // ---- Stages 1 to 3: o', the pair products, C ----------------------------------
  logic [3*ORG_W-1:0]   unused_s1_org;
  logic [3*PAIR_W-1:0]  s2_pair;
  logic [3*ORG_W-1:0]   unused_s2_org;
  logic [3*ORG_W-1:0]   s3_org;
  logic [COM_W-1:0]     s3_common;

  rt_mirror_pairs #(.ComW(COM_W)) u_pairs (
    .clk_i,
    .valid_i,
    .org_i       (ray_i.org),
    .dir_i       (ray_i.dir),
    .mag_i       (mag),
    .s1_valid_i  (s1_valid),
    .s1_active_i (s1_active),
    .s2_valid_i  (s2_valid),
    .s1_org_o    (unused_s1_org),
    .s2_org_o    (unused_s2_org),
    .s2_pair_o   (s2_pair),
    .s3_org_o    (s3_org),
    .s3_common_o (s3_common)
  );

  // Stage 3 also holds the pair products, which the box tester scales by.
  logic [3*PAIR_W-1:0]  s3_pair_q;

  always_ff @(posedge clk_i) begin
    if (s2_valid) s3_pair_q <= s2_pair;
  end

  assign origin_o = s3_org;
  assign pair_o   = s3_pair_q;
  assign common_o = s3_common;

endmodule
