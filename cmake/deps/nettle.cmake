# Debian's nettle-dev (SHA-256 of the registration's inputs, io/file_sha256.h): header
# nettle/sha2.h and library nettle. Defines the imported target Nettle::Nettle when both are found.
# Also installed next to breastfitConfig.cmake, which includes it to recreate the target for
# consumers of the installed package (the io layer links it privately: a static library still
# passes it on to whatever links the layer).
include(${CMAKE_CURRENT_LIST_DIR}/import_library.cmake)
breastfit_import_library(Nettle::Nettle HEADER nettle/sha2.h LIBRARY nettle)
