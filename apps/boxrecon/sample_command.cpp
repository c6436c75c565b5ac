#include "apps/boxrecon/sample_command.h"

#include <fmt/format.h>

#include <optional>

#include "apps/boxrecon/output_volume.h"
#include "frontend/sample_grid.h"
#include "runtime/nrrd_io.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"

namespace boxgen::app {

namespace {

template <class T>
void sample_and_write(const runtime::TestFunction& fn, const runtime::LatticeGrid& grid,
                      const std::string& output, std::optional<runtime::SampleType> type) {
  write_output_volume(output, runtime::sample_lattice<T>(fn.value, grid), type);
}

}  // namespace

int run_sample(const std::string& function, int n, const std::optional<double>& h,
               const std::string& lattice_text, const std::string& filter,
               const std::string& precision, const std::string& output,
               const std::string& type_text) {
  const runtime::TestFunction& fn = runtime::find_test_function(function);
  const std::optional<runtime::SampleType> type = parse_type_option(type_text);
  const runtime::LatticeGrid grid = frontend::sample_grid(
      n, h, lattice_text, filter, precision == "float" ? sizeof(float) : sizeof(double));
  require_output_volume(output, {}, grid.lattice);
  if (precision == "float")
    sample_and_write<float>(fn, grid, output, type);
  else
    sample_and_write<double>(fn, grid, output, type);
  return 0;
}

}  // namespace boxgen::app
