// One printer per target language (docs/design.md §11), in the manner of Halide's CodeGen_C and
// its GPU subclasses: the strategies build expression graphs only
// (generator/codegen/strategies/polynomial_code.h), the print pass writes a scheduled graph through
// a printer (generator/codegen/targets/expr_print.h), and each printer owns what differs between
// C++, CUDA and GLSL: literals, the declaration of a temporary, the wrapping of an orbit's code
// into functions, the dispatch between orbits, and the tables of
// generator/codegen/targets/evaluator_tables.h as the target's initialisers.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "generator/codegen/strategies/polynomial_code.h"
#include "generator/codegen/targets/evaluator_tables.h"
#include "generator/derivation.h"

namespace boxgen::generator {

// A template's fields (templates/*.fmt) by name, as text.
using TemplateFields = std::vector<std::pair<const char*, std::string>>;

// The comment above an orbit's code, the same in every target: the strategy's template
// (OrbitComment) filled in, as "// " lines without a final newline.
std::string orbit_comment(const OrbitCode& code);

class TargetPrinter {
 public:
  TargetPrinter() = default;
  TargetPrinter(const TargetPrinter&) = default;
  TargetPrinter& operator=(const TargetPrinter&) = default;
  TargetPrinter(TargetPrinter&&) = default;
  TargetPrinter& operator=(TargetPrinter&&) = default;
  virtual ~TargetPrinter() = default;

  // An exact constant in the code, rounded as the target's arithmetic reads it.
  virtual std::string literal(const Rational& r) const = 0;
  // What precedes a temporary's name where it is defined: "const T ", "float ".
  virtual std::string declaration() const = 0;
  // The functions of orbit `orbit`'s code, its comment first.
  virtual std::string orbit_functions(const OrbitCode& code, int orbit) const = 0;
  // The lines of the dispatch to orbit `orbit`'s functions.
  virtual std::string orbit_dispatch(int orbit) const = 0;

  // Every orbit's functions, and the dispatch between them, as the templates' fields
  // {orbit_functions} and {orbit_dispatch} take them.
  std::string functions(const std::vector<OrbitCode>& orbits) const;
  std::string dispatch(std::size_t orbit_count) const;
};

// C++ (templates/evaluator.hpp.fmt): `template <int Order, class T> T orbit_k(const T* v,
// const T* x, T* d)` per orbit, constants as T(double), the tables as C++ initialisers of the
// traits type that support/evaluator_support.hpp reads.
class CppPrinter : public TargetPrinter {
 public:
  std::string literal(const Rational& r) const override;
  std::string declaration() const override;
  std::string orbit_functions(const OrbitCode& code, int orbit) const override;
  std::string orbit_dispatch(int orbit) const override;
  // A double of a table (the centre, the prefilters' weights): the value that round-trips.
  static std::string table_literal(const Rational& r);
  // The tables' fields of the C++ and CUDA templates ({centre}, {lookup}, {cells}, ...).
  static TemplateFields table_fields(const Derivation& a, const KnotPlaneKeys& keys,
                                     const IntColumns& hermite, const CellTables& t);

 protected:
  // What precedes the return type of an orbit function.
  virtual std::string qualifiers() const;
};

// CUDA (templates/evaluator.cuh.fmt): the C++ code and tables, callable from host and device.
class CudaPrinter : public CppPrinter {
 public:
  std::string orbit_dispatch(int orbit) const override;

 protected:
  std::string qualifiers() const override;
};

// GLSL (templates/evaluator.glsl.fmt), float or double: no templates, so one function per orbit
// and path (NAME_orbitK_ORDER), every table a flat int array.
class GlslPrinter : public TargetPrinter {
 public:
  GlslPrinter(std::string name, int dimension, int stencil_size, bool double_precision);
  std::string literal(const Rational& r) const override;
  std::string declaration() const override;
  std::string orbit_functions(const OrbitCode& code, int orbit) const override;
  std::string orbit_dispatch(int orbit) const override;

  // The tables as `const` arrays (the fields of `constant`), and in `buffered` the ones indexed at
  // run time (by the point's cell, and with several orbits by its orbit) as the members of one
  // read-only storage block NAME_Tables whose contents are `block` (std430: the int arrays
  // tightly packed, in the order declared).
  struct Tables {
    TemplateFields constant, buffered;
    std::vector<int> block;
  };
  Tables tables(const SplineStructure& s, const KnotPlaneKeys& keys, const CellTables& t) const;

 private:
  std::string name_;
  int dimension_, stencil_size_;
  bool double_precision_;
};

}  // namespace boxgen::generator
