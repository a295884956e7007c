# The workstation (`breastfit serve`): the serve layer's HTTP library and the page's files.
#
# cpp-httplib from Debian (libcpp-httplib-dev) is a compiled library: httplib.h declares,
# libcpp-httplib.so implements; its header must see the same feature macros it was built with
# (pkg-config's Cflags). Linked by name, so the installed package needs no extra find module.
set(BREASTFIT_HTTPLIB_DEFINITIONS CPPHTTPLIB_OPENSSL_SUPPORT CPPHTTPLIB_ZLIB_SUPPORT CPPHTTPLIB_BROTLI_SUPPORT)
find_library(BREASTFIT_HTTPLIB_LIBRARY cpp-httplib)
find_path(BREASTFIT_HTTPLIB_INCLUDE httplib.h)
if(NOT BREASTFIT_HTTPLIB_LIBRARY OR NOT BREASTFIT_HTTPLIB_INCLUDE)
  message(FATAL_ERROR "cpp-httplib not found (Debian: libcpp-httplib-dev; scripts/setup.sh installs it)")
endif()
target_link_libraries(breastfit_serve PRIVATE cpp-httplib)
target_compile_definitions(breastfit_serve PRIVATE ${BREASTFIT_HTTPLIB_DEFINITIONS}
                           BREASTFIT_BUILD_WEB_ROOT="${PROJECT_BINARY_DIR}/share/breastfit/web")

# The page: web/ (our files) and the three.js modules it imports (web/node_modules, installed by
# scripts/setup.sh with `npm ci` from web/package-lock.json), copied to <build>/share/breastfit/web
# and installed to <prefix>/share/breastfit/web (where the installed binary looks, next to bin/).
set(_web_src ${PROJECT_SOURCE_DIR}/web)
set(_web_out ${PROJECT_BINARY_DIR}/share/breastfit/web)
set(_web_files index.html app.js style.css)
set(_three_files build/three.module.js build/three.core.js examples/jsm/controls/OrbitControls.js)
set(_web_commands)
foreach(f IN LISTS _web_files)
  list(APPEND _web_commands COMMAND ${CMAKE_COMMAND} -E copy_if_different ${_web_src}/${f} ${_web_out}/${f})
  install(FILES ${_web_src}/${f} DESTINATION ${CMAKE_INSTALL_DATADIR}/breastfit/web)
endforeach()
if(EXISTS ${_web_src}/node_modules/three/build/three.module.js)
  foreach(f IN LISTS _three_files)
    get_filename_component(_name ${f} NAME)
    list(APPEND _web_commands COMMAND ${CMAKE_COMMAND} -E copy_if_different ${_web_src}/node_modules/three/${f}
                                      ${_web_out}/vendor/three/${_name})
    install(FILES ${_web_src}/node_modules/three/${f} DESTINATION ${CMAKE_INSTALL_DATADIR}/breastfit/web/vendor/three)
  endforeach()
else()
  message(WARNING "web/node_modules/three is missing (run scripts/setup.sh, or `npm ci` in web/): "
                  "breastfit serve's page will not find three.js")
endif()
add_custom_target(breastfit_web ALL ${CMAKE_COMMAND} -E make_directory ${_web_out}/vendor/three ${_web_commands}
                  COMMENT "Copying the workstation page to share/breastfit/web" VERBATIM)
