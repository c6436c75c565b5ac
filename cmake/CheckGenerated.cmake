# generated/ from the generator: every filter of the registry (evaluator and prefilters) and
# registry.hpp. A cmake -P script with two modes:
#   -DMODE=check (default; the test GeneratedHeadersAreFresh): emit into WORK and fail if any file
#     differs from generated/ (SOURCE);
#   -DMODE=write (the target `regenerate`): emit straight into generated/.
# The registry's filters, in registry order (the first three are the BCC Reconstructor's Filter
# enum, runtime/reconstruction.h): M7, M8, M12 on BCC, fcc6 on FCC, tricubic and cart7 on the
# Cartesian lattice.
set(filters m7 m8 m12 fcc6 tricubic cart7)
string(REPLACE ";" "," registry "${filters}")
if(MODE STREQUAL "write")
  set(WORK ${SOURCE})
endif()
foreach(name ${filters})
  set(extra)
  if(name STREQUAL "m12")  # the registry is written with one of the filters
    set(extra --registry ${registry})
  endif()
  execute_process(COMMAND ${BOXGEN} emit ${name} --name ${name} ${extra} --out ${WORK} RESULT_VARIABLE rc OUTPUT_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "boxgen emit ${name} failed (${rc})")
  endif()
  if(MODE STREQUAL "write")
    continue()
  endif()
  set(files ${name}.hpp ${name}_prefilters.hpp)
  if(name STREQUAL "m12")
    list(APPEND files registry.hpp)
  endif()
  foreach(file ${files})
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/${file} ${SOURCE}/${file} RESULT_VARIABLE diff)
    if(NOT diff EQUAL 0)
      message(FATAL_ERROR "generated/${file} is stale: run `cmake --build build --target regenerate` and commit it")
    endif()
  endforeach()
endforeach()
if(MODE STREQUAL "write")
  message(STATUS "generated/ rewritten: ${registry} and registry.hpp")
else()
  message(STATUS "generated/ matches a fresh emission")
endif()
