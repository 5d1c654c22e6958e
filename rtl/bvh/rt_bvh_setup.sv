// rt_bvh_setup: per-ray setup of the BVH walk (fx::BvhRaySetup::setup), bit
// exact.
//
// Multiplications only, in three register stages (BVH_SETUP_LATENCY, one
// multiplication deep each):
//   stage 1  the mirrored origin o' = 2^P - o on axes with a negative
//            component (P+1 bits), |d|
//   stage 2  pair[a] = product of |d_b| over the other active axes (1 if none)
//   stage 3  the common denominator C = pair[x] * |d_x| = product of |d| over
//            the active axes (1 if none)
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

  // ---- Stage 1: |d| and the mirrored origin ------------------------------------
  logic [3*MAG_W-1:0]   s1_mag_q;
  logic [3*ORG_W-1:0]   s1_org_q;

  always_ff @(posedge clk_i) begin
    if (valid_i) begin
      for (int a = 0; a < 3; a++) begin
        logic [DIR_W-1:0] d;
        logic [ORG_W-1:0] o;
        d = ray_i.dir[a];
        o = ORG_W'(ray_i.org[a]);
        s1_mag_q[a*MAG_W +: MAG_W] <= mag[a*DIR_W +: MAG_W];
        s1_org_q[a*ORG_W +: ORG_W] <= d[DIR_W-1] ? (ORG_W'(1) << P) - o : o;
      end
    end
  end

  // ---- Stage 2: the pair products -----------------------------------------------
  logic [3*ORG_W-1:0]   s2_org_q;
  logic [3*PAIR_W-1:0]  s2_pair_q;
  logic [MAG_W-1:0]     s2_mx_q;      // |d_x|, 1 if x is inactive

  always_ff @(posedge clk_i) begin
    if (s1_valid) begin
      logic [MAG_W-1:0]  m [3];       // |d| masked to 1 on inactive axes
      for (int a = 0; a < 3; a++) begin
        m[a] = s1_active[a] ? s1_mag_q[a*MAG_W +: MAG_W] : MAG_W'(1);
      end
      s2_pair_q[0*PAIR_W +: PAIR_W] <= PAIR_W'(m[1]) * PAIR_W'(m[2]);
      s2_pair_q[1*PAIR_W +: PAIR_W] <= PAIR_W'(m[0]) * PAIR_W'(m[2]);
      s2_pair_q[2*PAIR_W +: PAIR_W] <= PAIR_W'(m[0]) * PAIR_W'(m[1]);
      s2_mx_q  <= m[0];
      s2_org_q <= s1_org_q;
    end
  end

  // ---- Stage 3: the common denominator -----------------------------------------
  logic [3*ORG_W-1:0]   s3_org_q;
  logic [3*PAIR_W-1:0]  s3_pair_q;
  logic [COM_W-1:0]     s3_common_q;

  always_ff @(posedge clk_i) begin
    if (s2_valid) begin
      s3_org_q    <= s2_org_q;
      s3_pair_q   <= s2_pair_q;
      s3_common_q <= COM_W'(s2_pair_q[0*PAIR_W +: PAIR_W]) * COM_W'(s2_mx_q);
    end
  end

  assign origin_o = s3_org_q;
  assign pair_o   = s3_pair_q;
  assign common_o = s3_common_q;

endmodule
