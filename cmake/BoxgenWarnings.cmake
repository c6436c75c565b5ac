# Warnings are errors for the project's own code only; third-party headers
# (GiNaC, CLN, fmt, GoogleTest) come in as SYSTEM includes through their targets.
function(boxgen_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Werror)
endfunction()
