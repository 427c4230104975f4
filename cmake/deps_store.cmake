# store/: SQLite (the default database) and libpq (PostgreSQL), through CMake's
# FindPostgreSQL or, where that finds nothing, pkg-config. The choice is kept in
# CELLFORGE_LIBPQ_FROM so the installed package config finds libpq the same way.
find_package(SQLite3 REQUIRED)
find_package(PostgreSQL QUIET)
if(PostgreSQL_FOUND)
  target_link_libraries(${layer} PUBLIC SQLite::SQLite3 PostgreSQL::PostgreSQL)
  set(CELLFORGE_LIBPQ_FROM PostgreSQL CACHE INTERNAL "")
else()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(LIBPQ REQUIRED IMPORTED_TARGET libpq)
  target_link_libraries(${layer} PUBLIC SQLite::SQLite3 PkgConfig::LIBPQ)
  set(CELLFORGE_LIBPQ_FROM pkg-config CACHE INTERNAL "")
endif()
