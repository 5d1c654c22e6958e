// The ports every per-ray setup shares, included in the port lists of
// rt_setup_front, rt_grid_setup, rt_mirror_pairs and rt_octree_setup (which add the figures
// they compute). Needs the module's SlotW; every line ends with a comma.

  input  logic                       clk_i,
  input  logic                       rst_ni,

  // A ray accepted into slot slot_i (valid_i high in the cycle before edge t).
  input  logic                       valid_i,
  input  logic [SlotW-1:0]           slot_i,
  input  rt_pkg::isect_ray_t         ray_i,

  // The ray and its slot after the three stages (after edge t+2), and its dominant
  // max |d|.
  output logic                       valid_o,
  output logic [SlotW-1:0]           slot_o,
  output rt_pkg::isect_ray_t         ray_o,
  output logic [rt_pkg::DIR_W-1:0]   dom_o,
