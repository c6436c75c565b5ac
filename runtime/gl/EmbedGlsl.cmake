# cmake -DDIR=<emitted .glsl> -DNAMES="m7;m8;..." -DOUT=registry_glsl.cpp -P EmbedGlsl.cmake:
# the registry's emitted GLSL (NAME.glsl and double/NAME.glsl) as the table of registry_glsl.h.
set(text "// Written by runtime/gl/EmbedGlsl.cmake at build time from `boxgen emit --target glsl`.\n")
string(APPEND text "#include \"runtime/gl/registry_glsl.h\"\n\nnamespace boxgen::runtime::gl {\n\n")
string(APPEND text "const RegistryGlsl kRegistryGlsl[] = {\n")
list(LENGTH NAMES count)
foreach(name ${NAMES})
  file(READ ${DIR}/${name}.glsl single)
  file(READ ${DIR}/double/${name}.glsl double)
  string(APPEND text "    {\"${name}\", R\"glsl(${single})glsl\",\n     R\"glsl(${double})glsl\"},\n")
endforeach()
string(APPEND text "};\nconst int kRegistryGlslCount = ${count};\n\n}  // namespace boxgen::runtime::gl\n")
file(WRITE ${OUT}.tmp "${text}")
file(RENAME ${OUT}.tmp ${OUT})
