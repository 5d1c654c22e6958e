# What the `cmake -P` checks of the CLI (check_*.cmake) share: running the
# command, reading a report, and requiring its keys.

# Runs the command ARGN; its standard output goes to `var`, and a failure ends
# the check with both outputs.
function(must_run var)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}\n${out}\n${err}")
  endif()
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

# The text of a JSON report.
function(json_of file var)
  file(READ ${file} json)
  set(${var} "${json}" PARENT_SCOPE)
endfunction()

# Ends the check unless the JSON text `json` has every top-level key of ARGN;
# `what` names the report in the message ("run", "whitted").
function(require_json_keys json what)
  foreach(key ${ARGN})
    string(JSON value ERROR_VARIABLE missing GET "${json}" ${key})
    if(missing)
      message(FATAL_ERROR "${what} report lacks '${key}': ${json}")
    endif()
  endforeach()
endfunction()
