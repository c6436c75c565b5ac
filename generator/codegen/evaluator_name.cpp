#include "generator/codegen/evaluator_name.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <regex>
#include <set>
#include <string_view>

#include "generator/embedded_templates.h"
#include "generator/error.h"

namespace boxgen::generator {

namespace {

const std::set<std::string>& keywords() {
  static const std::set<std::string> list = {"alignas",       "alignof",     "and",
                                             "and_eq",        "asm",         "auto",
                                             "bitand",        "bitor",       "bool",
                                             "break",         "case",        "catch",
                                             "char",          "char8_t",     "char16_t",
                                             "char32_t",      "class",       "compl",
                                             "concept",       "const",       "consteval",
                                             "constexpr",     "constinit",   "const_cast",
                                             "continue",      "co_await",    "co_return",
                                             "co_yield",      "decltype",    "default",
                                             "delete",        "do",          "double",
                                             "dynamic_cast",  "else",        "enum",
                                             "explicit",      "export",      "extern",
                                             "false",         "float",       "for",
                                             "friend",        "goto",        "if",
                                             "inline",        "int",         "long",
                                             "mutable",       "namespace",   "new",
                                             "noexcept",      "not",         "not_eq",
                                             "nullptr",       "operator",    "or",
                                             "or_eq",         "private",     "protected",
                                             "public",        "register",    "reinterpret_cast",
                                             "requires",      "return",      "short",
                                             "signed",        "sizeof",      "static",
                                             "static_assert", "static_cast", "struct",
                                             "switch",        "template",    "this",
                                             "thread_local",  "throw",       "true",
                                             "try",           "typedef",     "typeid",
                                             "typename",      "union",       "unsigned",
                                             "using",         "virtual",     "void",
                                             "volatile",      "wchar_t",     "while",
                                             "xor",           "xor_eq"};
  return list;
}

// Names the emitted code uses as it stands: the namespaces it refers to, the files beside an
// evaluator, the functions and arrays it declares in NAME's namespace, and, read from the
// templates (comments and {fields} left out), every type (a capital first: Traits, Located,
// Cell) and constant (k and a capital: kLattice, kCentre) they name. Any of them as NAME would be
// found in place of the namespace at `NAME::kLattice` inside Traits, or clash in the registry.
const std::set<std::string>& used_by_the_emitted_code() {
  static const std::set<std::string> names = [] {
    std::set<std::string> out = {"std",     "boxgen",   "generated",
                                 "support", "detail",   "cuda",
                                 "glsl",    "registry", "evaluator_support",
                                 "locate",  "evaluate", "evaluate_located",
                                 "orbit",   "q1",       "q2"};
    const std::regex comment("//[^\n]*"), field(R"(\{[a-z_0-9]*\})"),
        word("[A-Za-z_][A-Za-z0-9_]*");
    for (const std::string_view text :
         {templates::evaluator_hpp, templates::prefilters_hpp, templates::evaluator_cuh,
          templates::evaluator_glsl, templates::registry_hpp}) {
      const std::string code =
          std::regex_replace(std::regex_replace(std::string(text), comment, " "), field, " ");
      for (auto it = std::sregex_iterator(code.begin(), code.end(), word);
           it != std::sregex_iterator(); ++it) {
        const std::string w = it->str();
        const bool type = std::isupper(static_cast<unsigned char>(w[0])) != 0;
        const bool constant =
            w.size() > 1 && w[0] == 'k' && std::isupper(static_cast<unsigned char>(w[1]));
        if (type || constant) out.insert(w);
      }
    }
    return out;
  }();
  return names;
}

// Macros of the C and C++ headers in lowercase or mixed case (glibc's included): the standard's,
// and families by prefix (M_PIf, PRId64, si_pid). Names in capitals only are refused as a whole
// (below).
bool lowercase_macro(const std::string& name) {
  static const std::set<std::string> macros = {
      "errno",   "assert",  "assert_perror", "offsetof",    "math_errhandling",
      "stdin",   "stdout",  "stderr",        "alloca",      "setjmp",
      "sigmask", "strdupa", "strndupa",      "issubnormal", "unix",
      "linux",   "i386"};
  static constexpr std::array<std::string_view, 15> prefixes = {
      "si_", "sa_",  "sigev_", "va_",  "L_",   "P_",   "M_",  "PRI",
      "SCN", "be16", "be32",   "be64", "le16", "le32", "le64"};
  return macros.count(name) > 0 || name.starts_with("htobe") || name.starts_with("htole") ||
         std::any_of(prefixes.begin(), prefixes.end(),
                     [&](std::string_view p) { return name.starts_with(p); });
}

}  // namespace

void check_evaluator_name(const std::string& name) {
  const std::string shown = name.substr(0, 40) + (name.size() > 40 ? "..." : "");
  const auto letter = [](char ch) {
    return std::isalpha(static_cast<unsigned char>(ch)) || ch == '_';
  };
  const bool identifier =
      !name.empty() && letter(name[0]) && std::all_of(name.begin(), name.end(), [&](char ch) {
        return letter(ch) || std::isdigit(static_cast<unsigned char>(ch));
      });
  if (!identifier)
    fail_input(
        fmt::format("--name '{}' is not a C++ identifier: use letters, digits and '_', not "
                    "starting with a digit",
                    shown));
  if (name.size() > kMaxEvaluatorName)
    fail_input(fmt::format("--name '{}' has {} characters, more than the {} allowed", shown,
                           name.size(), kMaxEvaluatorName));
  if (keywords().count(name))
    fail_input(fmt::format("--name '{}' is a C++ keyword: choose another name", name));
  if (name.find("__") != std::string::npos ||
      (name.size() > 1 && name[0] == '_' && std::isupper(static_cast<unsigned char>(name[1]))))
    fail_input(fmt::format(
        "--name '{}' is reserved for the implementation in C++ ('__' or '_' and a capital)", name));
  if (name.starts_with("gl_"))
    fail_input(fmt::format(
        "--name '{}' starts with 'gl_', reserved in GLSL (the .glsl evaluator's functions are "
        "named after it): choose another",
        name));
  if (name.size() > 11 && name.ends_with("_prefilters"))
    fail_input(fmt::format(
        "--name '{}' ends in '_prefilters', the suffix of an evaluator's prefilter file", name));
  if (used_by_the_emitted_code().count(name))
    fail_input(fmt::format(
        "--name '{}' is taken: the emitted code or its folder uses that name; choose another",
        name));
  if (std::none_of(name.begin(), name.end(),
                   [](char ch) { return std::islower(static_cast<unsigned char>(ch)); }))
    fail_input(fmt::format(
        "--name '{}' has no lowercase letter: names in capitals are the macros' (the C and C++ "
        "headers define hundreds, such as FLT_MAX, BUFSIZ and RAND_MAX); use a lowercase letter",
        name));
  if (lowercase_macro(name))
    fail_input(
        fmt::format("--name '{}' is a macro of the C and C++ headers: choose another", name));
}

}  // namespace boxgen::generator
