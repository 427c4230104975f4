# boolean/: the exact fallback of its predicates uses GMP integers (libgmp-dev).
find_path(GMP_INCLUDE_DIR gmp.h)
find_library(GMP_LIBRARY NAMES gmp)
if(NOT GMP_INCLUDE_DIR OR NOT GMP_LIBRARY)
  message(FATAL_ERROR "boolean: GMP not found (Debian package libgmp-dev)")
endif()
target_include_directories(${layer} PRIVATE ${GMP_INCLUDE_DIR})
target_link_libraries(${layer} PUBLIC ${GMP_LIBRARY})
# Its stages run on threads (Options::threads).
find_package(Threads REQUIRED)
target_link_libraries(${layer} PUBLIC Threads::Threads)
