// Kept for code written against the earlier runtime: its names live on in runtime/compat.h.
#pragma once
#include "runtime/compat.h"  // IWYU pragma: export
