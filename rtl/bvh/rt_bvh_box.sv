// rt_bvh_box: the ray-box tests of a BVH node's two children (fx::boxTest),
// side by side, exact over the lattice planes, pipelined.
//
// Per child c and axis a, with the node's frame (base, shift) and the child's
// plane steps (q_lo, q_hi) from the node record, and the ray's mirrored origin
// o', mirror bits, active axes and pair products (read by the response's slot):
//   stage 1 (cycle r, registered at its end)
//            planes lo = base + (q_lo << shift), hi = base + (q_hi << shift);
//            on a mirrored axis [lo, hi] becomes [2^P - hi, 2^P - lo]; less o'
//            (signed, |plane' - o'| < 2^(P+1)); on an inactive axis whether o'
//            lies in [lo, hi]
//   stage 2 (r+1) the twelve products T = (plane' - o') * pair[a]
//   stage 3 (r+2) per child max T0 and min T1 over the active axes (two
//            levels of comparison each)
//   stage 4 (r+3) the hit (max T0 <= min T1, min T1 > 0, o' inside on every
//            inactive axis), the entry max(max T0, 0), the order near = (both
//            hit and entry1 < entry0); stages 3 and 4 were one until synthesis
//            put the unit's longest path there (66 gates, issue #25)
// The answer leaves registers in cycle r + BVH_BOX_LATENCY with the slot and
// the two child references.
//
// Every stage loads only with a node in it (enabled flops).
//
// Latency:    BVH_BOX_LATENCY = 4 cycles (valid_i in r, valid_o in r+4).
// Throughput: one node per cycle.
module rt_bvh_box #(
  parameter int unsigned SlotW = 5
) (
  input  logic                                  clk_i,
  input  logic                                  rst_ni,

  input  logic                                  valid_i,
  input  logic [SlotW-1:0]                      slot_i,
  input  logic [rt_pkg::BVH_NODE_W-1:0]         node_i,     // bvh_node_t as plain bits
  input  logic [3*(rt_pkg::POS_W+1)-1:0]        origin_i,   // the slot's o' {z, y, x}
  input  logic [2:0]                            mirror_i,   // bit a: axis a mirrored
  input  logic [2:0]                            active_i,   // bit a: axis a crosses planes
  input  logic [3*2*(rt_pkg::DIR_W-1)-1:0]      pair_i,     // {z, y, x}

  output logic                                  valid_o,
  output logic [SlotW-1:0]                      slot_o,
  output logic [1:0]                            hit_o,      // bit c: the ray enters child c
  output logic [2*rt_pkg::BVH_ENTRY_W-1:0]      entry_o,    // {entry1, entry0}
  output logic                                  near_o,     // both hit: child 1 is the nearer
  output logic [2*rt_pkg::BVH_REF_W-1:0]        child_o     // {ref1, ref0}, bvh_ref_t as plain bits
);

  localparam int P       = rt_pkg::POS_W;
  localparam int PAIR_W  = 2 * (rt_pkg::DIR_W - 1);
  localparam int ORG_W   = P + 1;
  localparam int PLANE_W = rt_pkg::BVH_PLANE_W;
  localparam int SHIFT_W = rt_pkg::BVH_SHIFT_W;
  localparam int COUNT_W = rt_pkg::BVH_COUNT_W;
  localparam int T_W     = rt_pkg::BVH_T_W;
  localparam int ENTRY_W = rt_pkg::BVH_ENTRY_W;
  localparam int REF_W   = rt_pkg::BVH_REF_W;
  localparam int PL_W    = P + 2;          // a reconstructed plane, [0, 2^P + 2^shift)
  localparam int DIFF_W  = P + 3;          // plane' - o', signed

  // bvh_node_t's fields as bit offsets (element 0 least significant; the
  // record's fields, last one least significant: Yosys 0.23 reads no element of
  // a struct's packed array).
  localparam int OFF_FIRST = 0;
  localparam int OFF_COUNT = OFF_FIRST + 2 * 32;
  localparam int OFF_LEAF  = OFF_COUNT + 2 * COUNT_W;
  localparam int OFF_HI    = OFF_LEAF + 2;
  localparam int OFF_LO    = OFF_HI + 6 * PLANE_W;
  localparam int OFF_SHIFT = OFF_LO + 6 * PLANE_W;
  localparam int OFF_BASE  = OFF_SHIFT + 3 * SHIFT_W;

  // ---- Stage 1: the planes, mirrored, less the origin --------------------------------
  logic                    v1_q;
  logic [SlotW-1:0]        slot1_q;
  logic [12*DIFF_W-1:0]    diff1_q;     // [(2c + k) * 3 + a]: k = 0 lower, 1 upper plane
  logic [1:0]              inside1_q;   // child c: o' in_slab on every inactive axis
  logic [2:0]              active1_q;
  logic [3*PAIR_W-1:0]     pair1_q;
  logic [2*REF_W-1:0]      child1_q;

  always_ff @(posedge clk_i) begin
    if (valid_i) begin : b_stage1
      logic [PL_W-1:0]          base, lo, hi;
      logic [SHIFT_W-1:0]       sh;
      logic signed [DIFF_W-1:0] l, h, o;
      logic [1:0]               in_slab;
      in_slab = 2'b11;
      for (int c = 0; c < 2; c++) begin
        for (int a = 0; a < 3; a++) begin
          base = PL_W'(node_i[OFF_BASE + a*P +: P]);
          sh   = node_i[OFF_SHIFT + a*SHIFT_W +: SHIFT_W];
          lo   = base + (PL_W'(node_i[OFF_LO + (3*c + a)*PLANE_W +: PLANE_W]) << sh);
          hi   = base + (PL_W'(node_i[OFF_HI + (3*c + a)*PLANE_W +: PLANE_W]) << sh);
          o    = DIFF_W'(origin_i[a*ORG_W +: ORG_W]);
          if (mirror_i[a]) begin
            l = (DIFF_W'(1) << P) - DIFF_W'(hi);
            h = (DIFF_W'(1) << P) - DIFF_W'(lo);
          end else begin
            l = DIFF_W'(lo);
            h = DIFF_W'(hi);
          end
          diff1_q[((2*c + 0)*3 + a)*DIFF_W +: DIFF_W] <= l - o;
          diff1_q[((2*c + 1)*3 + a)*DIFF_W +: DIFF_W] <= h - o;
          if (!active_i[a] && (o < l || o > h)) in_slab[c] = 1'b0;
        end
        child1_q[c*REF_W +: REF_W] <= {node_i[OFF_LEAF + c], node_i[OFF_COUNT + c*COUNT_W +: COUNT_W],
                                      node_i[OFF_FIRST + c*32 +: 32]};
      end
      inside1_q <= in_slab;
      slot1_q   <= slot_i;
      active1_q <= active_i;
      pair1_q   <= pair_i;
    end
  end

  // ---- Stage 2: the products ------------------------------------------------------------
  logic                    v2_q;
  logic [SlotW-1:0]        slot2_q;
  logic [12*T_W-1:0]       t2_q;        // as diff1_q
  logic [1:0]              inside2_q;
  logic [2:0]              active2_q;
  logic [2*REF_W-1:0]      child2_q;

  always_ff @(posedge clk_i) begin
    if (v1_q) begin
      for (int k = 0; k < 12; k++) begin
        t2_q[k*T_W +: T_W] <= T_W'($signed(diff1_q[k*DIFF_W +: DIFF_W]))
                              * T_W'($signed({1'b0, pair1_q[(k%3)*PAIR_W +: PAIR_W]}));
      end
      slot2_q   <= slot1_q;
      inside2_q <= inside1_q;
      active2_q <= active1_q;
      child2_q  <= child1_q;
    end
  end

  // ---- Stage 3: the intervals over the active axes --------------------------------------
  logic                    v3_q;
  logic [SlotW-1:0]        slot3_q;
  logic [2*T_W-1:0]        tmax3_q, tmin3_q;  // child c: max T0, min T1
  logic [1:0]              any3_q;           // child c: some axis active (the same for both)
  logic [1:0]              inside3_q;
  logic [2*REF_W-1:0]      child3_q;

  always_ff @(posedge clk_i) begin
    if (v2_q) begin : b_stage3
      logic signed [T_W-1:0] t0, t1, tmin, tmax;
      logic                  any;
      for (int c = 0; c < 2; c++) begin
        tmin = '0;
        tmax = '0;
        any  = 1'b0;
        for (int a = 0; a < 3; a++) begin
          t0 = t2_q[((2*c + 0)*3 + a)*T_W +: T_W];
          t1 = t2_q[((2*c + 1)*3 + a)*T_W +: T_W];
          if (active2_q[a]) begin
            if (!any || t0 > tmax) tmax = t0;   // max T0
            if (!any || t1 < tmin) tmin = t1;   // min T1
            any = 1'b1;
          end
        end
        tmax3_q[c*T_W +: T_W] <= tmax;
        tmin3_q[c*T_W +: T_W] <= tmin;
        any3_q[c]             <= any;
      end
      slot3_q   <= slot2_q;
      inside3_q <= inside2_q;
      child3_q  <= child2_q;
    end
  end

  // ---- Stage 4: the hits, the entries and the order ------------------------------------
  logic [1:0]              hit4_q;
  logic [2*ENTRY_W-1:0]    entry4_q;
  logic                    near4_q;
  logic                    v4_q;
  logic [SlotW-1:0]        slot4_q;
  logic [2*REF_W-1:0]      child4_q;

  always_ff @(posedge clk_i) begin
    if (v3_q) begin : b_stage4
      logic signed [T_W-1:0] tmin, tmax;
      logic [1:0]            hit;
      logic [ENTRY_W-1:0]    entry [2];
      for (int c = 0; c < 2; c++) begin
        tmax     = tmax3_q[c*T_W +: T_W];
        tmin     = tmin3_q[c*T_W +: T_W];
        hit[c]   = inside3_q[c] && any3_q[c] && tmax <= tmin && tmin > 0;
        entry[c] = tmax > 0 ? ENTRY_W'(tmax) : '0;
      end
      hit4_q   <= hit;
      entry4_q <= {entry[1], entry[0]};
      near4_q  <= hit[0] && hit[1] && entry[1] < entry[0];
      slot4_q  <= slot3_q;
      child4_q <= child3_q;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      v1_q <= 1'b0;
      v2_q <= 1'b0;
      v3_q <= 1'b0;
      v4_q <= 1'b0;
    end else begin
      v1_q <= valid_i;
      v2_q <= v1_q;
      v3_q <= v2_q;
      v4_q <= v3_q;
    end
  end

  assign valid_o = v4_q;
  assign slot_o  = slot4_q;
  assign hit_o   = hit4_q;
  assign entry_o = entry4_q;
  assign near_o  = near4_q;
  assign child_o = child4_q;

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  `RT_ASSERT_STATIC(g_node_layout_check, OFF_BASE + 3 * P == rt_pkg::BVH_NODE_W,
                    "rt_bvh_box: bvh_node_t's layout differs from rt_pkg::BVH_NODE_W")
  `RT_ASSERT_STATIC(g_box_latency_check, rt_pkg::BVH_BOX_LATENCY == 4,
                    "rt_bvh_box: its four stages differ from rt_pkg::BVH_BOX_LATENCY")
`endif

endmodule
