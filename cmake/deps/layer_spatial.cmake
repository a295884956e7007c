# Included inside breastfit_layer(spatial ...): ${_target} is breastfit_spatial.
# nanoflann (Debian libnanoflann-dev 1.4.3, header-only) is used only inside
# src/breastfit/spatial/knn_index.cpp (PImpl), so it is a PRIVATE dependency.
if(NOT TARGET nanoflann::nanoflann)
  find_package(nanoflann REQUIRED)
endif()
if(NOT "${_scope}" STREQUAL "INTERFACE")
  target_link_libraries(${_target} PRIVATE nanoflann::nanoflann)
endif()
