# Serialisation stays out of the domain headers: no header under SRC mentions nlohmann (an
# #include of <nlohmann/...> or a nlohmann:: type) unless its name ends in _json.h, the files
# whose interface is JSON (e.g. model/params_json.h beside model/pose_params.h). Comment lines
# are ignored. Run as a script:
#   cmake -DSRC=<dir of headers> -P no_json_in_headers.cmake
# Fails (FATAL_ERROR) listing every offending header.
cmake_minimum_required(VERSION 3.20)

if(NOT DEFINED SRC OR NOT IS_DIRECTORY "${SRC}")
  message(FATAL_ERROR "no_json_in_headers: SRC='${SRC}' is not a directory")
endif()

# Headers still allowed to use nlohmann, relative to SRC (none today; name a reason beside any).
set(_exempt)

file(GLOB_RECURSE _headers RELATIVE "${SRC}" "${SRC}/*.h" "${SRC}/*.hpp")
list(SORT _headers)
set(_offenders "")
foreach(h IN LISTS _headers)
  if(h MATCHES "_json\\.(h|hpp)$" OR h IN_LIST _exempt)
    continue()
  endif()
  file(STRINGS "${SRC}/${h}" _lines REGEX "nlohmann")
  foreach(line IN LISTS _lines)
    if(NOT line MATCHES "^[ \t]*//")
      list(APPEND _offenders "${h}: ${line}")
      break()
    endif()
  endforeach()
endforeach()

if(_offenders)
  list(LENGTH _offenders _n)
  list(JOIN _offenders "\n  " _list)
  message(FATAL_ERROR
    "${_n} domain header(s) use nlohmann::json; move the (de)serialisation into a *_json.h/.cpp "
    "beside the type (see breastfit/model/params_json.h):\n  ${_list}")
endif()
list(LENGTH _headers _n)
message(STATUS "no_json_in_headers: ${_n} headers checked, none outside *_json.h uses nlohmann")
