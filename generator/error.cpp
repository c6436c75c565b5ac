#include "generator/error.h"

namespace boxgen::generator {

void fail_input(const std::string& message) { throw InputError(message); }
void fail_internal(const std::string& message) { throw InternalError(message); }

}  // namespace boxgen::generator
