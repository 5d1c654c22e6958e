# Sources of rt_octree for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
-f rt_trav_shell.f
lib/rt_mirror_pairs.sv
octree/rt_octree_setup.sv
octree/rt_octree.sv
