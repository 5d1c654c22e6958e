# The traversal units: the one list a new unit adds its name to. What knows of
# the units derives from it: the RTL (rtl/<unit>/unit.cmake, rtl/CMakeLists.txt),
# the SystemC traits and systems, the driver's devices, the golden registry
# (golden/unit_list.h, generated below: fx::TraversalUnits and fx::UnitKind),
# and scripts/regress, which reads this line.
set(LANCER_TRAVERSAL_UNITS grid octree bvh CACHE INTERNAL "The traversal units (rtl/<unit>/)")

# lancer_unit_descriptor(<unit> <var>): the C++ descriptor of a unit of the
# list, in lancer::fx (grid -> GridUnit: golden/<unit>_unit.h).
function(lancer_unit_descriptor unit var)
  string(SUBSTRING ${unit} 0 1 first)
  string(SUBSTRING ${unit} 1 -1 rest)
  string(TOUPPER ${first} first)
  set(${var} ${first}${rest}Unit PARENT_SCOPE)
endfunction()

# golden/unit_list.h: the descriptors' headers, the descriptors and their kinds,
# in the list's order (the golden library and rt_pkg's bootstrap include it).
set(LANCER_UNIT_LIST_DIR ${CMAKE_BINARY_DIR}/generated/include)
block()
  set(includes "")
  set(descriptors "")
  set(kinds "")
  foreach(unit IN LISTS LANCER_TRAVERSAL_UNITS)
    lancer_unit_descriptor(${unit} descriptor)
    string(REGEX REPLACE "Unit$" "" kind ${descriptor})
    string(APPEND includes "#include \"golden/${unit}_unit.h\"\n")
    list(APPEND descriptors ${descriptor})
    list(APPEND kinds ${kind})
  endforeach()
  list(JOIN descriptors ", " descriptors)
  list(JOIN kinds ", " kinds)
  file(CONFIGURE OUTPUT ${LANCER_UNIT_LIST_DIR}/golden/unit_kinds.h CONTENT
"// The kinds of LANCER_TRAVERSAL_UNITS (cmake/Units.cmake), generated: do not edit.
#pragma once
#define LANCER_TRAVERSAL_UNIT_KINDS ${kinds}
" @ONLY)
  file(CONFIGURE OUTPUT ${LANCER_UNIT_LIST_DIR}/golden/unit_list.h CONTENT
"// The descriptors of LANCER_TRAVERSAL_UNITS (cmake/Units.cmake), generated: do not edit.
#pragma once
${includes}
#define LANCER_TRAVERSAL_UNIT_DESCRIPTORS ${descriptors}
" @ONLY)
endblock()
