# csg/: text() lays out glyphs as OpenSCAD does, through Debian's FreeType
# (libfreetype-dev), HarfBuzz (libharfbuzz-dev) and fontconfig (libfontconfig-dev),
# whose headers alone are used here: csg/text.cpp loads the libraries with dlopen at
# the first text(), so that runs without text do not load them. surface() reads PNG
# heightmaps through libpng (libpng-dev), linked.
find_package(PkgConfig REQUIRED)
pkg_check_modules(CSG_TEXT REQUIRED IMPORTED_TARGET freetype2 harfbuzz fontconfig)
cellforge_prefer_static()
pkg_check_modules(CSG_PNG REQUIRED IMPORTED_TARGET libpng)
target_include_directories(${layer} PRIVATE $<TARGET_PROPERTY:PkgConfig::CSG_TEXT,INTERFACE_INCLUDE_DIRECTORIES>)
target_link_libraries(${layer} PUBLIC PkgConfig::CSG_PNG)
if(CELLFORGE_STATIC_DEPS)
  target_link_libraries(${layer} PUBLIC ZLIB::ZLIB m)  # what libpng's archive needs, after it
endif()
