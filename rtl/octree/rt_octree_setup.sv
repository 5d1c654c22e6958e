// rt_octree_setup: per-ray setup of the parametric octree walk
// (fx::OctreeRaySetup::setup), bit exact.
//
// Multiplications only, in three register stages (OCTREE_SETUP_LATENCY, one
// multiplication deep each; issue #23: the root's parameters and its test once
// followed stage 2 in one cycle) plus the output logic:
//   stage 1  mirror bits a (4, 2, 1 for a negative x, y, z), the mirrored
//            origin o' = 2^P - o on mirrored axes (P+1 bits), |d|, the active
//            axes (d != 0), dominant = max |d|
//   stage 2  pair[a] = product of |d_b| over the other active axes (1 if none),
//            2^P - o'[a]
//   stage 3  common = pair[x] * |d_x| = product of |d| over all active axes
//            (1 if none); the root's plane parameters over the common
//            denominator as products, o'[a] * pair[a] and (2^P - o'[a]) * pair[a]
//   output   T0[a] = -o'[a] * pair[a], T1[a] = (2^P - o'[a]) * pair[a]
//            (inactive axes: -inf / +inf, values 0), and the root test
//            max t0 < min t1 over the active axes (true with none active)
//
// rt_mirror_pairs (with rt_setup_front) carries the ray through the stages and
// computes |d|, the active and negative axes, the dominant, o', the pair
// products and common, as for the BVH's setup.
//
// Latency:    a ray accepted at edge t (valid_i high in the cycle before t) is on
//             valid_o after edge t+2; the slot loads it at edge t+3.
// Throughput: one ray per cycle; the pipeline never stalls (the slot is
//             reserved when the ray is accepted).
module rt_octree_setup #(
  parameter int unsigned SlotW = 5  // width of the slot index carried along
) (
`include "rt_setup_ports.svh"

  output logic [2:0]                             mirror_o,  // a: bit 2 = x
  output logic [2:0]                             active_o,  // bit a = axis a crosses planes
  output logic [3*(rt_pkg::POS_W+1)-1:0]         origin_o,  // o' {z, y, x}
  output logic [3*rt_pkg::OCTREE_T_W-1:0]        t0_o,      // {z, y, x}, signed each
  output logic [3*rt_pkg::OCTREE_T_W-1:0]        t1_o,      // {z, y, x}, signed each
  output logic [rt_pkg::OCTREE_COMMON_W-1:0]     common_o,
  output logic                                   enter_o    // the ray meets the root
);

  localparam int P      = rt_pkg::POS_W;
  localparam int DIR_W  = rt_pkg::DIR_W;
  localparam int MAG_W  = DIR_W - 1;             // |d| <= DIR_MAX < 2^(D-1)
  localparam int PAIR_W = 2 * MAG_W;
  localparam int COM_W  = rt_pkg::OCTREE_COMMON_W;
  localparam int T_W    = rt_pkg::OCTREE_T_W;
  localparam int ORG_W  = P + 1;

  // ---- The shared stages (rt_mirror_pairs): valid, slot and ray, the active
  // and mirrored axes, the dominant, o', the pair products, C ------------------
  logic               s1_valid, s2_valid;
  logic [2:0]         s3_active, s3_neg;
  logic [3*ORG_W-1:0] s1_org, s2_org, s3_org;
  logic [3*PAIR_W-1:0] s2_pair, unused_s3_pair;
  logic [COM_W-1:0]   s3_common;

  // The ray in, and valid, slot, ray and dom out, by name.
  rt_mirror_pairs #(.SlotW(SlotW), .Latency(rt_pkg::OCTREE_SETUP_LATENCY), .ComW(COM_W)) u_pairs (
    .*,
    .s1_valid_o  (s1_valid),
    .s2_valid_o  (s2_valid),
    .active_o    (s3_active),
    .neg_o       (s3_neg),
    .s1_org_o    (s1_org),
    .s2_org_o    (s2_org),
    .s2_pair_o   (s2_pair),
    .s3_org_o    (s3_org),
    .s3_pair_o   (unused_s3_pair),
    .s3_common_o (s3_common)
  );

  // ---- Stage 2: the far plane's distance 2^P - o' --------------------------------
  logic [3*ORG_W-1:0]   s2_org_hi_q;

  // The stage's arithmetic only in the cycles it loads (as in rt_isect: a
  // simulator then evaluates it once per ray, not in every cycle).
  always_ff @(posedge clk_i) begin
    if (s1_valid) begin
      for (int a = 0; a < 3; a++) begin
        s2_org_hi_q[a*ORG_W +: ORG_W] <= (ORG_W'(1) << P) - s1_org[a*ORG_W +: ORG_W];
      end
    end
  end

  // ---- Stage 3: the root's planes as products ---------------------------------
  // |plane - o'| <= 2^P and pair < 2^(2(D-1)): every product fits T_W signed.
  logic [3*T_W-1:0]     s3_low_q;     // o' * pair
  logic [3*T_W-1:0]     s3_high_q;    // (2^P - o') * pair

  always_ff @(posedge clk_i) begin
    if (s2_valid) begin
      for (int a = 0; a < 3; a++) begin
        s3_low_q[a*T_W +: T_W]  <= T_W'(s2_org[a*ORG_W +: ORG_W]) * T_W'(s2_pair[a*PAIR_W +: PAIR_W]);
        s3_high_q[a*T_W +: T_W] <= T_W'(s2_org_hi_q[a*ORG_W +: ORG_W]) * T_W'(s2_pair[a*PAIR_W +: PAIR_W]);
      end
    end
  end

  // ---- Output: the root's plane parameters and the root test ------------------
  logic signed [T_W-1:0] t0 [3];
  logic signed [T_W-1:0] t1 [3];

  always_comb begin
    for (int a = 0; a < 3; a++) begin
      t0[a] = s3_active[a] ? -$signed(s3_low_q[a*T_W +: T_W]) : '0;
      t1[a] = s3_active[a] ? $signed(s3_high_q[a*T_W +: T_W]) : '0;
      t0_o[a*T_W +: T_W] = t0[a];
      t1_o[a*T_W +: T_W] = t1[a];
    end
  end

  // Revelles' root test: the ray meets the root's interior, enter < leave.
  always_comb begin
    enter_o = 1'b1;
    for (int a = 0; a < 3; a++) begin
      for (int b = 0; b < 3; b++) begin
        if (s3_active[a] && s3_active[b] && !(t0[a] < t1[b])) enter_o = 1'b0;
      end
    end
  end

  assign mirror_o = {s3_neg[0], s3_neg[1], s3_neg[2]};
  assign active_o = s3_active;
  assign origin_o = s3_org;
  assign common_o = s3_common;

endmodule
