# rt_grid's build (read by lancer_rtl_traversal_unit, rtl/CMakeLists.txt): its
# sources in compile order after the package and the shell, and its own
# parameter CellQueue (docs/grid-unit.md), carried to the models as a definition.
set(LANCER_GRID_CELL_QUEUE 2 CACHE STRING
    "Cells per ray slot of the Verilated rt_grid read and not finished (CellQueue: 2, 4, 8; 2 = one cell ahead)")
if(NOT LANCER_GRID_CELL_QUEUE MATCHES "^(2|4|8)$")
  message(FATAL_ERROR "LANCER_GRID_CELL_QUEUE must be 2, 4 or 8 (got ${LANCER_GRID_CELL_QUEUE})")
endif()
set(unit_lib_sources)
set(unit_sources rt_grid_setup.sv rt_grid.sv)
# Its configuration port besides cfg_slots_i (the models bind it by name).
set(unit_cfg_port cfg_res_i)
set(unit_params CellQueue=${LANCER_GRID_CELL_QUEUE})
set(unit_definitions LANCER_GRID_CELL_QUEUE=${LANCER_GRID_CELL_QUEUE})
