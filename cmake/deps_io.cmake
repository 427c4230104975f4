# io/: 3MF through Debian's lib3mf (lib3mf-dev). Optional: without it, 3MF reads
# and writes report that the build has no lib3mf. Found by hand rather than
# through lib3MF.pc, whose Libs line asks for libzip's static link flags.
find_path(LIB3MF_INCLUDE_DIR Model/COM/NMR_DLLInterfaces.h PATH_SUFFIXES lib3mf)
find_library(LIB3MF_LIBRARY NAMES 3MF lib3MF)
if(LIB3MF_INCLUDE_DIR AND LIB3MF_LIBRARY)
  target_include_directories(${layer} PRIVATE ${LIB3MF_INCLUDE_DIR})
  target_link_libraries(${layer} PRIVATE ${LIB3MF_LIBRARY})
  target_compile_definitions(${layer} PRIVATE CELLFORGE_HAVE_LIB3MF)
  message(STATUS "io: 3MF through ${LIB3MF_LIBRARY}")
else()
  message(STATUS "io: lib3mf not found; 3MF disabled")
endif()
