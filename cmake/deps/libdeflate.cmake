# Debian's libdeflate-dev (1.14 ships a pkg-config file but no CMake package): header libdeflate.h
# and library libdeflate. Defines the imported target Libdeflate::Libdeflate when both are found.
# Also installed next to breastfitConfig.cmake, which includes it to recreate the target for
# consumers of the installed package (the render layer links it privately: a static library
# still passes it on to whatever links the layer).
include(${CMAKE_CURRENT_LIST_DIR}/import_library.cmake)
breastfit_import_library(Libdeflate::Libdeflate HEADER libdeflate.h LIBRARY deflate)
