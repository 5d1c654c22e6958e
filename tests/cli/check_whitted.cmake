# `lancer render --whitted` and `lancer spd`: the plan and the SPD counts on the
# terminal and in the report; the generated NFF file is the built-in scene.
include(${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake)

must_run(printed ${LANCER} render --scene ${DATA}/spheres.nff --whitted --sampling corners --width 24 --height 24
         --image ${OUT}/spheres.png --report ${OUT}/spheres.json)
foreach(line "refraction yes  material f@24: T 0.9, index of refraction 1.5" "eye hit rays" "self-hits 0")
  string(FIND "${printed}" "${line}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "render --whitted should print '${line}':\n${printed}")
  endif()
endforeach()
json_of(${OUT}/spheres.json json)
require_json_keys("${json}" whitted eye_hit_rays reflect_rays refract_rays shadow_rays shadow_rays_blocked self_hits
                  plan)
string(JSON eye GET "${json}" eye_rays)
string(JSON reflect GET "${json}" reflect_rays)
string(JSON refract GET "${json}" refract_rays)
string(JSON self GET "${json}" self_hits)
string(JSON enabled GET "${json}" plan classes refraction enabled)
string(JSON primary GET "${json}" classes primary rays)
if(NOT eye EQUAL 625 OR NOT primary EQUAL 625 OR NOT reflect GREATER 0 OR NOT refract GREATER 0 OR NOT self EQUAL 0
   OR NOT enabled)
  message(FATAL_ERROR "unexpected whitted report: ${json}")
endif()

# The generated file and the built-in scene give the same counts.
execute_process(COMMAND ${LANCER} spd tetra OUTPUT_FILE ${OUT}/tetra.nff RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "lancer spd tetra failed (${status})")
endif()
foreach(scene ${OUT}/tetra.nff builtin:spd-tetra)
  must_run(printed ${LANCER} render --scene ${scene} --whitted --sampling corners --width 64 --height 64
           --image ${OUT}/tetra.png --report ${OUT}/tetra.json)
  json_of(${OUT}/tetra.json json)
  string(JSON hits GET "${json}" eye_hit_rays)
  string(JSON shadows GET "${json}" shadow_rays)
  list(APPEND counts "${hits}/${shadows}")
endforeach()
list(GET counts 0 fromFile)
list(GET counts 1 builtin)
if(NOT fromFile STREQUAL builtin OR fromFile STREQUAL "0/0")
  message(FATAL_ERROR "lancer spd tetra and builtin:spd-tetra differ: ${counts}")
endif()
