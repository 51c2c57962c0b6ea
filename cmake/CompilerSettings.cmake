# Warning and optimisation flags shared by every target (issue 2 §1).
add_library(erythro_flags INTERFACE)
target_compile_options(erythro_flags INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  # GCC 12 false positive on std::string concatenation at -O2/-O3 (GCC bug 105329).
  target_compile_options(erythro_flags INTERFACE -Wno-restrict)
endif()
if(ERYTHRO_WERROR)
  target_compile_options(erythro_flags INTERFACE -Werror)
endif()
if(ERYTHRO_NATIVE AND NOT ERYTHRO_SANITIZE)
  # Full-width vectors where the machine has them (AVX-512: GCC's default for -march=native
  # is 256-bit). Each lane does the same IEEE operations whatever the width (no -ffast-math,
  # no reassociation, no vector libm calls in the hot loops), so the results are the same bits;
  # the stream–collide kernel runs 11-17 % faster (docs/performance.md, "Full-width vectors").
  # Ignored on machines without AVX-512.
  target_compile_options(erythro_flags INTERFACE -march=native -mprefer-vector-width=512)
endif()
if(ERYTHRO_SANITIZE)
  target_compile_options(erythro_flags INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  target_link_options(erythro_flags INTERFACE -fsanitize=address,undefined)
  # GCC's -Wmaybe-uninitialized gives false positives inside libstdc++ (std::regex,
  # std::function) under sanitizer instrumentation; the Release build keeps it.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(erythro_flags INTERFACE -Wno-maybe-uninitialized)
  endif()
endif()
if(ERYTHRO_FUZZ)
  # libFuzzer's coverage instrumentation in every library the target calls; the target
  # itself links the fuzzer's main (solver/tests/fuzz). ci/fuzz.sh also sets ERYTHRO_SANITIZE.
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "ERYTHRO_FUZZ needs clang (libFuzzer): -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++")
  endif()
  target_compile_options(erythro_flags INTERFACE -fsanitize=fuzzer-no-link)
endif()
# Strict IEEE semantics: no -ffast-math, so round-off tests mean what they say, and no
# floating-point contraction (a·b + c → fma): with contraction the compiler fuses
# according to the surrounding code, so the same collide_node() rounded differently
# in the kernel's interior and boundary paths, and a node's result depended on where
# it sat (docs/performance.md, "Rounding and equivalence").
target_compile_options(erythro_flags INTERFACE -ffp-contract=off)
# No errno from the math functions: nothing reads it, and with it GCC keeps every std::sqrt
# scalar (a branch to the library call for a negative argument), so loops over pair
# distances did not vectorise. sqrt is correctly rounded either way: the same bits
# (docs/performance.md, "Square roots in vector loops").
target_compile_options(erythro_flags INTERFACE -fno-math-errno)
