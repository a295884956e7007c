# The fit layer reads its options from JSON config files.
target_link_libraries(${_target} PUBLIC nlohmann_json::nlohmann_json)
# The fit layer runs its correspondence searches and normal-equation assembly on all cores with
# the process's worker pool (core/chunk_pool.h, std::thread; fit/parallel_chunks.h). Eigen must
# not parallelise on its own inside the layer: the layer decides the order of every sum (results
# independent of the thread count).
if(NOT "${_scope}" STREQUAL "INTERFACE")
  target_compile_definitions(${_target} PRIVATE EIGEN_DONT_PARALLELIZE)
endif()
