# store/: SQLite (the default database), linked, and libpq (PostgreSQL), whose header
# alone is used here: store/pg_connection.cpp loads libpq.so.5 with dlopen when a
# PostgreSQL database is first opened, so that the twenty libraries libpq needs are
# not loaded by every run. libpq is found through CMake's FindPostgreSQL or, where that
# finds nothing, pkg-config; CELLFORGE_LIBPQ is the target, for the test and benchmark
# programs that call libpq themselves.
set(suffixes ${CMAKE_FIND_LIBRARY_SUFFIXES})
cellforge_prefer_static()
find_package(SQLite3 REQUIRED)
set(CMAKE_FIND_LIBRARY_SUFFIXES ${suffixes})  # libpq, below, stays shared
target_link_libraries(${layer} PUBLIC SQLite::SQLite3)
if(CELLFORGE_STATIC_DEPS)
  target_link_libraries(${layer} PUBLIC m)  # SQLite's archive needs libm
endif()
find_package(PostgreSQL QUIET)
if(PostgreSQL_FOUND)
  set(CELLFORGE_LIBPQ PostgreSQL::PostgreSQL)
else()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(LIBPQ REQUIRED IMPORTED_TARGET libpq)
  set(CELLFORGE_LIBPQ PkgConfig::LIBPQ)
endif()
target_include_directories(${layer} PRIVATE $<TARGET_PROPERTY:${CELLFORGE_LIBPQ},INTERFACE_INCLUDE_DIRECTORIES>)
set(CELLFORGE_LIBPQ ${CELLFORGE_LIBPQ} CACHE INTERNAL "")
