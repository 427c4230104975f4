# csg/: text() lays out glyphs as OpenSCAD does, through Debian's FreeType
# (libfreetype-dev), HarfBuzz (libharfbuzz-dev) and fontconfig (libfontconfig-dev);
# surface() reads PNG heightmaps through libpng (libpng-dev).
find_package(PkgConfig REQUIRED)
pkg_check_modules(CSG_TEXT REQUIRED IMPORTED_TARGET freetype2 harfbuzz fontconfig)
pkg_check_modules(CSG_PNG REQUIRED IMPORTED_TARGET libpng)
target_link_libraries(${layer} PUBLIC PkgConfig::CSG_TEXT PkgConfig::CSG_PNG)
