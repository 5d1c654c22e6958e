# lancer_share_verilator_runtime(<model> <runtime> [LINK <libs...>] [OPTIONS <compile options...>])
#
# verilate() compiles Verilator's runtime (verilated.cpp, verilated_threads.cpp,
# verilated_fst_c.cpp, ...) into every model's own library: ten copies of the
# same code in a tree with five C++ and five SystemC models, a quarter of the
# tree's Verilator compile time, for objects of which a program links one.
# This moves the runtime's sources out of <model> into <runtime>, one static
# library per flavour (the C++ models share one, the SystemC models another:
# VM_SC changes the runtime's time-keeping), made by the first model that asks
# for it with that model's VM_* switches, and linked PUBLIC by every model.
# Every model of a flavour must be Verilated with the same switches (tracing,
# coverage): the runtime is compiled once, with the first model's.
# LINK and OPTIONS apply to <runtime> when it is made (e.g. SystemC itself for
# the SystemC flavour, -w for third-party code).
function(lancer_share_verilator_runtime model runtime)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "" "LINK;OPTIONS")
  get_target_property(sources ${model} SOURCES)
  set(own)
  set(runtime_sources)
  foreach(source IN LISTS sources)
    get_filename_component(folder "${source}" DIRECTORY)
    if(folder STREQUAL "${VERILATOR_ROOT}/include")
      list(APPEND runtime_sources ${source})
    else()
      list(APPEND own ${source})
    endif()
  endforeach()
  if(NOT runtime_sources)
    message(FATAL_ERROR "${model}: no Verilator runtime sources under ${VERILATOR_ROOT}/include")
  endif()
  set_property(TARGET ${model} PROPERTY SOURCES ${own})

  set(switches VERILATOR_COVERAGE VERILATOR_SYSTEMC VERILATOR_TRACE VERILATOR_TRACE_VCD VERILATOR_TRACE_FST)
  if(NOT TARGET ${runtime})
    add_library(${runtime} STATIC)
    foreach(switch IN LISTS switches)
      get_target_property(value ${model} ${switch})
      if(value)
        set_property(TARGET ${runtime} PROPERTY ${switch} ${value})
      endif()
    endforeach()
    # The same definitions verilate() gives the generated code.
    target_compile_definitions(${runtime} PRIVATE
      VM_COVERAGE=$<BOOL:$<TARGET_PROPERTY:VERILATOR_COVERAGE>>
      VM_SC=$<BOOL:$<TARGET_PROPERTY:VERILATOR_SYSTEMC>>
      VM_TRACE=$<BOOL:$<TARGET_PROPERTY:VERILATOR_TRACE>>
      VM_TRACE_VCD=$<BOOL:$<TARGET_PROPERTY:VERILATOR_TRACE_VCD>>
      VM_TRACE_FST=$<BOOL:$<TARGET_PROPERTY:VERILATOR_TRACE_FST>>)
    target_include_directories(${runtime} SYSTEM PUBLIC ${VERILATOR_ROOT}/include ${VERILATOR_ROOT}/include/vltstd)
    find_package(Threads REQUIRED)
    find_package(ZLIB REQUIRED)  # the FST writer
    target_link_libraries(${runtime} PUBLIC Threads::Threads ZLIB::ZLIB ${arg_LINK})
    target_compile_options(${runtime} PRIVATE ${arg_OPTIONS})
    get_target_property(pic ${model} POSITION_INDEPENDENT_CODE)
    if(pic)
      set_property(TARGET ${runtime} PROPERTY POSITION_INDEPENDENT_CODE ON)
    endif()
  else()
    foreach(switch IN LISTS switches)
      get_target_property(mine ${model} ${switch})
      get_target_property(shared ${runtime} ${switch})
      if(NOT "${mine}" STREQUAL "${shared}" AND (mine OR shared))
        message(FATAL_ERROR "${model}: ${switch} is '${mine}', but ${runtime} was built with '${shared}'; "
                            "the models sharing a Verilator runtime must be Verilated alike")
      endif()
    endforeach()
  endif()
  target_sources(${runtime} PRIVATE ${runtime_sources})
  target_link_libraries(${model} PUBLIC ${runtime})
endfunction()
