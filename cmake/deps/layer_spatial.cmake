# Included inside breastfit_layer(spatial ...): ${_target} is breastfit_spatial.
# nanoflann (Debian libnanoflann-dev 1.4.3, header-only) is used only inside
# src/breastfit/spatial/knn_index.cpp (PImpl), so it is a PRIVATE dependency.
if(NOT TARGET nanoflann::nanoflann)
  find_package(nanoflann REQUIRED)
endif()
if(NOT "${_scope}" STREQUAL "INTERFACE")
  target_link_libraries(${_target} PRIVATE nanoflann::nanoflann)
endif()
# The index builds run their per-face and per-leaf loops on several threads with OpenMP
# (spatial/detail/parallel_for.h; deterministic: fixed chunks). PRIVATE, like the fit layer's.
if(NOT "${_scope}" STREQUAL "INTERFACE")
  find_package(OpenMP REQUIRED COMPONENTS CXX)
  target_link_libraries(${_target} PRIVATE OpenMP::OpenMP_CXX)
endif()
