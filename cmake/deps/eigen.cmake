if(TARGET Eigen3::Eigen)
  return()
endif()
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
