# io/: 3MF packages are ZIP archives (zlib, for deflate and CRC-32) holding XML
# (expat), both from Debian (zlib1g-dev, libexpat1-dev).
cellforge_prefer_static()
find_package(ZLIB REQUIRED)
find_package(EXPAT REQUIRED)
target_link_libraries(${layer} PUBLIC ZLIB::ZLIB EXPAT::EXPAT)
