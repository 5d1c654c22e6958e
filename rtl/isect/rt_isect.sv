// rt_isect: the watertight ray-triangle intersection pipeline.
//
// Implements steps 1-7 of sw/golden/isect.h (Woop, Benthin & Wald's watertight
// test in exact integer arithmetic, shear scaled by d[kz] instead of divided by
// it) bit for bit: every result equals lancer::fx::intersect() of the request.
// All widths come from rt_pkg, generated from sw/golden/formats.h.
//
//   stage 1  dominant axis kz of dir (ties to the lower axis), rotate the axes so
//            kz becomes the last one (no kx/ky swap), a/b/c = v0/v1/v2 - org
//   stage 2  shear: s{x,y}[k] = d[kz]*r{x,y}[k] - d{x,y}*rz[k]        (12 mul)
//   stage 3  edge functions U, V, W                                    (6 mul)
//   stage 4  sign test, det = U + V + W, products U*az, V*bz, W*cz      (3 mul)
//   stage 5  T = sum of the products, hit = inside && det != 0 && t > 0
//   stage 6  sign normalization; every numeric field is zero on a miss
//
// Latency:    rt_pkg::ISECT_LATENCY (= 6) register stages. A request accepted at
//             clock edge t is on res_valid_o / res_data_o after edge t+5 and is
//             taken at edge t+6 when the consumer is ready: 6 cycles from the
//             cycle it is accepted in to the cycle its result is taken.
// Throughput: one request per cycle (initiation interval 1). Each stage register
//             advances when it is empty or the stage after it advances, so an
//             output stall blocks the input only once all six stages are full,
//             bubbles are squeezed out meanwhile, and a full pipeline accepts a
//             request in the same cycle the consumer takes a result.
//             req_ready_o = res_ready_i || (some stage is empty): combinational in
//             res_ready_i. res_valid_o and res_data_o come straight from flops
//             and never depend on res_ready_i.
module rt_isect (
  input  logic               clk_i,
  input  logic               rst_ni,

  // Requests: one ray-triangle pair per transfer.
  input  logic               req_valid_i,
  output logic               req_ready_o,
  input  rt_pkg::isect_ray_t req_ray_i,
  input  rt_pkg::isect_tri_t req_tri_i,

  // Results, in request order.
  output logic               res_valid_o,
  input  logic               res_ready_i,
  output rt_pkg::isect_res_t res_data_o
);

  // Local copies of the package widths: a size cast needs a simple identifier.
  localparam int POS_W     = rt_pkg::POS_W;
  localparam int DIR_W     = rt_pkg::DIR_W;
  localparam int REL_W     = rt_pkg::REL_W;
  localparam int SHEAR_W   = rt_pkg::SHEAR_W;
  localparam int EDGE_W    = rt_pkg::EDGE_W;
  localparam int DET_W     = rt_pkg::DET_W;
  localparam int T_W       = rt_pkg::T_W;
  localparam int T_NUM_W   = rt_pkg::T_NUM_W;
  localparam int DET_ABS_W = rt_pkg::DET_ABS_W;
  localparam int BARY_W    = rt_pkg::BARY_W;
  localparam int RAY_ID_W  = rt_pkg::RAY_ID_W;
  localparam int PRIM_ID_W = rt_pkg::PRIM_ID_W;
  // The datapath below is written as this many register stages.
  localparam int NUM_STAGES = 6;

  // ---------------------------------------------------------------------------
  // Stage control: valid bits and the ready chain.
  // stage_ready[s]: register s may load this cycle (it is empty, or its content
  // moves on). stage_load[s]: it loads a valid item.
  // ---------------------------------------------------------------------------
  logic [NUM_STAGES-1:0] valid_q, valid_d;
  logic [NUM_STAGES-1:0] valid_in;
  logic [NUM_STAGES-1:0] stage_ready;
  logic [NUM_STAGES-1:0] stage_load;

  assign valid_in = {valid_q[NUM_STAGES-2:0], req_valid_i};

  // Register s may load when some register at or after it is empty, or the
  // result is taken this cycle: the closed form of "the next stage is empty or
  // advancing", with no combinational loop through a vector.
  for (genvar s = 0; s < NUM_STAGES; s++) begin : g_ready
    assign stage_ready[s] = res_ready_i || !(&valid_q[NUM_STAGES-1:s]);
  end

  assign stage_load  = valid_in & stage_ready;
  assign valid_d     = (valid_q & ~stage_ready) | stage_load;
  assign req_ready_o = stage_ready[0];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else begin
      valid_q <= valid_d;
    end
  end

  // ---------------------------------------------------------------------------
  // Vectors of the datapath. Packed like rt_pkg's `logic [2:0][W-1:0]` fields
  // (element 0 = x least significant); structs rather than 2-D packed arrays,
  // which Yosys 0.23 reads only inside structs.
  // ---------------------------------------------------------------------------
  typedef struct packed {
    logic [POS_W-1:0] z;
    logic [POS_W-1:0] y;
    logic [POS_W-1:0] x;
  } pos_vec_t;
  typedef struct packed {
    logic [DIR_W-1:0] z;
    logic [DIR_W-1:0] y;
    logic [DIR_W-1:0] x;
  } dir_vec_t;
  typedef struct packed {
    logic [REL_W-1:0] z;
    logic [REL_W-1:0] y;
    logic [REL_W-1:0] x;
  } rel_vec_t;
  // A sheared vertex: x and y scaled by d[kz], z left as the relative distance.
  typedef struct packed {
    logic [REL_W-1:0]   z;
    logic [SHEAR_W-1:0] y;
    logic [SHEAR_W-1:0] x;
  } shear_vec_t;

  // ---------------------------------------------------------------------------
  // Stage 1: dominant axis and vertices relative to the origin.
  // ---------------------------------------------------------------------------
  dir_vec_t dir_in;
  pos_vec_t org_in, v0_in, v1_in, v2_in;

  assign dir_in = req_ray_i.dir;
  assign org_in = req_ray_i.org;
  assign v0_in  = req_tri_i.v0;
  assign v1_in  = req_tri_i.v1;
  assign v2_in  = req_tri_i.v2;

  // |d| of the most negative code -2^(DIR_W-1) is 2^(DIR_W-1): DIR_W unsigned bits.
  logic [DIR_W-1:0] abs_dx, abs_dy, abs_dz;
  logic [1:0]       kz;

  assign abs_dx = dir_in.x[DIR_W-1] ? -dir_in.x : dir_in.x;
  assign abs_dy = dir_in.y[DIR_W-1] ? -dir_in.y : dir_in.y;
  assign abs_dz = dir_in.z[DIR_W-1] ? -dir_in.z : dir_in.z;

  // Ties go to the lower axis, as in fx::dominantAxis().
  always_comb begin
    if (abs_dx >= abs_dy && abs_dx >= abs_dz) begin
      kz = 2'd0;
    end else if (abs_dy >= abs_dz) begin
      kz = 2'd1;
    end else begin
      kz = 2'd2;
    end
  end

  // Rotate the axes so that x = kx = (kz+1)%3, y = ky = (kz+2)%3, z = kz.
  dir_vec_t dir_r;
  pos_vec_t org_r, v0_r, v1_r, v2_r;

  assign dir_r = (kz == 2'd0) ? {dir_in.x, dir_in.z, dir_in.y} :
                 (kz == 2'd1) ? {dir_in.y, dir_in.x, dir_in.z} : dir_in;
  assign org_r = (kz == 2'd0) ? {org_in.x, org_in.z, org_in.y} :
                 (kz == 2'd1) ? {org_in.y, org_in.x, org_in.z} : org_in;
  assign v0_r  = (kz == 2'd0) ? {v0_in.x, v0_in.z, v0_in.y} :
                 (kz == 2'd1) ? {v0_in.y, v0_in.x, v0_in.z} : v0_in;
  assign v1_r  = (kz == 2'd0) ? {v1_in.x, v1_in.z, v1_in.y} :
                 (kz == 2'd1) ? {v1_in.y, v1_in.x, v1_in.z} : v1_in;
  assign v2_r  = (kz == 2'd0) ? {v2_in.x, v2_in.z, v2_in.y} :
                 (kz == 2'd1) ? {v2_in.y, v2_in.x, v2_in.z} : v2_in;

  // a, b, c = v0, v1, v2 - org, |.| < 2^POS_W. Both operands are zero-extended
  // to REL_W = POS_W + 1, so the wrapped difference is the exact two's complement.
  rel_vec_t a_d, b_d, c_d, a_q, b_q, c_q;

  assign a_d = {REL_W'(v0_r.z) - REL_W'(org_r.z), REL_W'(v0_r.y) - REL_W'(org_r.y),
                REL_W'(v0_r.x) - REL_W'(org_r.x)};
  assign b_d = {REL_W'(v1_r.z) - REL_W'(org_r.z), REL_W'(v1_r.y) - REL_W'(org_r.y),
                REL_W'(v1_r.x) - REL_W'(org_r.x)};
  assign c_d = {REL_W'(v2_r.z) - REL_W'(org_r.z), REL_W'(v2_r.y) - REL_W'(org_r.y),
                REL_W'(v2_r.x) - REL_W'(org_r.x)};

  dir_vec_t             dir1_q;
  logic [RAY_ID_W-1:0]  ray_id1_q;
  logic [PRIM_ID_W-1:0] prim_id1_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[0]) begin
      a_q        <= a_d;
      b_q        <= b_d;
      c_q        <= c_d;
      dir1_q     <= dir_r;
      ray_id1_q  <= req_ray_i.ray_id;
      prim_id1_q <= req_tri_i.prim_id;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 2: shear scaled by d[kz]:  sx = d[kz]*r.x - d[kx]*r.z,
  // sy = d[kz]*r.y - d[ky]*r.z. |d| <= 2^(DIR_W-1) and |r| < 2^POS_W, so each
  // product is below 2^(POS_W+DIR_W-1) and the difference fits SHEAR_W signed.
  // A vertex shared by two triangles gets bit-identical sheared values.
  // ---------------------------------------------------------------------------
  logic signed [SHEAR_W-1:0] dx_s, dy_s, dz_s;

  assign dx_s = SHEAR_W'($signed(dir1_q.x));
  assign dy_s = SHEAR_W'($signed(dir1_q.y));
  assign dz_s = SHEAR_W'($signed(dir1_q.z));

  shear_vec_t sa_d, sb_d, sc_d, sa_q, sb_q, sc_q;

  assign sa_d = {a_q.z, dz_s * SHEAR_W'($signed(a_q.y)) - dy_s * SHEAR_W'($signed(a_q.z)),
                        dz_s * SHEAR_W'($signed(a_q.x)) - dx_s * SHEAR_W'($signed(a_q.z))};
  assign sb_d = {b_q.z, dz_s * SHEAR_W'($signed(b_q.y)) - dy_s * SHEAR_W'($signed(b_q.z)),
                        dz_s * SHEAR_W'($signed(b_q.x)) - dx_s * SHEAR_W'($signed(b_q.z))};
  assign sc_d = {c_q.z, dz_s * SHEAR_W'($signed(c_q.y)) - dy_s * SHEAR_W'($signed(c_q.z)),
                        dz_s * SHEAR_W'($signed(c_q.x)) - dx_s * SHEAR_W'($signed(c_q.z))};

  logic                 dz_neg2_q;
  logic [RAY_ID_W-1:0]  ray_id2_q;
  logic [PRIM_ID_W-1:0] prim_id2_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[1]) begin
      sa_q       <= sa_d;
      sb_q       <= sb_d;
      sc_q       <= sc_d;
      dz_neg2_q  <= dir1_q.z[DIR_W-1];
      ray_id2_q  <= ray_id1_q;
      prim_id2_q <= prim_id1_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 3: edge functions, d[kz]^2 times Woop's. |s| < 2^(POS_W+DIR_W), so
  // each product is below 2^(2(POS_W+DIR_W)) and the difference fits EDGE_W.
  //   U = cx*by - cy*bx,  V = ax*cy - ay*cx,  W = bx*ay - by*ax
  // A shared edge gives the exact negation in the neighbour: no ray leaks.
  // ---------------------------------------------------------------------------
  logic signed [EDGE_W-1:0] ax_e, ay_e, bx_e, by_e, cx_e, cy_e;

  assign ax_e = EDGE_W'($signed(sa_q.x));
  assign ay_e = EDGE_W'($signed(sa_q.y));
  assign bx_e = EDGE_W'($signed(sb_q.x));
  assign by_e = EDGE_W'($signed(sb_q.y));
  assign cx_e = EDGE_W'($signed(sc_q.x));
  assign cy_e = EDGE_W'($signed(sc_q.y));

  logic signed [EDGE_W-1:0] edge_u_d, edge_v_d, edge_w_d;
  logic signed [EDGE_W-1:0] edge_u_q, edge_v_q, edge_w_q;

  assign edge_u_d = cx_e * by_e - cy_e * bx_e;
  assign edge_v_d = ax_e * cy_e - ay_e * cx_e;
  assign edge_w_d = bx_e * ay_e - by_e * ax_e;

  rel_vec_t             sz3_q;
  logic                 dz_neg3_q;
  logic [RAY_ID_W-1:0]  ray_id3_q;
  logic [PRIM_ID_W-1:0] prim_id3_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[2]) begin
      edge_u_q   <= edge_u_d;
      edge_v_q   <= edge_v_d;
      edge_w_q   <= edge_w_d;
      sz3_q      <= {sc_q.z, sb_q.z, sa_q.z};
      dz_neg3_q  <= dz_neg2_q;
      ray_id3_q  <= ray_id2_q;
      prim_id3_q <= prim_id2_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 4: sign test and determinant; the three products of T.
  // Inside unless the signs of U, V, W disagree (zero agrees with both);
  // det = U + V + W, |det| < 3 * 2^(EDGE_W-1) fits DET_W, and det == 0 (ray in
  // the plane, degenerate triangle) is a miss. |U*az| < 2^(3POS_W+2DIR_W+1).
  // ---------------------------------------------------------------------------
  logic any_neg, any_pos, in_tri;
  logic signed [DET_W-1:0] det_d;

  assign any_neg = edge_u_q[EDGE_W-1] || edge_v_q[EDGE_W-1] || edge_w_q[EDGE_W-1];
  assign any_pos = (!edge_u_q[EDGE_W-1] && (|edge_u_q)) ||
                   (!edge_v_q[EDGE_W-1] && (|edge_v_q)) ||
                   (!edge_w_q[EDGE_W-1] && (|edge_w_q));
  assign in_tri  = !(any_neg && any_pos);
  assign det_d   = DET_W'(edge_u_q) + DET_W'(edge_v_q) + DET_W'(edge_w_q);

  logic signed [T_W-1:0] tp_u_d, tp_v_d, tp_w_d, tp_u_q, tp_v_q, tp_w_q;

  assign tp_u_d = T_W'(edge_u_q) * T_W'($signed(sz3_q.x));
  assign tp_v_d = T_W'(edge_v_q) * T_W'($signed(sz3_q.y));
  assign tp_w_d = T_W'(edge_w_q) * T_W'($signed(sz3_q.z));

  logic                     cand4_q;
  logic signed [DET_W-1:0]  det4_q;
  logic signed [EDGE_W-1:0] edge_v4_q, edge_w4_q;
  logic                     dz_neg4_q;
  logic [RAY_ID_W-1:0]      ray_id4_q;
  logic [PRIM_ID_W-1:0]     prim_id4_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[3]) begin
      tp_u_q     <= tp_u_d;
      tp_v_q     <= tp_v_d;
      tp_w_q     <= tp_w_d;
      cand4_q    <= in_tri && (|det_d);
      det4_q     <= det_d;
      edge_v4_q  <= edge_v_q;
      edge_w4_q  <= edge_w_q;
      dz_neg4_q  <= dz_neg3_q;
      ray_id4_q  <= ray_id3_q;
      prim_id4_q <= prim_id3_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 5: T = U*az + V*bz + W*cz, |T| < 2^(T_W-1), and the hit decision:
  // t = T / (d[kz] * det) > 0 iff T != 0 and T has the sign of d[kz] * det
  // (flip: det and d[kz] have opposite signs, so T must be negative).
  // ---------------------------------------------------------------------------
  logic signed [T_W-1:0] t_d;
  logic                  flip_d, hit_d;

  assign t_d    = tp_u_q + tp_v_q + tp_w_q;
  assign flip_d = det4_q[DET_W-1] ^ dz_neg4_q;
  assign hit_d  = cand4_q && (|t_d) && (t_d[T_W-1] == flip_d);

  logic                     hit5_q, flip5_q;
  logic signed [T_W-1:0]    t5_q;
  logic signed [DET_W-1:0]  det5_q;
  logic signed [EDGE_W-1:0] edge_v5_q, edge_w5_q;
  logic [RAY_ID_W-1:0]      ray_id5_q;
  logic [PRIM_ID_W-1:0]     prim_id5_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[4]) begin
      hit5_q     <= hit_d;
      flip5_q    <= flip_d;
      t5_q       <= t_d;
      det5_q     <= det4_q;
      edge_v5_q  <= edge_v4_q;
      edge_w5_q  <= edge_w4_q;
      ray_id5_q  <= ray_id4_q;
      prim_id5_q <= prim_id4_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 6: sign normalization. On a hit every output is non-negative: T is
  // negated when flipped, det, V and W when det < 0 (then V, W <= 0). The
  // magnitudes fit the one-bit-narrower output fields. A miss is all zeros.
  // ---------------------------------------------------------------------------
  logic              det_neg;
  logic [T_NUM_W-1:0]   t_abs;
  logic [DET_ABS_W-1:0] det_abs;
  logic [BARY_W-1:0]    u_abs, v_abs;

  assign det_neg = det5_q[DET_W-1];
  assign t_abs   = T_NUM_W'(flip5_q ? -t5_q : t5_q);
  assign det_abs = DET_ABS_W'(det_neg ? -det5_q : det5_q);
  assign u_abs   = BARY_W'(det_neg ? -edge_v5_q : edge_v5_q);
  assign v_abs   = BARY_W'(det_neg ? -edge_w5_q : edge_w5_q);

  rt_pkg::isect_res_t res_d, res_q;

  always_comb begin
    res_d         = '0;
    res_d.ray_id  = ray_id5_q;
    res_d.prim_id = prim_id5_q;
    if (hit5_q) begin
      res_d.hit   = 1'b1;
      res_d.t_num = t_abs;
      res_d.det   = det_abs;
      res_d.u_num = u_abs;
      res_d.v_num = v_abs;
    end
  end

  always_ff @(posedge clk_i) begin
    if (stage_load[5]) begin
      res_q <= res_d;
    end
  end

  assign res_valid_o = valid_q[NUM_STAGES-1];
  assign res_data_o  = res_q;

  // ---------------------------------------------------------------------------
  // Assertions: Verilator only (LANCER_RTL_VERILATOR_ARGS defines RT_ASSERT_ON
  // and passes --assert); Yosys and Icarus skip them.
  // ---------------------------------------------------------------------------
`ifdef RT_ASSERT_ON
  if (rt_pkg::ISECT_LATENCY != NUM_STAGES) begin : g_latency_check
    $error("rt_isect has %0d stages but rt_pkg::ISECT_LATENCY is %0d",
           NUM_STAGES, rt_pkg::ISECT_LATENCY);
  end

  // Valid and ready are never X once out of reset.
  a_res_valid_known : assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown(res_valid_o));
  a_req_ready_known : assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown(req_ready_o));
  a_req_valid_known : assert property (@(posedge clk_i) disable iff (!rst_ni)
      !$isunknown(req_valid_i));
  // Output stream: a result that is not taken stays, unchanged.
  a_res_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      res_valid_o && !res_ready_i |=> res_valid_o && $stable(res_data_o));
  // Input stream (the producer's duty): an offered request stays, unchanged.
  a_req_hold : assert property (@(posedge clk_i) disable iff (!rst_ni)
      req_valid_i && !req_ready_o |=> req_valid_i && $stable(req_ray_i) && $stable(req_tri_i));
  // A full pipeline whose result is taken accepts a new request (II = 1).
  a_full_throughput : assert property (@(posedge clk_i) disable iff (!rst_ni)
      res_ready_i |-> req_ready_o);
`endif

endmodule
