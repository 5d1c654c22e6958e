# Runs the Icarus Verilog bench of rt_isect (CTest test rtl_isect_icarus):
#   1. make_isect_vectors writes golden vectors (hard cases + random pairs);
#   2. Icarus-11 copies of the package and the DUT (see below);
#   3. iverilog -g2012 compiles package, DUT and tb_rt_isect.sv; vvp runs them.
# Fails unless the bench prints "N passed, 0 failed" with N = every vector.
#
# Icarus 11 aborts on a struct typedef inside a package (elab_type.cc:86,
# "failed assertion scope"; fixed in Icarus 12). The copies move the struct
# typedefs of rt_pkg.sv out of the package into the compilation unit, and
# rename rt_pkg::isect_*_t to isect_*_t in the DUT; nothing else changes.
#
# cmake -DVECTOR_TOOL=... -DIVERILOG=... -DVVP=... -DPKG=rt_pkg.sv -DDUT="rt_stall_stages.sv|rt_isect.sv"
#       -DTB=tb_rt_isect.sv -DWORK=dir [-DRANDOM=n] [-DMAX_HARD=n] [-DSTALL=pct]
#       [-DIDLE=pct] [-DSEED=s] -P run_icarus.cmake
foreach(var VECTOR_TOOL IVERILOG VVP PKG DUT TB WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_icarus.cmake: -D${var}=... is required")
  endif()
endforeach()
# Defaults of the optional settings, NAME=value.
foreach(default RANDOM=5000 MAX_HARD=100000 STALL=30 IDLE=20 SEED=1)
  string(REPLACE "=" ";" name_value ${default})
  list(GET name_value 0 name)
  list(GET name_value 1 value)
  if(NOT DEFINED ${name})
    set(${name} ${value})
  endif()
endforeach()
file(MAKE_DIRECTORY ${WORK})

# 1. Vectors.
execute_process(COMMAND ${VECTOR_TOOL} ${WORK}/vectors ${RANDOM} ${MAX_HARD}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "make_isect_vectors failed (${rc})")
endif()
file(STRINGS ${WORK}/vectors.count count)

# 2. Icarus-11 copies. gen_rt_pkg emits the parameters first, then the types.
file(READ ${PKG} pkg)
string(FIND "${pkg}" "typedef struct packed" first_type)
string(FIND "${pkg}" "endpackage" end_pkg REVERSE)
if(first_type LESS 0 OR end_pkg LESS first_type)
  message(FATAL_ERROR "unexpected layout of ${PKG}")
endif()
string(SUBSTRING "${pkg}" 0 ${first_type} pkg_params)
math(EXPR types_length "${end_pkg} - ${first_type}")
string(SUBSTRING "${pkg}" ${first_type} ${types_length} pkg_types)
if(pkg_types MATCHES "localparam")
  message(FATAL_ERROR "${PKG}: parameters after the types; update run_icarus.cmake")
endif()
file(WRITE ${WORK}/rt_pkg_icarus.sv
  "// Icarus-11 copy of ${PKG}: struct typedefs moved out of the package.\n"
  "${pkg_params}endpackage\n\n${pkg_types}")
# DUT: the sources of rt_isect in compile order, separated by '|'.
string(REPLACE "|" ";" dut_sources "${DUT}")
set(dut_copies)
foreach(source ${dut_sources})
  file(READ ${source} dut)
  string(REGEX REPLACE "rt_pkg::(isect_[a-z_]+_t)" "\\1" dut "${dut}")
  get_filename_component(name ${source} NAME_WE)
  file(WRITE ${WORK}/${name}_icarus.sv "// Icarus-11 copy of ${source}: type names unscoped.\n${dut}")
  list(APPEND dut_copies ${WORK}/${name}_icarus.sv)
endforeach()

# 3. Compile and run.
execute_process(COMMAND ${IVERILOG} -g2012 -Wall -Wno-timescale -o ${WORK}/tb_rt_isect.vvp
                        -s tb_rt_isect ${WORK}/rt_pkg_icarus.sv ${dut_copies} ${TB}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "iverilog failed (${rc}):\n${out}")
endif()
if(out)
  message(STATUS "iverilog:\n${out}")
endif()
execute_process(COMMAND ${VVP} -n ${WORK}/tb_rt_isect.vvp +vectors=${WORK}/vectors +n=${count}
                        +seed=${SEED} +stall=${STALL} +idle=${IDLE}
                WORKING_DIRECTORY ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vvp failed (${rc})")
endif()
if(NOT out MATCHES "tb_rt_isect: ([0-9]+) passed, 0 failed" OR NOT CMAKE_MATCH_1 EQUAL count)
  message(FATAL_ERROR "rt_isect under Icarus: mismatches (expected ${count} passed, 0 failed)")
endif()
if(NOT out MATCHES "\nPASS")
  message(FATAL_ERROR "rt_isect under Icarus: the bench did not report PASS")
endif()
