# BLOCKDEM_SANITIZE=ON builds blockdem's own targets (tests, examples) with AddressSanitizer and
# UndefinedBehaviorSanitizer, any finding fatal (-fno-sanitize-recover=all), at -O1 without debug information: a
# build cheap enough for CI that still runs the vault tests in minutes (scripts/run-sanitized-tests.sh, which uses
# clang when installed: it compiles this code with the sanitizers in about 60 % of GCC's time).
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  message(FATAL_ERROR "BLOCKDEM_SANITIZE needs GCC or Clang (AddressSanitizer and UndefinedBehaviorSanitizer)")
endif()
set(blockdem_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
add_compile_options(-O1 -g0 ${blockdem_sanitizers})
add_link_options(${blockdem_sanitizers})
