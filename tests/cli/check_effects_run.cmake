# `lancer run` on a scene with effects: every wave through the Verilated RTL
# (and the SystemC models), bit-exact against golden, the plan and the SPD
# counts in the report, no self-hits; the float reference's counts beside them.
include(${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake)

foreach(run grid:rtl octree:rtl isect:rtl grid:systemc octree:rtl-systemc)
  string(REPLACE ":" ";" parts ${run})
  list(GET parts 0 accel)
  list(GET parts 1 model)
  must_run(printed ${LANCER} run --scene ${DATA}/spheres.nff --sampling corners --accel ${accel} --model ${model}
           --width 20 --height 20 --image ${OUT}/effects_${accel}.png --report ${OUT}/effects_${accel}.json)
  foreach(line "refraction yes" "any-hit saving" "SPD count" "bit-exact vs golden")
    if(accel STREQUAL "isect" AND line STREQUAL "any-hit saving")
      continue()
    endif()
    string(FIND "${printed}" "${line}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "run (${accel}) should print '${line}':\n${printed}")
    endif()
  endforeach()
  file(READ ${OUT}/effects_${accel}.json json)
  string(JSON mismatches GET "${json}" mismatches)
  string(JSON self GET "${json}" self_hits)
  string(JSON eye GET "${json}" classes primary rays)
  string(JSON shadow GET "${json}" shadow_rays)
  string(JSON shadowClass GET "${json}" classes shadow rays)
  string(JSON refract GET "${json}" refract_rays)
  string(JSON cycles GET "${json}" classes shadow cycles)
  string(JSON refShadow GET "${json}" float_reference shadow_rays)
  if(NOT mismatches EQUAL 0 OR NOT self EQUAL 0 OR NOT eye EQUAL 441 OR NOT shadow EQUAL shadowClass
     OR NOT refract GREATER 0 OR NOT cycles GREATER 0 OR NOT refShadow GREATER 0)
    message(FATAL_ERROR "unexpected effects report (${accel}): ${json}")
  endif()
endforeach()

# --effects primary,shadow: no secondary ray, no wave beyond the shadow rays.
must_run(printed ${LANCER} run --scene ${DATA}/spheres.nff --effects primary,shadow --accel grid --model golden
         --width 16 --height 16 --report ${OUT}/effects_restricted.json)
file(READ ${OUT}/effects_restricted.json json)
string(JSON reflect GET "${json}" reflect_rays)
string(JSON waves LENGTH "${json}" wave_rays)
string(JSON reflection ERROR_VARIABLE none GET "${json}" classes reflection)
if(NOT reflect EQUAL 0 OR NOT waves EQUAL 2 OR NOT none)
  message(FATAL_ERROR "--effects primary,shadow should trace two waves and no reflection: ${json}")
endif()
