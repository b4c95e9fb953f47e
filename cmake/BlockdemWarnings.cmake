# Warnings for blockdem's own targets (tests, examples, benchmarks); never imposed on consumers.
function(blockdem_target_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
      -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wdouble-promotion)
    if(BLOCKDEM_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  elseif(MSVC)
    target_compile_options(${target} PRIVATE /W4 $<$<BOOL:${BLOCKDEM_WARNINGS_AS_ERRORS}>:/WX>)
  endif()
endfunction()

# OpenMP for blockdem's own programs and tests: the library's loops carry `omp parallel for` pragmas and use
# OpenMP when the consumer compiles with it. Without OpenMP the pragmas are ignored (and not warned about).
find_package(OpenMP QUIET)
function(blockdem_target_openmp target)
  if(OpenMP_CXX_FOUND)
    target_link_libraries(${target} PRIVATE OpenMP::OpenMP_CXX)
  elseif(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wno-unknown-pragmas)
  endif()
endfunction()
