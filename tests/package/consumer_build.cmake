# cmake -DBUILD_DIR=... -DCONFIG=... -DCONSUMER_SOURCE=... -DWORK=... -DGENERATOR=... -DCXX_COMPILER=... -P
# Installs BUILD_DIR into WORK/prefix, configures and builds CONSUMER_SOURCE against it (same
# compiler, generator and build type) and runs the consumer. Any failing step fails the test.
# WORK is wiped first, so nothing from an earlier run (or outside the two trees) is reused.
foreach(var BUILD_DIR CONFIG CONSUMER_SOURCE WORK GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "consumer_build.cmake: -D${var}=... is missing")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
set(build ${WORK}/build)

run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --config ${CONFIG} --prefix ${prefix})
# Programs installed: the two tools, never a test, benchmark or fuzz binary.
file(GLOB programs RELATIVE ${prefix}/bin ${prefix}/bin/*)
list(SORT programs)
if(NOT programs STREQUAL "boxgen;boxrecon")
  message(FATAL_ERROR "bin/ should hold boxgen and boxrecon only, not: ${programs}")
endif()

# Only the package's own search path: no user or system package registry.
run("configuring the consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE} -B ${build} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=${CONFIG} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
    -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)

# The package found must be the one just installed.
file(STRINGS ${build}/CMakeCache.txt found REGEX "^boxgen_DIR:")
string(REGEX REPLACE "^boxgen_DIR:[A-Z]*=" "" found "${found}")
file(REAL_PATH "${found}" found)
file(REAL_PATH ${prefix} real_prefix)
string(FIND "${found}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "the consumer found another boxgen: ${found}")
endif()

run("building the consumer" ${CMAKE_COMMAND} --build ${build} --config ${CONFIG})

# The project's warnings-as-errors must not reach its users.
if(EXISTS ${build}/compile_commands.json)
  file(READ ${build}/compile_commands.json commands)
  if(commands MATCHES "-Werror")
    message(FATAL_ERROR "-Werror leaked into the consumer's compile flags:\n${commands}")
  endif()
endif()

run("running the consumer" ${build}/boxgen_consumer)
message("${run_output}")
