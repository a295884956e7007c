# The fit layer reads its options from JSON config files.
target_link_libraries(${_target} PUBLIC nlohmann_json::nlohmann_json)
# The fit layer runs its correspondence searches and normal-equation assembly on all cores with
# OpenMP (GCC's libgomp; fit/parallel_chunks.h). PRIVATE: only the fit layer's sources are
# compiled with -fopenmp (its headers need no OpenMP); consumers link libgomp through the static
# library. Eigen must not parallelise on its own inside the layer: the layer decides the order
# of every sum (results independent of the thread count).
if(NOT "${_scope}" STREQUAL "INTERFACE")
  find_package(OpenMP REQUIRED COMPONENTS CXX)
  target_link_libraries(${_target} PRIVATE OpenMP::OpenMP_CXX)
  target_compile_definitions(${_target} PRIVATE EIGEN_DONT_PARALLELIZE)
endif()
