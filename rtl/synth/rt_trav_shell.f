# Sources of rt_trav_shell, the traversal shell every traversal unit is built
# on, relative to rtl/, in compile order (read by the units' lists with -f).
lib/rt_fifo.sv
lib/rt_pipe_reg.sv
lib/rt_pipe_regs.sv
lib/rt_rr_arb.sv
lib/rt_closest_hit.sv
lib/rt_exit_test.sv
lib/rt_setup_front.sv
lib/rt_idx_count.sv
lib/rt_stall_stages.sv
isect/rt_isect.sv
isect/rt_quadric.sv
lib/rt_trav_shell.sv
