# Sources of rt_grid for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
lib/rt_fifo.sv
lib/rt_rr_arb.sv
lib/rt_closest_hit.sv
lib/rt_exit_test.sv
lib/rt_setup_front.sv
isect/rt_isect.sv
lib/rt_trav_shell.sv
grid/rt_grid_setup.sv
grid/rt_grid_slots.sv
grid/rt_grid.sv
