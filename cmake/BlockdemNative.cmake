# The programs and the Python module built for this machine's instruction set (-DBLOCKDEM_NATIVE=ON; off by default):
# -march=native where the compiler takes it. On the development machine (a Zen 4 with AVX-512) the rigid vault's
# step is 1.6 (MassProportional) to 2.0 (Maxwell<3>) times as fast as in a portable x86-64 build, the deformable
# vault's 1.0-1.2 times (docs/performance.md, portable or native programs). Off by default, because results differ
# from a portable build's by rounding (GCC fuses multiplies and adds, Eigen uses FMA), which a cracking structure
# carries into its histories (the rigid vault's crown, 8 % of its peak at the 50 % level), while a portable build
# gives the same bits on every x86-64 processor; a checkpoint resumes only in a build of the kind that wrote it; and
# a native program may not start on an older processor (a cluster's compute nodes, when built on its login node).
# The library itself never sets -march; a user's own program chooses. The tests are always built portable.
include(CheckCXXCompilerFlag)
if(BLOCKDEM_NATIVE OR BLOCKDEM_BENCHMARKS_NATIVE)
  check_cxx_compiler_flag(-march=native blockdem_has_march_native)
  if(BLOCKDEM_NATIVE AND NOT blockdem_has_march_native)
    message(STATUS "blockdem: the compiler does not take -march=native; the programs are built portable")
  endif()
endif()

# `target` built for this machine's instruction set, where the compiler takes -march=native (the benchmarks always,
# unless BLOCKDEM_BENCHMARKS_NATIVE is off).
function(blockdem_target_march_native target)
  if(blockdem_has_march_native)
    target_compile_options(${target} PRIVATE -march=native)
    # GCC 12 takes the _mm256_undefined_pd() of Eigen's AVX-512 packets for an uninitialised value (its matrix-vector
    # product): a false alarm in a system header. The portable build of the tests keeps the warning.
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized)
    endif()
  endif()
endfunction()

# A program or the Python module: for this machine only with -DBLOCKDEM_NATIVE=ON.
function(blockdem_target_native target)
  if(BLOCKDEM_NATIVE)
    blockdem_target_march_native(${target})
  endif()
endfunction()
