// Build-time tool of the GL device (runtime/gl/CMakeLists.txt): writes the table of
// runtime/gl/registry_glsl.h, the registry's GLSL evaluators in float and double as `boxgen emit
// --target glsl` prints them, each with the variant whose run-time-indexed tables live in a
// storage block and that block's contents, all taken from the generator's Emission: the device
// reads them as data and never searches the text.
//   boxgen_embed_glsl OUT.cpp NAME...
#include <fmt/format.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "generator/codegen/emitter.h"
#include "generator/derivation.h"
#include "generator/spec.h"

namespace gen = boxgen::generator;

namespace {

gen::Emission glsl(const gen::Derivation& a, const std::string& name, bool double_precision) {
  gen::EmissionRequest request;
  request.name = name;
  // The command boxgen emit writes into the file's banner.
  request.command =
      fmt::format("boxgen emit {0} --name {0} --strategy auto --target glsl{1} --out .", name,
                  double_precision ? " --precision double" : "");
  request.target = gen::EmissionTarget::Glsl;
  request.double_precision = double_precision;
  return gen::emit(a, request);
}

std::string raw(const std::string& text) { return "R\"glsl(" + text + ")glsl\""; }

std::string ints(const std::vector<int>& values) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i)
    out += fmt::format("{}{}", i == 0 ? "" : i % 16 == 0 ? ",\n    " : ", ", values[i]);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: boxgen_embed_glsl OUT.cpp NAME...\n";
    return 2;
  }
  try {
    std::string blocks, entries;
    for (int i = 2; i < argc; ++i) {
      const std::string name = argv[i];
      const gen::Derivation a = gen::derive(gen::parse_spec(name));
      const gen::Emission single = glsl(a, name, false), dbl = glsl(a, name, true);
      if (single.glsl_block != dbl.glsl_block)
        throw std::logic_error(name + ": the float and double tables differ");
      blocks +=
          fmt::format("const int k{}Block[] = {{\n    {}}};\n", name, ints(single.glsl_block));
      entries += fmt::format(
          "    {{\"{0}\", {1}, {2},\n     {3},\n     {4},\n     {5},\n     k{0}Block, {6}}},\n",
          name, single.stencil_size, raw(single.files.at(0).text), raw(dbl.files.at(0).text),
          raw(single.glsl_buffered), raw(dbl.glsl_buffered), single.glsl_block.size());
    }
    const std::string text = fmt::format(
        "// Written by boxgen_embed_glsl (generator/codegen/tools/embed_glsl.cpp) at build time.\n"
        "#include \"runtime/gl/registry_glsl.h\"\n\nnamespace boxgen::runtime::gl {{\n\n"
        "namespace {{\n{}}}  // namespace\n\nconst RegistryGlsl kRegistryGlsl[] = {{\n{}}};\n"
        "const int kRegistryGlslCount = {};\n\n}}  // namespace boxgen::runtime::gl\n",
        blocks, entries, argc - 2);
    const std::filesystem::path out = argv[1], tmp = out.string() + ".tmp";
    {
      std::ofstream file(tmp);
      file << text;
      if (!file.flush()) throw std::runtime_error("cannot write " + tmp.string());
    }
    std::filesystem::rename(tmp, out);
  } catch (const std::exception& e) {
    std::cerr << "boxgen_embed_glsl: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
