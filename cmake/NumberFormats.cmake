# The two parameters every fixed-point format derives from (sw/golden/formats.h).
# A precision sweep configures one build tree per pair: a rebuild, not an edit.
set(LANCER_POS_BITS 16 CACHE STRING "Bits of a position on the scene lattice (5..24, P + D >= 12)")
set(LANCER_DIR_BITS 16 CACHE STRING "Bits of a signed direction component (4..24)")
if(LANCER_POS_BITS LESS 4 OR LANCER_POS_BITS GREATER 24 OR LANCER_DIR_BITS LESS 4 OR LANCER_DIR_BITS GREATER 24)
  message(FATAL_ERROR "LANCER_POS_BITS and LANCER_DIR_BITS must lie in 4..24 "
                      "(got ${LANCER_POS_BITS} and ${LANCER_DIR_BITS})")
endif()
# The quadric record rounds its coefficients to K >= 8 bits, K = min(59 - P - D,
# P + D - 4, 2P - 2, 60 - 2P) (sw/golden/quadric.h): P >= 5 and P + D >= 12.
math(EXPR lancer_width_sum "${LANCER_POS_BITS} + ${LANCER_DIR_BITS}")
if(LANCER_POS_BITS LESS 5 OR lancer_width_sum LESS 12)
  message(FATAL_ERROR "LANCER_POS_BITS=${LANCER_POS_BITS}, LANCER_DIR_BITS=${LANCER_DIR_BITS}: the quadric "
                      "pipeline needs P >= 5 and P + D >= 12 (its coefficients' K bits, sw/golden/quadric.h)")
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
