# Sources of rt_octree for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
lib/rt_fifo.sv
lib/rt_rr_arb.sv
lib/rt_closest_hit.sv
lib/rt_exit_test.sv
lib/rt_setup_front.sv
isect/rt_isect.sv
lib/rt_trav_shell.sv
octree/rt_octree_setup.sv
octree/rt_octree_slots.sv
octree/rt_octree.sv
