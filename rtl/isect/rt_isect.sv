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
//   stage 5  T = sum of the products, hit = inside && det != 0 && t > 0,
//            |det| * t_max (the segment end's bound)                  (1 mul)
//   stage 6  within the segment: |T| * 2^SEG_FRAC_W <= |det| * t_max; sign
//            normalization; every numeric field is zero on a miss
// The ray's any_hit flag is the traversal units' (they end a walk at its
// first hit); the pipeline tests every pair the same way.
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
  localparam int SEG_W     = rt_pkg::SEG_END_W;
  localparam int SEG_FRAC  = rt_pkg::SEG_FRAC_W;
  // |det| * t_max, and |T| * 2^SEG_FRAC: the segment test's two sides.
  localparam int SEG_PROD_W = DET_ABS_W + SEG_W;
  localparam int SEG_CMP_W  = (SEG_PROD_W > T_NUM_W + SEG_FRAC) ? SEG_PROD_W : T_NUM_W + SEG_FRAC;
  // The datapath below is written as this many register stages.
  localparam int NUM_STAGES = 6;

  // ---------------------------------------------------------------------------
  // Stage control (rt_stall_stages): stage_load[s], register s loads a valid
  // item; the ready chain, the result's valid bit and the stream checks.
  // ---------------------------------------------------------------------------
  logic [NUM_STAGES-1:0] stage_load;

  rt_stall_stages #(
    .Stages(NUM_STAGES), .ReqW(rt_pkg::ISECT_RAY_W + rt_pkg::ISECT_TRI_W), .ResW(rt_pkg::ISECT_RES_W)
  ) u_stages (
    .clk_i, .rst_ni, .req_valid_i, .req_ready_o, .req_data_i({req_ray_i, req_tri_i}),
    .res_valid_o, .res_ready_i, .res_data_i(res_data_o), .stage_load_o(stage_load)
  );

  // ---------------------------------------------------------------------------
  // Vectors of the datapath. Packed like rt_pkg's `logic [2:0][W-1:0]` fields
  // (element 0 = x least significant); structs rather than 2-D packed arrays,
  // which Yosys 0.23 reads only inside structs.
  // ---------------------------------------------------------------------------
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
  // Datapath functions. Each stage computes only in the always_ff branch where
  // it loads, so the Verilated model skips the wide products of empty or
  // stalled stages (continuous assigns were evaluated every cycle).
  // Yosys 0.23 reads neither struct-typed arguments, results nor locals here:
  // they are flat vectors, split with {z, y, x} = v.
  // ---------------------------------------------------------------------------

  // |d|: the most negative code -2^(DIR_W-1) gives 2^(DIR_W-1), DIR_W unsigned bits.
  function automatic logic [DIR_W-1:0] abs_dir(logic [DIR_W-1:0] d);
    abs_dir = d[DIR_W-1] ? -d : d;
  endfunction

  // Dominant axis of d; ties go to the lower axis, as in fx::dominantAxis().
  function automatic logic [1:0] dominant_axis(logic [3*DIR_W-1:0] d);
    logic [DIR_W-1:0] dx, dy, dz;
    {dz, dy, dx} = d;
    dx = abs_dir(dx);
    dy = abs_dir(dy);
    dz = abs_dir(dz);
    if (dx >= dy && dx >= dz) begin
      dominant_axis = 2'd0;
    end else if (dy >= dz) begin
      dominant_axis = 2'd1;
    end else begin
      dominant_axis = 2'd2;
    end
  endfunction

  // v - org, |.| < 2^POS_W. Both operands are zero-extended to REL_W = POS_W + 1,
  // so the wrapped difference is the exact two's complement.
  function automatic logic [3*REL_W-1:0] rel_vertex(logic [3*POS_W-1:0] v,
                                                    logic [3*POS_W-1:0] org);
    logic [POS_W-1:0] vx, vy, vz, ox, oy, oz;
    logic [REL_W-1:0] rx, ry, rz;
    {vz, vy, vx} = v;
    {oz, oy, ox} = org;
    rx = REL_W'(vx) - REL_W'(ox);
    ry = REL_W'(vy) - REL_W'(oy);
    rz = REL_W'(vz) - REL_W'(oz);
    rel_vertex = {rz, ry, rx};
  endfunction

  // Rotate the axes so that x = kx = (kz+1)%3, y = ky = (kz+2)%3, z = kz (no
  // kx/ky swap). One function per width: SystemVerilog functions have no
  // width parameter that Yosys reads.
  function automatic logic [3*REL_W-1:0] rotate_rel(logic [3*REL_W-1:0] v, logic [1:0] kz);
    logic [REL_W-1:0] x, y, z;
    {z, y, x} = v;
    case (kz)
      2'd0:    rotate_rel = {x, z, y};
      2'd1:    rotate_rel = {y, x, z};
      default: rotate_rel = v;
    endcase
  endfunction
  function automatic logic [3*DIR_W-1:0] rotate_dir(logic [3*DIR_W-1:0] v, logic [1:0] kz);
    logic [DIR_W-1:0] x, y, z;
    {z, y, x} = v;
    case (kz)
      2'd0:    rotate_dir = {x, z, y};
      2'd1:    rotate_dir = {y, x, z};
      default: rotate_dir = v;
    endcase
  endfunction

  // Shear of one vertex r, scaled by d[kz]: sx = d[kz]*r.x - d[kx]*r.z,
  // sy = d[kz]*r.y - d[ky]*r.z, z kept. |d| <= 2^(DIR_W-1) and |r| < 2^POS_W,
  // so each product is below 2^(POS_W+DIR_W-1) and the difference fits
  // SHEAR_W signed. A vertex shared by two triangles gets bit-identical values.
  function automatic logic [REL_W+2*SHEAR_W-1:0] shear_vertex(logic [3*REL_W-1:0] r,
                                                              logic [3*DIR_W-1:0] d);
    logic signed [REL_W-1:0]   rx, ry, rz;
    logic signed [DIR_W-1:0]   dx, dy, dz;
    logic signed [SHEAR_W-1:0] sx, sy;
    {rz, ry, rx} = r;
    {dz, dy, dx} = d;
    sx = SHEAR_W'(dz) * SHEAR_W'(rx) - SHEAR_W'(dx) * SHEAR_W'(rz);
    sy = SHEAR_W'(dz) * SHEAR_W'(ry) - SHEAR_W'(dy) * SHEAR_W'(rz);
    shear_vertex = {rz, sy, sx};
  endfunction

  // Edge function of the sheared vertices p, q: p.x*q.y - p.y*q.x.
  // |s| < 2^(POS_W+DIR_W), so each product is below 2^(2(POS_W+DIR_W)) and the
  // difference fits EDGE_W.
  function automatic logic signed [EDGE_W-1:0] edge_fn(logic signed [SHEAR_W-1:0] px,
                                                       logic signed [SHEAR_W-1:0] py,
                                                       logic signed [SHEAR_W-1:0] qx,
                                                       logic signed [SHEAR_W-1:0] qy);
    edge_fn = EDGE_W'(px) * EDGE_W'(qy) - EDGE_W'(py) * EDGE_W'(qx);
  endfunction

  // Edge function times the relative z of the opposite vertex, one term of T.
  // |U*az| < 2^(3POS_W+2DIR_W+1).
  function automatic logic signed [T_W-1:0] t_term(logic signed [EDGE_W-1:0] e,
                                                   logic signed [REL_W-1:0]  z);
    t_term = T_W'(e) * T_W'(z);
  endfunction

  // e > 0
  function automatic logic is_pos(logic [EDGE_W-1:0] e);
    is_pos = !e[EDGE_W-1] && (|e);
  endfunction

  // ---------------------------------------------------------------------------
  // Stage 1: dominant axis, vertices relative to the origin, axes rotated
  // (a rotation commutes with the per-axis difference).
  // ---------------------------------------------------------------------------
  rel_vec_t             a_q, b_q, c_q;
  dir_vec_t             dir1_q;
  logic [RAY_ID_W-1:0]  ray_id1_q;
  logic [PRIM_ID_W-1:0] prim_id1_q;
  logic [SEG_W-1:0]     seg1_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[0]) begin : s1_load
      logic [1:0] kz;
      kz         = dominant_axis(req_ray_i.dir);
      a_q        <= rotate_rel(rel_vertex(req_tri_i.v0, req_ray_i.org), kz);
      b_q        <= rotate_rel(rel_vertex(req_tri_i.v1, req_ray_i.org), kz);
      c_q        <= rotate_rel(rel_vertex(req_tri_i.v2, req_ray_i.org), kz);
      dir1_q     <= rotate_dir(req_ray_i.dir, kz);
      ray_id1_q  <= req_ray_i.ray_id;
      prim_id1_q <= req_tri_i.prim_id;
      seg1_q     <= req_ray_i.t_max;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 2: shear scaled by d[kz].
  // ---------------------------------------------------------------------------
  shear_vec_t           sa_q, sb_q, sc_q;
  logic                 dz_neg2_q;
  logic [RAY_ID_W-1:0]  ray_id2_q;
  logic [PRIM_ID_W-1:0] prim_id2_q;
  logic [SEG_W-1:0]     seg2_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[1]) begin
      sa_q       <= shear_vertex(a_q, dir1_q);
      sb_q       <= shear_vertex(b_q, dir1_q);
      sc_q       <= shear_vertex(c_q, dir1_q);
      dz_neg2_q  <= dir1_q.z[DIR_W-1];
      ray_id2_q  <= ray_id1_q;
      prim_id2_q <= prim_id1_q;
      seg2_q     <= seg1_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 3: edge functions, d[kz]^2 times Woop's.
  //   U = cx*by - cy*bx,  V = ax*cy - ay*cx,  W = bx*ay - by*ax
  // A shared edge gives the exact negation in the neighbour: no ray leaks.
  // ---------------------------------------------------------------------------
  logic signed [EDGE_W-1:0] edge_u_q, edge_v_q, edge_w_q;
  rel_vec_t                 sz3_q;
  logic                     dz_neg3_q;
  logic [RAY_ID_W-1:0]      ray_id3_q;
  logic [PRIM_ID_W-1:0]     prim_id3_q;
  logic [SEG_W-1:0]         seg3_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[2]) begin
      edge_u_q   <= edge_fn(sc_q.x, sc_q.y, sb_q.x, sb_q.y);
      edge_v_q   <= edge_fn(sa_q.x, sa_q.y, sc_q.x, sc_q.y);
      edge_w_q   <= edge_fn(sb_q.x, sb_q.y, sa_q.x, sa_q.y);
      sz3_q      <= {sc_q.z, sb_q.z, sa_q.z};
      dz_neg3_q  <= dz_neg2_q;
      ray_id3_q  <= ray_id2_q;
      prim_id3_q <= prim_id2_q;
      seg3_q     <= seg2_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 4: sign test and determinant; the three products of T.
  // Inside unless the signs of U, V, W disagree (zero agrees with both);
  // det = U + V + W, |det| < 3 * 2^(EDGE_W-1) fits DET_W, and det == 0 (ray in
  // the plane, degenerate triangle) is a miss.
  // ---------------------------------------------------------------------------
  logic signed [T_W-1:0]    tp_u_q, tp_v_q, tp_w_q;
  logic                     cand4_q;
  logic signed [DET_W-1:0]  det4_q;
  logic signed [EDGE_W-1:0] edge_v4_q, edge_w4_q;
  logic                     dz_neg4_q;
  logic [RAY_ID_W-1:0]      ray_id4_q;
  logic [PRIM_ID_W-1:0]     prim_id4_q;
  logic [SEG_W-1:0]         seg4_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[3]) begin : s4_load
      logic                    any_neg, any_pos;
      logic signed [DET_W-1:0] det;
      any_neg    = edge_u_q[EDGE_W-1] || edge_v_q[EDGE_W-1] || edge_w_q[EDGE_W-1];
      any_pos    = is_pos(edge_u_q) || is_pos(edge_v_q) || is_pos(edge_w_q);
      det        = DET_W'(edge_u_q) + DET_W'(edge_v_q) + DET_W'(edge_w_q);
      tp_u_q     <= t_term(edge_u_q, sz3_q.x);
      tp_v_q     <= t_term(edge_v_q, sz3_q.y);
      tp_w_q     <= t_term(edge_w_q, sz3_q.z);
      cand4_q    <= !(any_neg && any_pos) && (|det);
      det4_q     <= det;
      edge_v4_q  <= edge_v_q;
      edge_w4_q  <= edge_w_q;
      dz_neg4_q  <= dz_neg3_q;
      ray_id4_q  <= ray_id3_q;
      prim_id4_q <= prim_id3_q;
      seg4_q     <= seg3_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 5: T = U*az + V*bz + W*cz, |T| < 2^(T_W-1), and the hit decision:
  // t = T / (d[kz] * det) > 0 iff T != 0 and T has the sign of d[kz] * det
  // (flip: det and d[kz] have opposite signs, so T must be negative).
  // ---------------------------------------------------------------------------
  logic                     hit5_q, flip5_q;
  logic signed [T_W-1:0]    t5_q;
  logic signed [DET_W-1:0]  det5_q;
  logic signed [EDGE_W-1:0] edge_v5_q, edge_w5_q;
  logic [RAY_ID_W-1:0]      ray_id5_q;
  logic [PRIM_ID_W-1:0]     prim_id5_q;
  logic [SEG_PROD_W-1:0]    seg_bound5_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[4]) begin : s5_load
      logic signed [T_W-1:0]   t;
      logic                    flip;
      logic [DET_ABS_W-1:0]    det_abs;
      t          = tp_u_q + tp_v_q + tp_w_q;
      flip       = det4_q[DET_W-1] ^ dz_neg4_q;
      det_abs    = DET_ABS_W'(det4_q[DET_W-1] ? -det4_q : det4_q);
      seg_bound5_q <= SEG_PROD_W'(det_abs) * SEG_PROD_W'(seg4_q);
      hit5_q     <= cand4_q && (|t) && (t[T_W-1] == flip);
      flip5_q    <= flip;
      t5_q       <= t;
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
  rt_pkg::isect_res_t res_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[5]) begin : s6_load
      logic               det_neg, hit;
      logic [T_NUM_W-1:0] t_abs;
      det_neg       = det5_q[DET_W-1];
      t_abs         = T_NUM_W'(flip5_q ? -t5_q : t5_q);
      hit           = hit5_q && (SEG_CMP_W'(t_abs) << SEG_FRAC) <= SEG_CMP_W'(seg_bound5_q);
      res_q.ray_id  <= ray_id5_q;
      res_q.prim_id <= prim_id5_q;
      res_q.hit     <= hit;
      res_q.t_num   <= hit ? t_abs : '0;
      res_q.det     <= hit ? DET_ABS_W'(det_neg ? -det5_q : det5_q) : '0;
      res_q.u_num   <= hit ? BARY_W'(det_neg ? -edge_v5_q : edge_v5_q) : '0;
      res_q.v_num   <= hit ? BARY_W'(det_neg ? -edge_w5_q : edge_w5_q) : '0;
    end
  end

  assign res_data_o  = res_q;

  // ---------------------------------------------------------------------------
  // Assertions: Verilator only (LANCER_RTL_VERILATOR_ARGS defines RT_ASSERT_ON
  // and passes --assert); Yosys and Icarus skip them.
  // ---------------------------------------------------------------------------
`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  `RT_ASSERT_STATIC(g_latency_check, rt_pkg::ISECT_LATENCY == NUM_STAGES,
                    "rt_isect: its stages differ from rt_pkg::ISECT_LATENCY")

  // The stream checks are rt_stall_stages'.
`endif

endmodule
