# breastfit_import_library(<target> HEADER <file> LIBRARY <name> [SUFFIX <dir>]): an imported
# INTERFACE target for a Debian library that ships no CMake package, defined when both its header
# and its library are found (nothing is defined otherwise; the caller decides whether that is an
# error). Installed next to breastfitConfig.cmake with the files that call it, which recreate
# their targets for consumers of the installed package.
function(breastfit_import_library target)
  cmake_parse_arguments(ARG "" "HEADER;LIBRARY;SUFFIX" "" ${ARGN})
  if(TARGET ${target})
    return()
  endif()
  string(MAKE_C_IDENTIFIER "${target}" var)
  find_path(${var}_INCLUDE_DIR ${ARG_HEADER} PATH_SUFFIXES ${ARG_SUFFIX})
  find_library(${var}_LIBRARY ${ARG_LIBRARY})
  if(${var}_INCLUDE_DIR AND ${var}_LIBRARY)
    add_library(${target} INTERFACE IMPORTED)
    set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${${var}_INCLUDE_DIR}"
                                               INTERFACE_LINK_LIBRARIES "${${var}_LIBRARY}")
  endif()
endfunction()
