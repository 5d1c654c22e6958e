# The two parameters every fixed-point format derives from (sw/golden/formats.h).
# A precision sweep configures one build tree per pair: a rebuild, not an edit.
set(LANCER_POS_BITS 16 CACHE STRING "Bits of a position on the scene lattice (4..24)")
set(LANCER_DIR_BITS 16 CACHE STRING "Bits of a signed direction component (4..24)")
if(LANCER_POS_BITS LESS 4 OR LANCER_POS_BITS GREATER 24 OR LANCER_DIR_BITS LESS 4 OR LANCER_DIR_BITS GREATER 24)
  message(FATAL_ERROR "LANCER_POS_BITS and LANCER_DIR_BITS must lie in 4..24 "
                      "(got ${LANCER_POS_BITS} and ${LANCER_DIR_BITS})")
endif()
set(LANCER_MEM_ADDR_BITS 24 CACHE STRING "Address bits of each memory region of the traversal units (10..30)")
if(LANCER_MEM_ADDR_BITS LESS 10 OR LANCER_MEM_ADDR_BITS GREATER 30)
  message(FATAL_ERROR "LANCER_MEM_ADDR_BITS must lie in 10..30 (got ${LANCER_MEM_ADDR_BITS})")
endif()
set(LANCER_FORMAT_DEFINES LANCER_POS_BITS=${LANCER_POS_BITS} LANCER_DIR_BITS=${LANCER_DIR_BITS}
                          LANCER_MEM_ADDR_BITS=${LANCER_MEM_ADDR_BITS})
set(LANCER_GENERATED_DIR ${CMAKE_BINARY_DIR}/generated)
set(LANCER_RT_PKG ${LANCER_GENERATED_DIR}/rtl/rt_pkg.sv)
message(STATUS "Lancer number formats: positions ${LANCER_POS_BITS} bits, directions ${LANCER_DIR_BITS} bits")
