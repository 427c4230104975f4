# geom/: the exact stage of the predicates on implicit points (filtered.h) uses GMP
# integers (libgmp-dev); its header is part of geom's public headers.
find_path(GMP_INCLUDE_DIR gmp.h)
cellforge_prefer_static()
find_library(GMP_LIBRARY NAMES gmp)
if(NOT GMP_INCLUDE_DIR OR NOT GMP_LIBRARY)
  message(FATAL_ERROR "geom: GMP not found (Debian package libgmp-dev)")
endif()
target_include_directories(${layer} PUBLIC $<BUILD_INTERFACE:${GMP_INCLUDE_DIR}>)
target_link_libraries(${layer} PUBLIC ${GMP_LIBRARY})
# geom/shared_library.cpp opens libraries with dlopen (libdl; in libc since glibc 2.34).
target_link_libraries(${layer} PUBLIC ${CMAKE_DL_LIBS})
# geom/workers.cpp keeps the process's worker threads.
find_package(Threads REQUIRED)
target_link_libraries(${layer} PUBLIC Threads::Threads)
