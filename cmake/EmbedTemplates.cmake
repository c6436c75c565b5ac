# Writes OUTPUT, a header holding every templates/*.fmt file as a raw string literal, so the
# boxgen binary carries its templates (cmake -P script, run by a custom command).
file(GLOB templates "${TEMPLATE_DIR}/*.fmt")
set(content "// Produced by cmake/EmbedTemplates.cmake from templates/*.fmt. Do not edit.\n#pragma once\n#include <string_view>\n\nnamespace boxgen::templates {\n")
foreach(path ${templates})
  get_filename_component(name "${path}" NAME_WLE)
  string(REPLACE "." "_" name "${name}")
  file(READ "${path}" text)
  string(APPEND content "inline constexpr std::string_view ${name} = R\"boxgen_template(${text})boxgen_template\";\n")
endforeach()
string(APPEND content "}  // namespace boxgen::templates\n")
file(WRITE "${OUTPUT}.tmp" "${content}")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
