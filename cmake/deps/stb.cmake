# Debian's libstb-dev: headers in /usr/include/stb, implementation in libstb. Defines the imported
# target Stb::Stb when both are found. Also installed next to breastfitConfig.cmake, which includes
# it to recreate Stb::Stb for consumers of the installed package (the render layer links it).
include(${CMAKE_CURRENT_LIST_DIR}/import_library.cmake)
breastfit_import_library(Stb::Stb HEADER stb_image_write.h LIBRARY stb SUFFIX stb)
