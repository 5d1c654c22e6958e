// rt_quadric: the ray-quadric intersection pipeline (spheres and NFF cones).
//
// Implements lancer::fx::intersectQuadric() (sw/golden/quadric.h) bit for bit:
// a ray against a quadric's record q'Qq + 2g'q + k = 0, q = 2x - S, cut by the
// planes |q.w| <= W (a cone's ends; a sphere's record has w = 0). With
// x = o + lambda d the quadric is 4A lambda^2 + 4B lambda + C; the roots are
// big / 2A and C / 2big, big = -(B + sgn(B) s), s = floor(sqrt(B^2 - AC)).
// All widths come from rt_pkg, generated from sw/golden/quadric.h. Every sum
// and product is computed modulo its documented width: exact, because the
// value fits (docs/quadrics.md, "The pipeline").
//
//   stage 1      q = 2o - S; Q d (9 mul); d.w (3 mul); |d_dom|
//   stage 2      Q q (9 mul); q.w (3 mul); rows of Q d
//   stage 3      rows of Q q plus g and 2g; A's terms (3 mul); q.w, d.w summed
//   stage 4      B's and C's terms (6 mul); A
//   stage 5      B, C
//   stage 6      B^2 and AC as products of halves (7 mul)
//   stage 7      disc = B^2 - AC; a negative one is a miss
//   stages 8..   the square root, QUADRIC_ROOT_STEP result bits a stage
//                (restoring digit recurrence, two discriminant bits a bit)
//   then 4       the roots and their order (swap: the second is nearer when
//                disc > 0 and A, big share a sign); the plane, segment and
//                t products as products of halves (20 mul); their sums; the
//                root taken (the nearer ahead and between the planes, else the
//                farther), the segment rule, the result
//
// Latency:    rt_pkg::QUADRIC_LATENCY register stages (43 at 16/16), counted
//             as rt_isect's: from the cycle a request is accepted to the cycle
//             its result is taken, when the consumer is ready.
// Throughput: one request per cycle, with rt_isect's stage control: each
//             register advances when it is empty or the one after it
//             advances; req_ready_o = res_ready_i || (some stage is empty).
module rt_quadric (
  input  logic                 clk_i,
  input  logic                 rst_ni,

  // Requests: one ray-quadric pair per transfer.
  input  logic                 req_valid_i,
  output logic                 req_ready_o,
  input  rt_pkg::isect_ray_t     req_ray_i,
  input  rt_pkg::isect_quadric_t req_quadric_i,

  // Results, in request order.
  output logic                 res_valid_o,
  input  logic                 res_ready_i,
  output rt_pkg::isect_res_t   res_data_o
);

  // Local copies of the package widths: a size cast needs a simple identifier.
  localparam int POS_W     = rt_pkg::POS_W;
  localparam int DIR_W     = rt_pkg::DIR_W;
  localparam int RAY_ID_W  = rt_pkg::RAY_ID_W;
  localparam int PRIM_ID_W = rt_pkg::PRIM_ID_W;
  localparam int SEG_W     = rt_pkg::SEG_END_W;
  localparam int SEG_FRAC  = rt_pkg::SEG_FRAC_W;
  localparam int T_NUM_W   = rt_pkg::T_NUM_W;
  localparam int DET_ABS_W = rt_pkg::DET_ABS_W;
  localparam int BARY_W    = rt_pkg::BARY_W;
  localparam int SUM_W     = rt_pkg::QUADRIC_AXIS_SUM_W;
  localparam int AXIS_W    = rt_pkg::QUADRIC_AXIS_W;
  localparam int LEN2_W    = rt_pkg::QUADRIC_AXIS_LEN2_W;
  localparam int COEF_W    = rt_pkg::QUADRIC_COEF_W;
  localparam int LIN_W     = rt_pkg::QUADRIC_LIN_W;
  localparam int CONST_W   = rt_pkg::QUADRIC_CONST_W;
  localparam int Q_W       = rt_pkg::QUADRIC_Q_W;
  localparam int A_W       = rt_pkg::QUADRIC_A_W;
  localparam int B_W       = rt_pkg::QUADRIC_B_W;
  localparam int C_W       = rt_pkg::QUADRIC_C_W;
  localparam int DISC_W    = rt_pkg::QUADRIC_DISC_W;
  localparam int ROOT_W    = rt_pkg::QUADRIC_ROOT_W;
  localparam int NUM_W     = rt_pkg::QUADRIC_NUM_W;
  localparam int DEN_W     = rt_pkg::QUADRIC_DEN_W;
  localparam int OH_W      = rt_pkg::QUADRIC_OH_W;
  localparam int DH_W      = rt_pkg::QUADRIC_DH_W;
  localparam int PLANE_W   = rt_pkg::QUADRIC_PLANE_W;
  localparam int STEP      = rt_pkg::QUADRIC_ROOT_STEP;
  localparam int ROOT_STAGES = rt_pkg::QUADRIC_ROOT_STAGES;
  // Rows of Q d and Q q: |sum_j Q_ij d_j| < 2^(K+D+1), |sum_j Q_ij q_j| < 2^(P+K+3).
  localparam int DROW_W = rt_pkg::QUADRIC_K + DIR_W + 2;
  localparam int QROW_W = POS_W + rt_pkg::QUADRIC_K + 4;
  // B's and C's row factors (Q q)_i + g_i and (Q q)_i + 2 g_i: |g_i| <= 2^(P+K+1),
  // so both stay below 2^(P+K+4).
  localparam int ROW_W = POS_W + rt_pkg::QUADRIC_K + 5;
  // The remainder of the square root: at most 2 s + 1 before a step's
  // subtraction, times 4 plus 3 within one.
  localparam int REM_W = ROOT_W + 3;
  // Halves of the discriminant's operands (B, A, C): the low halves unsigned.
  localparam int HALF = (DISC_W + 3) / 4;
  // Halves of a root's numerator and denominator for the plane, segment and t products.
  localparam int NUM_LO = (NUM_W + 1) / 2;
  localparam int DEN_LO = (DEN_W + 1) / 2;
  // t_max * den against t_num * 2^SEG_FRAC.
  localparam int SEG_CMP_W = (SEG_W + DEN_W > T_NUM_W + SEG_FRAC) ? SEG_W + DEN_W : T_NUM_W + SEG_FRAC;
  // The stages: seven before the square root, four after it.
  localparam int FRONT = 7;
  localparam int NUM_STAGES = FRONT + ROOT_STAGES + 4;

  // ---------------------------------------------------------------------------
  // Stage control, as rt_isect's (rt_stall_stages).
  // ---------------------------------------------------------------------------
  logic [NUM_STAGES-1:0] stage_load;

  rt_stall_stages #(
    .Stages(NUM_STAGES), .ReqW(rt_pkg::ISECT_RAY_W + rt_pkg::ISECT_QUADRIC_W), .ResW(rt_pkg::ISECT_RES_W)
  ) u_stages (
    .clk_i, .rst_ni, .req_valid_i, .req_ready_o, .req_data_i({req_ray_i, req_quadric_i}),
    .res_valid_o, .res_ready_i, .res_data_i(res_data_o), .stage_load_o(stage_load)
  );

  // ---------------------------------------------------------------------------
  // Datapath functions. Flat vectors (Yosys 0.23 reads no struct arguments);
  // element 0 = x least significant, as rt_pkg's arrays.
  // ---------------------------------------------------------------------------

  // Q_ij of the record's six entries (xx, yy, zz, yz, xz, xy).
  function automatic logic [COEF_W-1:0] coef(logic [6*COEF_W-1:0] quad, int i, int j);
    int idx;
    idx = (i == j) ? i : 6 - i - j;
    coef = quad[idx*COEF_W +: COEF_W];
  endfunction

  // (Q q)_i: the sum of a row's three products, sign-extended to ROW_W.
  function automatic logic [ROW_W-1:0] row_sum(logic [3*QROW_W-1:0] products);
    row_sum = ROW_W'($signed(products[0 +: QROW_W])) + ROW_W'($signed(products[QROW_W +: QROW_W])) +
              ROW_W'($signed(products[2*QROW_W +: QROW_W]));
  endfunction

  // |d| of a D-bit code: -2^(D-1) gives 2^(D-1), D unsigned bits.
  function automatic logic [DIR_W-1:0] abs_dir(logic [DIR_W-1:0] d);
    abs_dir = d[DIR_W-1] ? -d : d;
  endfunction

  // ---------------------------------------------------------------------------
  // Stage 1: q = 2o - S (P + 2 bits signed); the products of Q d and d.w.
  // ---------------------------------------------------------------------------
  logic [3*Q_W-1:0]       q1_q;
  logic [3*DIR_W-1:0]     d1_q;
  logic [9*DROW_W-1:0]    qd1_q;       // Q_ij d_j, row i at [3i+j]
  logic [3*DH_W-1:0]      dw1_q;       // d_i w_i
  logic [6*COEF_W-1:0]    quad1_q;
  logic [3*LIN_W-1:0]     lin1_q;
  logic [CONST_W-1:0]     konst1_q;
  logic [3*AXIS_W-1:0]    axis1_q;
  logic [LEN2_W-1:0]      len2_1_q;
  logic [DIR_W-1:0]       ddom1_q;
  logic [SEG_W-1:0]       seg1_q;
  logic [RAY_ID_W-1:0]    ray_id1_q;
  logic [PRIM_ID_W-1:0]   prim_id1_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[0]) begin : s1_load
      logic [3*POS_W-1:0]  org;
      logic [3*DIR_W-1:0]  dir;
      logic [3*SUM_W-1:0]  sum;
      logic [3*AXIS_W-1:0] axis;
      logic [DIR_W-1:0]    ax, ay, az;
      org  = req_ray_i.org;
      dir  = req_ray_i.dir;
      sum  = req_quadric_i.axis_sum;
      axis = req_quadric_i.axis;
      for (int k = 0; k < 3; k++) begin
        q1_q[k*Q_W +: Q_W] <= Q_W'({org[k*POS_W +: POS_W], 1'b0}) - Q_W'(sum[k*SUM_W +: SUM_W]);
        dw1_q[k*DH_W +: DH_W] <= DH_W'($signed(dir[k*DIR_W +: DIR_W])) * DH_W'($signed(axis[k*AXIS_W +: AXIS_W]));
        for (int j = 0; j < 3; j++) begin
          qd1_q[(3*k+j)*DROW_W +: DROW_W] <=
              DROW_W'($signed(coef(req_quadric_i.quad, k, j))) * DROW_W'($signed(dir[j*DIR_W +: DIR_W]));
        end
      end
      ax = abs_dir(dir[0 +: DIR_W]);
      ay = abs_dir(dir[DIR_W +: DIR_W]);
      az = abs_dir(dir[2*DIR_W +: DIR_W]);
      ddom1_q    <= (ax >= ay && ax >= az) ? ax : (ay >= az) ? ay : az;
      d1_q       <= req_ray_i.dir;
      quad1_q    <= req_quadric_i.quad;
      lin1_q     <= req_quadric_i.lin;
      konst1_q   <= req_quadric_i.konst;
      axis1_q    <= req_quadric_i.axis;
      len2_1_q   <= req_quadric_i.axis_len2;
      seg1_q     <= req_ray_i.t_max;
      ray_id1_q  <= req_ray_i.ray_id;
      prim_id1_q <= req_quadric_i.prim_id;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 2: the products of Q q and q.w; the rows of Q d.
  // ---------------------------------------------------------------------------
  logic [3*Q_W-1:0]       q2_q;
  logic [3*DIR_W-1:0]     d2_q;
  logic [9*QROW_W-1:0]    qq2_q;       // Q_ij q_j
  logic [3*OH_W-1:0]      qw2_q;       // q_i w_i
  logic [3*DROW_W-1:0]    drow2_q;     // (Q d)_i
  logic [3*DH_W-1:0]      dw2_q;
  logic [3*LIN_W-1:0]     lin2_q;
  logic [CONST_W-1:0]     konst2_q;
  logic [LEN2_W-1:0]      len2_2_q;
  logic [DIR_W-1:0]       ddom2_q;
  logic [SEG_W-1:0]       seg2_q;
  logic [RAY_ID_W-1:0]    ray_id2_q;
  logic [PRIM_ID_W-1:0]   prim_id2_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[1]) begin
      for (int k = 0; k < 3; k++) begin
        qw2_q[k*OH_W +: OH_W] <= OH_W'($signed(q1_q[k*Q_W +: Q_W])) * OH_W'($signed(axis1_q[k*AXIS_W +: AXIS_W]));
        drow2_q[k*DROW_W +: DROW_W] <= qd1_q[(3*k)*DROW_W +: DROW_W] + qd1_q[(3*k+1)*DROW_W +: DROW_W] +
                                       qd1_q[(3*k+2)*DROW_W +: DROW_W];
        for (int j = 0; j < 3; j++) begin
          qq2_q[(3*k+j)*QROW_W +: QROW_W] <=
              QROW_W'($signed(coef(quad1_q, k, j))) * QROW_W'($signed(q1_q[j*Q_W +: Q_W]));
        end
      end
      q2_q       <= q1_q;
      d2_q       <= d1_q;
      dw2_q      <= dw1_q;
      lin2_q     <= lin1_q;
      konst2_q   <= konst1_q;
      len2_2_q   <= len2_1_q;
      ddom2_q    <= ddom1_q;
      seg2_q     <= seg1_q;
      ray_id2_q  <= ray_id1_q;
      prim_id2_q <= prim_id1_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 3: the rows of Q q with g added, B's factors (Q q)_i + g_i and C's
  // (Q q)_i + 2 g_i (so that stage 4 only multiplies); A's terms (Q d)_i d_i;
  // the heights q.w and d.w.
  // ---------------------------------------------------------------------------
  logic [3*Q_W-1:0]       q3_q;
  logic [3*DIR_W-1:0]     d3_q;
  logic [3*ROW_W-1:0]     brow3_q;     // (Q q)_i + g_i
  logic [3*ROW_W-1:0]     crow3_q;     // (Q q)_i + 2 g_i
  logic [3*A_W-1:0]       aterm3_q;
  logic [OH_W-1:0]        oh3_q;
  logic [DH_W-1:0]        dh3_q;
  logic [CONST_W-1:0]     konst3_q;
  logic [LEN2_W-1:0]      len2_3_q;
  logic [DIR_W-1:0]       ddom3_q;
  logic [SEG_W-1:0]       seg3_q;
  logic [RAY_ID_W-1:0]    ray_id3_q;
  logic [PRIM_ID_W-1:0]   prim_id3_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[2]) begin
      for (int k = 0; k < 3; k++) begin
        brow3_q[k*ROW_W +: ROW_W] <= row_sum(qq2_q[k*3*QROW_W +: 3*QROW_W]) + ROW_W'($signed(lin2_q[k*LIN_W +: LIN_W]));
        crow3_q[k*ROW_W +: ROW_W] <= row_sum(qq2_q[k*3*QROW_W +: 3*QROW_W]) +
                                     (ROW_W'($signed(lin2_q[k*LIN_W +: LIN_W])) << 1);
        aterm3_q[k*A_W +: A_W] <= A_W'($signed(drow2_q[k*DROW_W +: DROW_W])) * A_W'($signed(d2_q[k*DIR_W +: DIR_W]));
      end
      oh3_q      <= qw2_q[0 +: OH_W] + qw2_q[OH_W +: OH_W] + qw2_q[2*OH_W +: OH_W];
      dh3_q      <= dw2_q[0 +: DH_W] + dw2_q[DH_W +: DH_W] + dw2_q[2*DH_W +: DH_W];
      q3_q       <= q2_q;
      d3_q       <= d2_q;
      konst3_q   <= konst2_q;
      len2_3_q   <= len2_2_q;
      ddom3_q    <= ddom2_q;
      seg3_q     <= seg2_q;
      ray_id3_q  <= ray_id2_q;
      prim_id3_q <= prim_id2_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 4: B's terms ((Q q)_i + g_i) d_i, C's terms ((Q q)_i + 2 g_i) q_i; A.
  // ---------------------------------------------------------------------------
  logic [3*B_W-1:0]       bterm4_q;
  logic [3*C_W-1:0]       cterm4_q;
  logic [A_W-1:0]         a4_q;
  logic [CONST_W-1:0]     konst4_q;
  logic [OH_W-1:0]        oh4_q;
  logic [DH_W-1:0]        dh4_q;
  logic [LEN2_W-1:0]      len2_4_q;
  logic [DIR_W-1:0]       ddom4_q;
  logic [SEG_W-1:0]       seg4_q;
  logic [RAY_ID_W-1:0]    ray_id4_q;
  logic [PRIM_ID_W-1:0]   prim_id4_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[3]) begin
      for (int k = 0; k < 3; k++) begin
        bterm4_q[k*B_W +: B_W] <= B_W'($signed(brow3_q[k*ROW_W +: ROW_W])) * B_W'($signed(d3_q[k*DIR_W +: DIR_W]));
        cterm4_q[k*C_W +: C_W] <= C_W'($signed(crow3_q[k*ROW_W +: ROW_W])) * C_W'($signed(q3_q[k*Q_W +: Q_W]));
      end
      a4_q       <= aterm3_q[0 +: A_W] + aterm3_q[A_W +: A_W] + aterm3_q[2*A_W +: A_W];
      konst4_q   <= konst3_q;
      oh4_q      <= oh3_q;
      dh4_q      <= dh3_q;
      len2_4_q   <= len2_3_q;
      ddom4_q    <= ddom3_q;
      seg4_q     <= seg3_q;
      ray_id4_q  <= ray_id3_q;
      prim_id4_q <= prim_id3_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 5: B and C. From here on what the roots need travels as one record.
  // ---------------------------------------------------------------------------
  typedef struct packed {
    logic [A_W-1:0]       a;
    logic [B_W-1:0]       b;
    logic [C_W-1:0]       c;
    logic [OH_W-1:0]      oh;
    logic [DH_W-1:0]      dh;
    logic [LEN2_W-1:0]    len2;
    logic [DIR_W-1:0]     ddom;
    logic [SEG_W-1:0]     seg;
    logic [RAY_ID_W-1:0]  ray_id;
    logic [PRIM_ID_W-1:0] prim_id;
  } carry_t;
  localparam int CARRY_W = A_W + B_W + C_W + OH_W + DH_W + LEN2_W + DIR_W + SEG_W + RAY_ID_W + PRIM_ID_W;

  carry_t carry5_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[4]) begin
      carry5_q.a       <= a4_q;
      carry5_q.b       <= bterm4_q[0 +: B_W] + bterm4_q[B_W +: B_W] + bterm4_q[2*B_W +: B_W];
      carry5_q.c       <= cterm4_q[0 +: C_W] + cterm4_q[C_W +: C_W] + cterm4_q[2*C_W +: C_W] +
                          C_W'($signed(konst4_q));
      carry5_q.oh      <= oh4_q;
      carry5_q.dh      <= dh4_q;
      carry5_q.len2    <= len2_4_q;
      carry5_q.ddom    <= ddom4_q;
      carry5_q.seg     <= seg4_q;
      carry5_q.ray_id  <= ray_id4_q;
      carry5_q.prim_id <= prim_id4_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 6: B^2 and AC from products of halves, X = Xh 2^HALF + Xl (Xl
  // unsigned), each product at most HALF + 1 bits by the other half's width.
  // ---------------------------------------------------------------------------
  logic [DISC_W-1:0] bb_hh6_q, bb_hl6_q, bb_ll6_q, ac_hh6_q, ac_hl6_q, ac_lh6_q, ac_ll6_q;
  carry_t            carry6_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[5]) begin : s6_load
      logic signed [DISC_W-1:0] bh, bl, ah, al, ch, cl;
      bh = DISC_W'($signed(carry5_q.b[B_W-1:HALF]));
      bl = DISC_W'(carry5_q.b[HALF-1:0]);
      ah = DISC_W'($signed(carry5_q.a[A_W-1:HALF]));
      al = DISC_W'(carry5_q.a[HALF-1:0]);
      ch = DISC_W'($signed(carry5_q.c[C_W-1:HALF]));
      cl = DISC_W'(carry5_q.c[HALF-1:0]);
      bb_hh6_q <= bh * bh;
      bb_hl6_q <= bh * bl;
      bb_ll6_q <= bl * bl;
      ac_hh6_q <= ah * ch;
      ac_hl6_q <= ah * cl;
      ac_lh6_q <= al * ch;
      ac_ll6_q <= al * cl;
      carry6_q <= carry5_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Stage 7: disc = B^2 - AC. A negative one is a miss: the square root sees 0.
  // ---------------------------------------------------------------------------
  logic [DISC_W-1:0] disc7_q;
  logic              disc_neg7_q, disc_pos7_q;
  carry_t            carry7_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[6]) begin : s7_load
      logic [DISC_W-1:0] bb, ac, disc;
      bb   = (bb_hh6_q << (2*HALF)) + (bb_hl6_q << (HALF + 1)) + bb_ll6_q;
      ac   = (ac_hh6_q << (2*HALF)) + ((ac_hl6_q + ac_lh6_q) << HALF) + ac_ll6_q;
      disc = bb - ac;
      disc7_q     <= disc[DISC_W-1] ? '0 : disc;
      disc_neg7_q <= disc[DISC_W-1];
      disc_pos7_q <= !disc[DISC_W-1] && (|disc);
      carry7_q    <= carry6_q;
    end
  end

  // ---------------------------------------------------------------------------
  // The square root: ROOT_STAGES stages of STEP result bits, most significant
  // first. A step brings down the next two discriminant bits into the
  // remainder and subtracts 4 s + 1 when it fits (the result bit is 1).
  // Root stage r's registers sit at [r*W +: W] of flat vectors.
  // ---------------------------------------------------------------------------
  // The last stage's remainder and leftover bits are read by nothing (the
  // root is all that is wanted); synthesis drops those registers.
  /* verilator lint_off UNUSEDSIGNAL */
  logic [ROOT_STAGES*DISC_W-1:0]  rest_q;   // discriminant bits still to bring down, left-aligned
  logic [ROOT_STAGES*REM_W-1:0]   rem_q;
  /* verilator lint_on UNUSEDSIGNAL */
  logic [ROOT_STAGES*ROOT_W-1:0]  root_q;
  logic [ROOT_STAGES-1:0]         neg_q, pos_q;
  logic [ROOT_STAGES*CARRY_W-1:0] carry_q;

  for (genvar r = 0; r < ROOT_STAGES; r++) begin : g_root
    // Result bits this stage decides: STEP, fewer in the first stage when
    // ROOT_W is not a multiple of STEP.
    localparam int BITS = (r == 0 && ROOT_W % STEP != 0) ? ROOT_W % STEP : STEP;
    logic [DISC_W-1:0]  rest_in;
    logic [REM_W-1:0]   rem_in;
    logic [ROOT_W-1:0]  root_in;
    logic               neg_in, pos_in;
    logic [CARRY_W-1:0] carry_in;
    if (r == 0) begin : g_first
      assign rest_in  = disc7_q;
      assign rem_in   = '0;
      assign root_in  = '0;
      assign neg_in   = disc_neg7_q;
      assign pos_in   = disc_pos7_q;
      assign carry_in = carry7_q;
    end else begin : g_next
      assign rest_in  = rest_q[(r-1)*DISC_W +: DISC_W];
      assign rem_in   = rem_q[(r-1)*REM_W +: REM_W];
      assign root_in  = root_q[(r-1)*ROOT_W +: ROOT_W];
      assign neg_in   = neg_q[r-1];
      assign pos_in   = pos_q[r-1];
      assign carry_in = carry_q[(r-1)*CARRY_W +: CARRY_W];
    end
    always_ff @(posedge clk_i) begin
      if (stage_load[FRONT + r]) begin : step_load
        logic [DISC_W-1:0] rest;
        logic [REM_W-1:0]  rem, trial;
        logic [ROOT_W-1:0] root;
        rest = rest_in;
        rem  = rem_in;
        root = root_in;
        for (int b = 0; b < BITS; b++) begin
          rem   = {rem[REM_W-3:0], rest[DISC_W-1 -: 2]};
          rest  = rest << 2;
          trial = (REM_W'(root) << 2) | REM_W'(1);
          if (rem >= trial) begin
            rem  = rem - trial;
            root = {root[ROOT_W-2:0], 1'b1};
          end else begin
            root = {root[ROOT_W-2:0], 1'b0};
          end
        end
        rest_q[r*DISC_W +: DISC_W]    <= rest;
        rem_q[r*REM_W +: REM_W]       <= rem;
        root_q[r*ROOT_W +: ROOT_W]    <= root;
        neg_q[r]                      <= neg_in;
        pos_q[r]                      <= pos_in;
        carry_q[r*CARRY_W +: CARRY_W] <= carry_in;
      end
    end
  end

  // ---------------------------------------------------------------------------
  // Root 1: the two roots in their forms without cancellation, each as
  // num / den with den > 0 (den = 0: no such root), ordered nearer first.
  //   first  = big / 2A, leaving when B < 0 and disc > 0
  //   second = C / 2big, leaving when B >= 0 and disc > 0
  // ---------------------------------------------------------------------------
  typedef struct packed {
    logic [NUM_W-1:0] num;
    logic [DEN_W-1:0] den;
    logic             leaving;
    logic             ahead;
  } root_t;
  // What the last stages keep of a root besides its products.
  typedef struct packed {
    logic [DEN_W-1:0] den;
    logic             leaving;
    logic             ahead;
  } pick_t;

  localparam int S1 = FRONT + ROOT_STAGES;  // the first stage after the square root
  localparam int DEN2_W = NUM_W + 1;         // 2A and 2big, signed
  carry_t            carry_r;
  logic [ROOT_W-1:0] s_root;
  assign carry_r = carry_q[(ROOT_STAGES-1)*CARRY_W +: CARRY_W];
  assign s_root  = root_q[(ROOT_STAGES-1)*ROOT_W +: ROOT_W];

  root_t near1_q, far1_q;
  logic  miss1_q;
  logic [OH_W-1:0]      oh1_q;
  logic [DH_W-1:0]      dh1_q;
  logic [LEN2_W-1:0]    len2_r1_q;
  logic [DIR_W-1:0]     ddom_r1_q;
  logic [SEG_W-1:0]     seg_r1_q;
  logic [RAY_ID_W-1:0]  ray_id_r1_q;
  logic [PRIM_ID_W-1:0] prim_id_r1_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[S1]) begin : r1_load
      logic                    b_neg, pos, a_neg, big_neg, swap;
      logic signed [NUM_W-1:0] b_ext, s_ext, big, num1, num2;
      logic signed [DEN2_W-1:0] den1, den2;
      logic                    leaving1, leaving2, ahead1, ahead2;
      b_neg   = carry_r.b[B_W-1];
      pos     = pos_q[ROOT_STAGES-1];
      b_ext   = NUM_W'($signed(carry_r.b));
      s_ext   = NUM_W'(s_root);
      big     = b_neg ? s_ext - b_ext : -(b_ext + s_ext);
      a_neg   = carry_r.a[A_W-1];
      big_neg = big[NUM_W-1];
      num1 = big;
      den1 = DEN2_W'($signed(carry_r.a)) <<< 1;
      num2 = NUM_W'($signed(carry_r.c));
      den2 = DEN2_W'(big) <<< 1;
      if (den1[DEN2_W-1]) begin
        num1 = -num1;
        den1 = -den1;
      end
      if (den2[DEN2_W-1]) begin
        num2 = -num2;
        den2 = -den2;
      end
      leaving1 = b_neg && pos;
      leaving2 = !b_neg && pos;
      ahead1   = (|den1) && !num1[NUM_W-1] && (|num1);
      ahead2   = (|den2) && !num2[NUM_W-1] && (|num2);
      swap = ahead1 && ahead2 && pos && (a_neg == big_neg);
      near1_q      <= swap ? {num2, DEN_W'(den2), leaving2, ahead2} : {num1, DEN_W'(den1), leaving1, ahead1};
      far1_q       <= swap ? {num1, DEN_W'(den1), leaving1, ahead1} : {num2, DEN_W'(den2), leaving2, ahead2};
      miss1_q      <= neg_q[ROOT_STAGES-1];
      oh1_q        <= carry_r.oh;
      dh1_q        <= carry_r.dh;
      len2_r1_q    <= carry_r.len2;
      ddom_r1_q    <= carry_r.ddom;
      seg_r1_q     <= carry_r.seg;
      ray_id_r1_q  <= carry_r.ray_id;
      prim_id_r1_q <= carry_r.prim_id;
    end
  end

  // ---------------------------------------------------------------------------
  // Root 2: per root the products of halves of
  //   (q.w) den, 2 num (d.w), W den   (the plane test)
  //   num |d_dom|, t_max den           (t and the segment rule)
  // den = Dh 2^DEN_LO + Dl, num = Nh 2^NUM_LO + Nl (low halves unsigned).
  // ---------------------------------------------------------------------------
  typedef struct packed {
    logic [PLANE_W-1:0]   ohd_h, ohd_l, ndh_h, ndh_l, wden_h, wden_l;
    logic [T_NUM_W-1:0]   t_h, t_l;
    logic [SEG_CMP_W-1:0] seg_h, seg_l;
  } prod_t;

  localparam int PROD_W = 6 * PLANE_W + 2 * T_NUM_W + 2 * SEG_CMP_W;

  // A root's prod_t, as a flat vector (Yosys 0.23 returns no struct).
  function automatic logic [PROD_W-1:0] root_products(logic [NUM_W-1:0] num, logic [DEN_W-1:0] den,
                                                      logic [OH_W-1:0] oh, logic [DH_W-1:0] dh,
                                                      logic [LEN2_W-1:0] len2, logic [DIR_W-1:0] ddom,
                                                      logic [SEG_W-1:0] seg);
    logic signed [PLANE_W-1:0] p_dh, p_dl, p_nh, p_nl, p_oh, p_dhgt;
    logic signed [T_NUM_W-1:0] t_nh, t_nl;
    logic [SEG_CMP_W-1:0]      s_dh, s_dl;
    p_dh   = PLANE_W'(den[DEN_W-1:DEN_LO]);
    p_dl   = PLANE_W'(den[DEN_LO-1:0]);
    p_nh   = PLANE_W'($signed(num[NUM_W-1:NUM_LO]));
    p_nl   = PLANE_W'(num[NUM_LO-1:0]);
    p_oh   = PLANE_W'($signed(oh));
    p_dhgt = PLANE_W'($signed(dh));
    t_nh   = T_NUM_W'($signed(num[NUM_W-1:NUM_LO]));
    t_nl   = T_NUM_W'(num[NUM_LO-1:0]);
    s_dh   = SEG_CMP_W'(den[DEN_W-1:DEN_LO]);
    s_dl   = SEG_CMP_W'(den[DEN_LO-1:0]);
    root_products = {p_oh * p_dh, p_oh * p_dl,                        // ohd_h, ohd_l
                     (p_nh * p_dhgt) <<< 1, (p_nl * p_dhgt) <<< 1,    // ndh_h, ndh_l
                     PLANE_W'(len2) * p_dh, PLANE_W'(len2) * p_dl,    // wden_h, wden_l
                     t_nh * T_NUM_W'(ddom), t_nl * T_NUM_W'(ddom),    // t_h, t_l
                     SEG_CMP_W'(seg) * s_dh, SEG_CMP_W'(seg) * s_dl}; // seg_h, seg_l
  endfunction

  prod_t near2_p_q, far2_p_q;
  pick_t near2_q, far2_q;
  logic  miss2_q;
  logic [RAY_ID_W-1:0]  ray_id_r2_q;
  logic [PRIM_ID_W-1:0] prim_id_r2_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[S1 + 1]) begin
      near2_p_q    <= root_products(near1_q.num, near1_q.den, oh1_q, dh1_q, len2_r1_q, ddom_r1_q, seg_r1_q);
      far2_p_q     <= root_products(far1_q.num, far1_q.den, oh1_q, dh1_q, len2_r1_q, ddom_r1_q, seg_r1_q);
      near2_q      <= {near1_q.den, near1_q.leaving, near1_q.ahead};
      far2_q       <= {far1_q.den, far1_q.leaving, far1_q.ahead};
      miss2_q      <= miss1_q;
      ray_id_r2_q  <= ray_id_r1_q;
      prim_id_r2_q <= prim_id_r1_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Root 3: the products' sums: per root the plane test's height and bound,
  // t_num, and the segment rule's two sides.
  // ---------------------------------------------------------------------------
  typedef struct packed {
    logic [PLANE_W-1:0]   height;   // (q.w) den + 2 num (d.w)
    logic [PLANE_W-1:0]   bound;    // W den
    logic [T_NUM_W-1:0]   t_num;
    logic [SEG_CMP_W-1:0] seg_bound;
  } sums_t;

  // A value from its products of halves: hi 2^shift + lo.
  function automatic logic [PLANE_W-1:0] plane_join(logic [PLANE_W-1:0] hi, logic [PLANE_W-1:0] lo, int shift);
    plane_join = (hi << shift) + lo;
  endfunction
  function automatic logic [T_NUM_W-1:0] t_join(logic [T_NUM_W-1:0] hi, logic [T_NUM_W-1:0] lo);
    t_join = (hi << NUM_LO) + lo;
  endfunction
  function automatic logic [SEG_CMP_W-1:0] seg_join(logic [SEG_CMP_W-1:0] hi, logic [SEG_CMP_W-1:0] lo);
    seg_join = (hi << DEN_LO) + lo;
  endfunction

  sums_t near3_s_q, far3_s_q;
  pick_t near3_q, far3_q;
  logic  miss3_q;
  logic [RAY_ID_W-1:0]  ray_id_r3_q;
  logic [PRIM_ID_W-1:0] prim_id_r3_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[S1 + 2]) begin
      near3_s_q    <= {plane_join(near2_p_q.ohd_h, near2_p_q.ohd_l, DEN_LO) +
                           plane_join(near2_p_q.ndh_h, near2_p_q.ndh_l, NUM_LO),
                       plane_join(near2_p_q.wden_h, near2_p_q.wden_l, DEN_LO),
                       t_join(near2_p_q.t_h, near2_p_q.t_l), seg_join(near2_p_q.seg_h, near2_p_q.seg_l)};
      far3_s_q     <= {plane_join(far2_p_q.ohd_h, far2_p_q.ohd_l, DEN_LO) +
                           plane_join(far2_p_q.ndh_h, far2_p_q.ndh_l, NUM_LO),
                       plane_join(far2_p_q.wden_h, far2_p_q.wden_l, DEN_LO),
                       t_join(far2_p_q.t_h, far2_p_q.t_l), seg_join(far2_p_q.seg_h, far2_p_q.seg_l)};
      near3_q      <= near2_q;
      far3_q       <= far2_q;
      miss3_q      <= miss2_q;
      ray_id_r3_q  <= ray_id_r2_q;
      prim_id_r3_q <= prim_id_r2_q;
    end
  end

  // ---------------------------------------------------------------------------
  // Root 4: the root taken (the nearer ahead and between the planes, else the
  // farther), then the segment rule (t_num 2^F <= t_max den); the result. A
  // miss is all zeros but its ids.
  // ---------------------------------------------------------------------------
  // Ahead of the origin and between the planes: |height| <= half_len (W den).
  function automatic logic on_surface(logic [PLANE_W-1:0] height, logic [PLANE_W-1:0] half_len, logic ahead);
    logic [PLANE_W-1:0] mag;
    mag = height[PLANE_W-1] ? -height : height;
    on_surface = ahead && mag <= half_len;
  endfunction

  rt_pkg::isect_res_t res_q;

  always_ff @(posedge clk_i) begin
    if (stage_load[S1 + 3]) begin : r4_load
      logic                 take_near, take_far, hit;
      logic [T_NUM_W-1:0]   t_num;
      logic [SEG_CMP_W-1:0] seg_bound;
      logic [DEN_W-1:0]     den;
      logic                 leaving;
      take_near = on_surface(near3_s_q.height, near3_s_q.bound, near3_q.ahead);
      take_far  = !take_near && on_surface(far3_s_q.height, far3_s_q.bound, far3_q.ahead);
      t_num     = take_near ? near3_s_q.t_num : far3_s_q.t_num;
      seg_bound = take_near ? near3_s_q.seg_bound : far3_s_q.seg_bound;
      den       = take_near ? near3_q.den : far3_q.den;
      leaving   = take_near ? near3_q.leaving : far3_q.leaving;
      hit = !miss3_q && (take_near || take_far) && (SEG_CMP_W'(t_num) << SEG_FRAC) <= seg_bound;
      res_q.ray_id  <= ray_id_r3_q;
      res_q.prim_id <= prim_id_r3_q;
      res_q.hit     <= hit;
      res_q.t_num   <= hit ? t_num : '0;
      res_q.det     <= hit ? DET_ABS_W'(den) : '0;
      res_q.u_num   <= hit ? BARY_W'(leaving) : '0;
      res_q.v_num   <= '0;
    end
  end

  assign res_data_o  = res_q;

`ifdef RT_ASSERT_ON
`include "rt_assert.svh"
  `RT_ASSERT_STATIC(g_latency_check, rt_pkg::QUADRIC_LATENCY == NUM_STAGES,
                    "rt_quadric: its stages differ from rt_pkg::QUADRIC_LATENCY")
  // The stream checks are rt_stall_stages'.
`endif

endmodule
