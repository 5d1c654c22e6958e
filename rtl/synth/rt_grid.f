# Sources of rt_grid for scripts/synth, relative to rtl/, in compile order
# (the generated package is read first by the script).
-f rt_trav_shell.f
grid/rt_grid_setup.sv
grid/rt_grid.sv
