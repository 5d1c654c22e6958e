// rt_mirror_pairs: the per-ray setup the parametric walks share (rt_octree's
// and rt_bvh's; fx::MirroredRay in golden/lattice.h): rt_setup_front's three
// stages, which carry the ray and give |d|, the active and negative axes and
// the dominant, and beside them, one multiplication deep each:
//   stage 1  the mirrored origin o' = 2^P - o on axes with a negative
//            component, o elsewhere (P+1 bits)
//   stage 2  pair[a] = product of |d_b| over the other active axes (1 if none)
//   stage 3  the common denominator C = pair[x] * |d_x| = product of |d| over
//            the active axes (1 if none); o' and the pairs carried along
// Each stage loads only in the cycle a ray passes. A unit's own stage
// arithmetic (the octree's root parameters) loads with s1_valid_o and
// s2_valid_o from the stage outputs.
//
// Latency:    a ray accepted at edge t (valid_i high in the cycle before t) is on
//             valid_o after edge t+2; the slot loads it at edge t+3.
// Throughput: one ray per cycle; the pipeline never stalls (the slot is
//             reserved when the ray is accepted).
module rt_mirror_pairs #(
  parameter int unsigned SlotW   = 5,   // width of the slot index carried along
  parameter int unsigned Latency = 3,   // the unit's rt_pkg::<UNIT>_SETUP_LATENCY (checked by rt_setup_front)
  parameter int unsigned ComW    = 64   // the unit's rt_pkg::<UNIT>_COMMON_W
) (
`include "rt_setup_ports.svh"

  output logic                                      s1_valid_o,   // stage 2 loads
  output logic                                      s2_valid_o,   // stage 3 loads
  output logic [2:0]                                active_o,     // stage 3's axes with d != 0
  output logic [2:0]                                neg_o,        // and with d < 0 (the mirrored ones)
  output logic [3*(rt_pkg::POS_W+1)-1:0]            s1_org_o,     // o' {z, y, x} in stage 1
  output logic [3*(rt_pkg::POS_W+1)-1:0]            s2_org_o,     // in stage 2
  output logic [3*2*(rt_pkg::DIR_W-1)-1:0]          s2_pair_o,    // pair {z, y, x} in stage 2
  output logic [3*(rt_pkg::POS_W+1)-1:0]            s3_org_o,     // in stage 3
  output logic [3*2*(rt_pkg::DIR_W-1)-1:0]          s3_pair_o,    // in stage 3
  output logic [ComW-1:0]                           s3_common_o   // C in stage 3
);

  localparam int P      = rt_pkg::POS_W;
  localparam int DIR_W  = rt_pkg::DIR_W;
  localparam int MAG_W  = DIR_W - 1;             // |d| <= DIR_MAX < 2^(D-1)
  localparam int PAIR_W = 2 * MAG_W;
  localparam int ORG_W  = P + 1;

  // ---- The stages: valid, slot and ray, |d|, the active and negative axes ------
  logic [3*DIR_W-1:0] mag;
  logic [2:0]         s1_active, unused_s1_neg;

  rt_setup_front #(.SlotW(SlotW), .Latency(Latency)) u_front (
    .*,
    .mag_o       (mag),
    .s1_active_o (s1_active),
    .s1_neg_o    (unused_s1_neg)
  );

  // ---- Stage 1: |d| and the mirrored origin ------------------------------------
  logic [3*MAG_W-1:0] s1_mag_q;

  always_ff @(posedge clk_i) begin
    if (valid_i) begin
      for (int a = 0; a < 3; a++) begin
        logic [DIR_W-1:0] d;
        logic [P-1:0]     op;
        logic [ORG_W-1:0] o;
        d  = ray_i.dir[a];
        op = ray_i.org[a];
        o  = ORG_W'(op);
        s1_mag_q[a*MAG_W +: MAG_W] <= mag[a*DIR_W +: MAG_W];
        s1_org_o[a*ORG_W +: ORG_W] <= d[DIR_W-1] ? (ORG_W'(1) << P) - o : o;
      end
    end
  end

  // ---- Stage 2: the pair products -----------------------------------------------
  logic [MAG_W-1:0] s2_mx_q;  // |d_x|, 1 if x is inactive

  always_ff @(posedge clk_i) begin
    if (s1_valid_o) begin
      logic [MAG_W-1:0] m [3];  // |d| masked to 1 on inactive axes
      for (int a = 0; a < 3; a++) begin
        m[a] = s1_active[a] ? s1_mag_q[a*MAG_W +: MAG_W] : MAG_W'(1);
      end
      s2_pair_o[0*PAIR_W +: PAIR_W] <= PAIR_W'(m[1]) * PAIR_W'(m[2]);
      s2_pair_o[1*PAIR_W +: PAIR_W] <= PAIR_W'(m[0]) * PAIR_W'(m[2]);
      s2_pair_o[2*PAIR_W +: PAIR_W] <= PAIR_W'(m[0]) * PAIR_W'(m[1]);
      s2_mx_q  <= m[0];
      s2_org_o <= s1_org_o;
    end
  end

  // ---- Stage 3: the common denominator -----------------------------------------
  always_ff @(posedge clk_i) begin
    if (s2_valid_o) begin
      s3_org_o    <= s2_org_o;
      s3_pair_o   <= s2_pair_o;
      s3_common_o <= ComW'(s2_pair_o[0*PAIR_W +: PAIR_W]) * ComW'(s2_mx_q);
    end
  end

endmodule
