// rt_mirror_pairs: the arithmetic the setups of the parametric walks share
// (rt_octree_setup, rt_bvh_setup; fx::MirroredRay in golden/lattice.h), beside
// rt_setup_front's stages, one multiplication deep each:
//   stage 1  the mirrored origin o' = 2^P - o on axes with a negative
//            component, o elsewhere (P+1 bits)
//   stage 2  pair[a] = product of |d_b| over the other active axes (1 if none)
//   stage 3  the common denominator C = pair[x] * |d_x| = product of |d| over
//            the active axes (1 if none), and o' carried along
// Each stage loads only in the cycle a ray passes (valid_i, s1_valid_i,
// s2_valid_i: rt_setup_front's), as the unit's own stage arithmetic does.
module rt_mirror_pairs #(
  parameter int unsigned ComW = 64  // the unit's rt_pkg::<UNIT>_COMMON_W
) (
  input  logic                                      clk_i,

  input  logic                                      valid_i,      // stage 1 loads the ray's
  input  logic [3*rt_pkg::POS_W-1:0]                org_i,        // origin {z, y, x}
  input  logic [3*rt_pkg::DIR_W-1:0]                dir_i,        // direction {z, y, x}
  input  logic [3*rt_pkg::DIR_W-1:0]                mag_i,        // and its |d| (rt_setup_front's mag_o)

  input  logic                                      s1_valid_i,   // stage 2 loads
  input  logic [2:0]                                s1_active_i,
  input  logic                                      s2_valid_i,   // stage 3 loads

  output logic [3*(rt_pkg::POS_W+1)-1:0]            s1_org_o,     // o' {z, y, x} in stage 1
  output logic [3*(rt_pkg::POS_W+1)-1:0]            s2_org_o,     // in stage 2
  output logic [3*2*(rt_pkg::DIR_W-1)-1:0]          s2_pair_o,    // pair {z, y, x} in stage 2
  output logic [3*(rt_pkg::POS_W+1)-1:0]            s3_org_o,     // in stage 3
  output logic [ComW-1:0]                           s3_common_o   // C in stage 3
);

  localparam int P      = rt_pkg::POS_W;
  localparam int DIR_W  = rt_pkg::DIR_W;
  localparam int MAG_W  = DIR_W - 1;             // |d| <= DIR_MAX < 2^(D-1)
  localparam int PAIR_W = 2 * MAG_W;
  localparam int ORG_W  = P + 1;

  // ---- Stage 1: |d| and the mirrored origin ------------------------------------
  logic [3*MAG_W-1:0] s1_mag_q;

  always_ff @(posedge clk_i) begin
    if (valid_i) begin
      for (int a = 0; a < 3; a++) begin
        logic [DIR_W-1:0] d;
        logic [ORG_W-1:0] o;
        d = dir_i[a*DIR_W +: DIR_W];
        o = ORG_W'(org_i[a*P +: P]);
        s1_mag_q[a*MAG_W +: MAG_W] <= mag_i[a*DIR_W +: MAG_W];
        s1_org_o[a*ORG_W +: ORG_W] <= d[DIR_W-1] ? (ORG_W'(1) << P) - o : o;
      end
    end
  end

  // ---- Stage 2: the pair products -----------------------------------------------
  logic [MAG_W-1:0] s2_mx_q;  // |d_x|, 1 if x is inactive

  always_ff @(posedge clk_i) begin
    if (s1_valid_i) begin
      logic [MAG_W-1:0] m [3];  // |d| masked to 1 on inactive axes
      for (int a = 0; a < 3; a++) begin
        m[a] = s1_active_i[a] ? s1_mag_q[a*MAG_W +: MAG_W] : MAG_W'(1);
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
    if (s2_valid_i) begin
      s3_org_o    <= s2_org_o;
      s3_common_o <= ComW'(s2_pair_o[0*PAIR_W +: PAIR_W]) * ComW'(s2_mx_q);
    end
  end

endmodule
