if(TARGET nlohmann_json::nlohmann_json)
  return()
endif()
find_package(nlohmann_json 3 REQUIRED)
