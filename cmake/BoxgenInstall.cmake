# Install rules and the CMake package `boxgen` (find_package(boxgen) in a user's project):
#   bin/boxgen, bin/boxrecon                      the programs
#   lib/libboxgen_runtime.a                       boxgen::runtime
#   include/boxgen/runtime/*.h                    included as "runtime/x.h"
#   include/boxgen/generated/*.hpp                boxgen::generated, included as "generated/x.hpp"
#   lib/libboxgen_support.a                       boxgen::support (the runtime's output files)
#   lib/libboxgen_gl.a                            boxgen::gl (the GL device: OpenGL compute, EGL)
#   include/boxgen/runtime/gl/*.h                 included as "runtime/gl/x.h"
#   include/boxgen/support/*.h, *.hpp             the evaluators' glue, included as "support/x.hpp"
#   lib/cmake/boxgen/boxgenConfig.cmake ...       the package, with boxgen::boxgen (the generator,
#                                                 to run at build time) and boxgen_emit()
# Tests, benchmarks and fuzz targets are never installed. Everything is relative to the install
# prefix, so `cmake --install build --prefix DIR` works for any DIR.
include(CMakePackageConfigHelpers)

set(BOXGEN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/boxgen)

set_target_properties(boxgen PROPERTIES EXPORT_NAME boxgen)
set_target_properties(boxrecon PROPERTIES EXPORT_NAME boxrecon)
install(TARGETS boxgen boxrecon boxgen_runtime boxgen_support boxgen_generated boxgen_gl
        EXPORT boxgenTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})

file(GLOB BOXGEN_RUNTIME_HEADERS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/runtime/*.h)
file(GLOB BOXGEN_GENERATED_HEADERS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/generated/*.hpp)
install(FILES ${BOXGEN_RUNTIME_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxgen/runtime)
file(GLOB BOXGEN_GL_HEADERS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/runtime/gl/*.h)
install(FILES ${BOXGEN_GL_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxgen/runtime/gl)
install(FILES ${BOXGEN_GENERATED_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxgen/generated)
file(GLOB BOXGEN_SUPPORT_HEADERS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/support/*.h ${PROJECT_SOURCE_DIR}/support/*.hpp)
install(FILES ${BOXGEN_SUPPORT_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/boxgen/support)

install(EXPORT boxgenTargets NAMESPACE boxgen:: DESTINATION ${BOXGEN_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/boxgenConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/boxgenConfig.cmake
                              INSTALL_DESTINATION ${BOXGEN_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/boxgenConfigVersion.cmake
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/boxgenConfig.cmake ${PROJECT_BINARY_DIR}/boxgenConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/boxgenEmit.cmake
        DESTINATION ${BOXGEN_INSTALL_CMAKEDIR})
