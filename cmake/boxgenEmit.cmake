# boxgen_emit: turn a direction matrix of your own into C++ headers (and GLSL) at build time.
#
#   boxgen_emit(<target> NAME <name> SPEC <spec> [LATTICE <lattice>] [STRATEGY auto|horner|shifted|bernstein|separable|monomial]
#               [OUTPUT_DIR <dir>] [HEADERS <variable>] [GLSL <variable>])
#
# adds a build step that runs `boxgen emit <spec> [--lattice <lattice>] [--strategy <strategy>]
# --name <name> --out <dir>`
# and makes <target> depend on its output: <dir>/<name>.hpp (namespace boxgen::generated::<name>,
# function evaluate<T>(x, fetch, gradient)) and <dir>/<name>_prefilters.hpp. <dir> (default
# ${CMAKE_CURRENT_BINARY_DIR}/boxgen_emitted) becomes an include directory of <target>, so the
# program writes #include "<name>.hpp". <spec> is a preset or a direction list as on the command
# line ("1,0; 0,1; 1,1"), <lattice> bcc | fcc | cartesian | "<rows of G>". HEADERS receives the
# two header paths. GLSL also emits the GLSL evaluator, <dir>/<name>.glsl (float) and
# <dir>/double/<name>.glsl, and the variable receives the two paths (for boxgen::gl's read_glsl,
# or your own shaders). Call it in the directory that defines <target>. The headers are emitted again
# when the installed boxgen changes; an invalid SPEC fails the build with boxgen's one-line
# message.
function(boxgen_emit target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "NAME;SPEC;LATTICE;STRATEGY;OUTPUT_DIR;HEADERS;GLSL" "")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "boxgen_emit: unexpected arguments: ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET ${target})
    message(FATAL_ERROR "boxgen_emit: '${target}' is not a target")
  endif()
  if(NOT arg_NAME OR NOT arg_SPEC)
    message(FATAL_ERROR "boxgen_emit: NAME and SPEC are required")
  endif()
  if(NOT arg_NAME MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
    message(FATAL_ERROR "boxgen_emit: NAME '${arg_NAME}' is not a C++ identifier")
  endif()
  if(NOT arg_OUTPUT_DIR)
    set(arg_OUTPUT_DIR ${CMAKE_CURRENT_BINARY_DIR}/boxgen_emitted)
  endif()

  # ';' separates directions (and rows of G) but also CMake list items: pass it through intact.
  string(REPLACE ";" "$<SEMICOLON>" spec "${arg_SPEC}")
  set(emit_options)  # --lattice, --strategy
  if(arg_LATTICE)
    string(REPLACE ";" "$<SEMICOLON>" lattice "${arg_LATTICE}")
    set(emit_options --lattice "${lattice}")
  endif()
  if(arg_STRATEGY)
    list(APPEND emit_options --strategy ${arg_STRATEGY})
  endif()

  set(headers ${arg_OUTPUT_DIR}/${arg_NAME}.hpp ${arg_OUTPUT_DIR}/${arg_NAME}_prefilters.hpp)
  add_custom_command(OUTPUT ${headers}
                     COMMAND boxgen::boxgen emit "${spec}" ${emit_options} --name ${arg_NAME} --out ${arg_OUTPUT_DIR}
                     DEPENDS boxgen::boxgen
                     COMMENT "boxgen emit ${arg_NAME}"
                     VERBATIM)
  target_sources(${target} PRIVATE ${headers})
  if(arg_GLSL)
    set(glsl ${arg_OUTPUT_DIR}/${arg_NAME}.glsl ${arg_OUTPUT_DIR}/double/${arg_NAME}.glsl)
    add_custom_command(OUTPUT ${glsl}
                       COMMAND boxgen::boxgen emit "${spec}" ${emit_options} --name ${arg_NAME} --target glsl --out ${arg_OUTPUT_DIR}
                       COMMAND boxgen::boxgen emit "${spec}" ${emit_options} --name ${arg_NAME} --target glsl --precision double --out ${arg_OUTPUT_DIR}/double
                       DEPENDS boxgen::boxgen
                       COMMENT "boxgen emit ${arg_NAME} --target glsl"
                       VERBATIM)
    # The files are read at run time: a custom target builds them before <target>.
    add_custom_target(${target}_${arg_NAME}_glsl DEPENDS ${glsl})
    add_dependencies(${target} ${target}_${arg_NAME}_glsl)
    set(${arg_GLSL} ${glsl} PARENT_SCOPE)
  endif()
  # The emitted header includes the fixed glue "support/evaluator_support.hpp" (boxgen::generated).
  target_include_directories(${target} PRIVATE ${arg_OUTPUT_DIR}
                                               $<TARGET_PROPERTY:boxgen::generated,INTERFACE_INCLUDE_DIRECTORIES>)
  if(arg_HEADERS)
    set(${arg_HEADERS} ${headers} PARENT_SCOPE)
  endif()
endfunction()
