# Flags every pemref target gets (pem_target_defaults). Bit-exactness rules:
#  - no contraction of a*b+c into FMA by the compiler (explicit std::fma only),
#  - no fast-math and no host-specific arch flags: the same bytes on any x86-64/arm64, gcc or
#    clang, -O0..-O3 (the AVX2+FMA fragment build is chosen at run time, raster/fragment.h).
function(pem_target_defaults target)
  target_compile_options(${target} PRIVATE
    -ffp-contract=off -fno-fast-math -fno-finite-math-only
    -Wall -Wextra -Wpedantic -Wshadow -Wdouble-promotion -Wimplicit-fallthrough
    -Wnon-virtual-dtor -Wcast-align)
  if(PEM_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(PEM_TSAN)
    target_compile_options(${target} PRIVATE -fsanitize=thread -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=thread)
  endif()
  if(PEM_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined
      -fsanitize=float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()
