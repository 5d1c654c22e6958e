// rt_setup_front: what the per-ray setups of every traversal unit share
// (rt_grid_setup, rt_octree_setup): the two-stage pipeline that carries the
// ray and its slot, and the direction's arithmetic of stage 1, |d[a]|, the
// active axes (d[a] != 0), the negative ones and the dominant max |d[a]|.
//
// The unit's own stage arithmetic sits beside it: stage 1 loads with valid_i
// (from ray_i and mag_o), stage 2 with s1_valid_o (from the unit's stage-1
// registers and s1_active_o / s1_neg_o). The registers load only in the cycle
// a ray passes (enabled flops), so a simulator evaluates them once per ray.
//
// Latency:    a ray accepted at edge t (valid_i high in the cycle before t) is
//             on valid_o after edge t+1; the slot loads it at edge t+2.
// Throughput: one ray per cycle; the pipeline never stalls (the slot is
//             reserved when the ray is accepted).
module rt_setup_front #(
  parameter int unsigned SlotW = 5  // width of the slot index carried along
) (
  input  logic                       clk_i,
  input  logic                       rst_ni,

  input  logic                       valid_i,
  input  logic [SlotW-1:0]           slot_i,
  input  rt_pkg::isect_ray_t         ray_i,
  output logic [3*rt_pkg::DIR_W-1:0] mag_o,        // |d| of ray_i {z, y, x}, for stage 1

  output logic                       s1_valid_o,   // stage 1 holds a ray
  output logic [2:0]                 s1_active_o,  // its axes with d != 0
  output logic [2:0]                 s1_neg_o,     // its axes with d < 0

  output logic                       valid_o,      // stage 2
  output logic [SlotW-1:0]           slot_o,
  output rt_pkg::isect_ray_t         ray_o,
  output logic [2:0]                 active_o,
  output logic [2:0]                 neg_o,
  output logic [rt_pkg::DIR_W-1:0]   dom_o         // max |d|
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

  // ---- Valid bits of both stages ------------------------------------------------
  logic s1_valid_q, s2_valid_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      s1_valid_q <= 1'b0;
      s2_valid_q <= 1'b0;
    end else begin
      s1_valid_q <= valid_i;
      s2_valid_q <= s1_valid_q;
    end
  end

  // ---- Stage 1 ------------------------------------------------------------------
  logic [SlotW-1:0]   s1_slot_q;
  rt_pkg::isect_ray_t s1_ray_q;
  logic [2:0]         s1_active_q, s1_neg_q;
  logic [DIR_W-1:0]   s1_dom_q;

  always_ff @(posedge clk_i) begin
    if (valid_i) begin : b_stage1
      logic [DIR_W-1:0] d, mag, dom;
      dom = '0;
      for (int a = 0; a < 3; a++) begin
        d   = ray_i.dir[a];
        mag = mag_o[a*DIR_W +: DIR_W];
        s1_active_q[a] <= (d != '0);
        s1_neg_q[a]    <= d[DIR_W-1];
        if (mag > dom) dom = mag;
      end
      s1_dom_q  <= dom;
      s1_slot_q <= slot_i;
      s1_ray_q  <= ray_i;
    end
  end

  // ---- Stage 2 ------------------------------------------------------------------
  logic [SlotW-1:0]   s2_slot_q;
  rt_pkg::isect_ray_t s2_ray_q;
  logic [2:0]         s2_active_q, s2_neg_q;
  logic [DIR_W-1:0]   s2_dom_q;

  always_ff @(posedge clk_i) begin
    if (s1_valid_q) begin
      s2_slot_q   <= s1_slot_q;
      s2_ray_q    <= s1_ray_q;
      s2_active_q <= s1_active_q;
      s2_neg_q    <= s1_neg_q;
      s2_dom_q    <= s1_dom_q;
    end
  end

  assign s1_valid_o  = s1_valid_q;
  assign s1_active_o = s1_active_q;
  assign s1_neg_o    = s1_neg_q;
  assign valid_o     = s2_valid_q;
  assign slot_o      = s2_slot_q;
  assign ray_o       = s2_ray_q;
  assign active_o    = s2_active_q;
  assign neg_o       = s2_neg_q;
  assign dom_o       = s2_dom_q;

endmodule
