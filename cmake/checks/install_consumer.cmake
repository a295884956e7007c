# cmake -DSOURCE_DIR=<repo> -DBUILD_DIR=<build> -DWORK_DIR=<scratch> -DCXX_COMPILER=<c++>
#       -DGENERATOR=<generator> [-DBUILD_TYPE=Release] [-DLAUNCHER=ccache] [-DNATIVE=ON]
#       -P install_consumer.cmake
#
# Installs the build into WORK_DIR/prefix, checks the installed headers are self-contained (every
# breastfit header they include is installed), builds examples/cpp against the prefix with the
# same compiler, runs it and the installed CLI, and checks what they print.
cmake_minimum_required(VERSION 3.20)
foreach(var SOURCE_DIR BUILD_DIR WORK_DIR CXX_COMPILER GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()
set(prefix ${WORK_DIR}/prefix)

# Runs a command; fails with its output unless it succeeds. Its stdout is returned in `out`.
function(run out)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " cmd)
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${stdout}\n${stderr}")
  endif()
  set(${out} "${stdout}" PARENT_SCOPE)
endfunction()

# Fails unless `text` (printed by `what`) matches `regex`.
function(expect what text regex)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "${what} printed\n${text}\nwhich does not match: ${regex}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
run(_ ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# Installed headers: no detail/ headers, and each breastfit header they include is installed.
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/breastfit/*.h)
list(LENGTH headers n_headers)
if(n_headers EQUAL 0)
  message(FATAL_ERROR "no headers installed under ${prefix}/include/breastfit")
endif()
foreach(h IN LISTS headers)
  if(h MATCHES "/detail/")
    message(FATAL_ERROR "a private header is installed: ${h}")
  endif()
  file(STRINGS ${prefix}/include/${h} includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]breastfit/")
  foreach(inc IN LISTS includes)
    string(REGEX REPLACE "^[^<\"]*[<\"]([^\">]*)[\">].*$" "\\1" inc "${inc}")
    if(NOT EXISTS ${prefix}/include/${inc})
      message(FATAL_ERROR "installed ${h} includes ${inc}, which is not installed")
    endif()
  endforeach()
endforeach()
foreach(f bin/breastfit bin/breastfit-serve share/breastfit/default_torso.glb)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${prefix}/${f}")
  endif()
endforeach()
foreach(f libbreastfit_mesh.a breastfitConfig.cmake breastfitConfigVersion.cmake)  # lib/ or lib/<arch>/
  file(GLOB_RECURSE found ${prefix}/lib*/${f})
  if(NOT found)
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

# The example, configured and built against the prefix only.
set(configure_args -S ${SOURCE_DIR}/examples/cpp -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_EXPORT_COMPILE_COMMANDS=ON)
if(BUILD_TYPE)
  list(APPEND configure_args -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
endif()
if(LAUNCHER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run(_ ${CMAKE_COMMAND} ${configure_args})
run(_ ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j2)
if(NATIVE)
  file(READ ${WORK_DIR}/build/compile_commands.json commands)
  expect("compile_commands.json of the example" "${commands}" "-march=native")
endif()

# Run them without BREASTFIT_TEMPLATE, so each must find the installed template itself.
unset(ENV{BREASTFIT_TEMPLATE})
set(template ${prefix}/share/breastfit/default_torso.glb)
run(out ${WORK_DIR}/build/breastfit_example)
message(STATUS "example:\n${out}")
expect("breastfit_example" "${out}" "template: ${template}\n")
expect("breastfit_example" "${out}" "vertices: [1-9][0-9]* faces: [1-9][0-9]* bones: [1-9]")
expect("breastfit_example" "${out}" "height ratio: 1\\.100\n")
expect("breastfit_example" "${out}" "body frame: landmarks")
run(out ${prefix}/bin/breastfit template info)
expect("the installed breastfit template info" "${out}" "${template}")
run(out ${prefix}/bin/breastfit serve --help)  # runs the installed breastfit-serve beside it
expect("the installed breastfit serve --help" "${out}" "--workspace")
message(STATUS "install.consumer: ${n_headers} headers; the example and the installed CLI use ${template}")
