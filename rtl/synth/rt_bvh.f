# Sources of rt_bvh for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
-f rt_trav_shell.f
lib/rt_mirror_pairs.sv
bvh/rt_bvh_box.sv
bvh/rt_bvh.sv
