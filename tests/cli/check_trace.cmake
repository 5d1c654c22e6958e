# `lancer trace` and `lancer run` on a tiny rays file: the CSV and the JSON
# report carry what the README promises.
include(${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake)

must_run(printed ${LANCER} trace --rays ${DATA}/two.rays --accel grid --hits ${OUT}/two.csv --report ${OUT}/trace.json)
file(STRINGS ${OUT}/two.csv lines)
list(GET lines 0 header)
if(NOT header STREQUAL "ray,hit,prim,t,u,v")
  message(FATAL_ERROR "bad CSV header: ${header}")
endif()
list(LENGTH lines count)
if(NOT count EQUAL 3)
  message(FATAL_ERROR "expected 2 rows, got: ${lines}")
endif()
list(GET lines 1 row)
if(NOT row MATCHES "^0,1,3[01],1091\\.9[0-9]*,")  # the tall block front face, from z = -800
  message(FATAL_ERROR "ray 0 should hit the tall block at t = 1091.97: ${row}")
endif()

must_run(printed ${LANCER} run --rays ${DATA}/two.rays --model golden --report ${OUT}/run.json --hits ${OUT}/run.csv)
json_of(${OUT}/run.json json)
require_json_keys("${json}" run rays mismatches cycles intersection_tests clock_hz intersections_per_second host_seconds
                  reference_disagreements)
string(JSON mismatches GET "${json}" mismatches)
string(JSON rays GET "${json}" rays)
if(NOT mismatches EQUAL 0 OR NOT rays EQUAL 2)
  message(FATAL_ERROR "unexpected run report: ${json}")
endif()
file(STRINGS ${OUT}/run.csv run_lines)
list(GET run_lines 0 run_header)
if(NOT run_header STREQUAL "ray,hit,prim,t,u,v,t_num,det,u_num,v_num")
  message(FATAL_ERROR "bad hardware CSV header: ${run_header}")
endif()
