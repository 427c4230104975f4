# Peers of bench_boolean, built only with -DCELLFORGE_PEERS=ON and never needed by the
# tests: CGAL corefinement and Nef polyhedra (Debian's libcgal-dev) compiled into the
# benchmark, and manifold-3d (npm) run with node from ${CMAKE_BINARY_DIR}/peers.
# bench/peers/setup.sh BUILD_DIR installs both; the build downloads nothing.
find_package(CGAL REQUIRED)
find_program(CELLFORGE_NODE node)
if(NOT CELLFORGE_NODE OR NOT EXISTS ${CMAKE_BINARY_DIR}/peers/node_modules/manifold-3d)
  message(STATUS "peers: manifold-3d not ready (run bench/peers/setup.sh ${CMAKE_BINARY_DIR}); "
                 "bench_boolean will report it missing")
endif()
target_sources(bench_boolean PRIVATE ${CMAKE_SOURCE_DIR}/bench/peers/cgal_peers.cpp)
target_include_directories(bench_boolean PRIVATE ${CMAKE_SOURCE_DIR}/bench)
target_link_libraries(bench_boolean PRIVATE CGAL::CGAL)
target_compile_definitions(bench_boolean PRIVATE CELLFORGE_PEERS
  CELLFORGE_PEERS_SOURCE_DIR="${CMAKE_SOURCE_DIR}/bench/peers"
  CELLFORGE_PEERS_NODE_DIR="${CMAKE_BINARY_DIR}/peers")
