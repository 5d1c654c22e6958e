# rt_bvh's build (read by lancer_rtl_traversal_unit, rtl/CMakeLists.txt):
# its sources in compile order after the package and the shell: the modules
# of rtl/lib it shares with some other units, then its own.
set(unit_lib_sources rt_mirror_pairs.sv)
set(unit_sources rt_bvh_box.sv rt_bvh.sv)
# Its configuration port besides cfg_slots_i (the models bind it by name).
set(unit_cfg_port cfg_root_i)
set(unit_params)
set(unit_definitions)
