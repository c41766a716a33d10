# Flags shared by every Rift target, carried by an interface target so third-party code is unaffected.
add_library(rift_options INTERFACE)
target_compile_options(rift_options INTERFACE -Wall -Wextra -Wno-unused-parameter)
# GCC 12 at -O3 reports false -Wrestrict positives inside std::string's own code (GCC bug 105329).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(rift_options INTERFACE -Wno-restrict)
endif()
if(RIFT_NATIVE)
  target_compile_options(rift_options INTERFACE -march=native)
endif()
if(RIFT_SANITIZE)
  # vptr is left out: oneTBB's flow graph downcasts task objects in its headers in a way UBSan's vptr
  # check reports (flow_graph_impl.h, apply_body_task_bypass) although it is not ours to fix.
  target_compile_options(rift_options INTERFACE -fsanitize=address,undefined -fno-sanitize=vptr
                                                -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(rift_options INTERFACE -fsanitize=address,undefined -fno-sanitize=vptr)
endif()
# Eigen must not spawn its own threads; TBB owns parallelism.
target_compile_definitions(rift_options INTERFACE EIGEN_DONT_PARALLELIZE
  $<$<BOOL:${RIFT_SANITIZE}>:RIFT_SANITIZED>)

find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
endif()
