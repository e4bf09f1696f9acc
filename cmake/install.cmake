# `cmake --install build --prefix P`: the cpgi tools in P/bin, the libraries' headers in P/include/cpgi
# (included as "radiosity/bake/bake.h", as in the sources), the static libraries in P/lib and the CMake
# package in P/lib/cmake/cpgi: find_package(cpgi) gives cpgi::cpgi, the bake() library with everything
# below it (examples/ builds against it).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# cpgi::cpgi: what a program that bakes links.
add_library(cpgi_library INTERFACE)
target_link_libraries(cpgi_library INTERFACE cpgi_bake)
set_target_properties(cpgi_library PROPERTIES EXPORT_NAME cpgi)

set(CPGI_EXPORTED_LIBRARIES cpgi_library cpgi_bake cpgi_cells cpgi_gpu cpgi_cpu cpgi_solve cpgi_lightmap
                            cpgi_decomposition cpgi_html_report cpgi_core)
# A sanitized build's libraries (CPGI_SANITIZE, bench/sanitizer_suite.sh) call the sanitizers' runtime: a
# program linking the installed package links that runtime too, or its link fails on __asan_* symbols.
if(CPGI_SANITIZE)
  target_link_options(cpgi_core INTERFACE $<INSTALL_INTERFACE:-fsanitize=address,undefined>)
endif()
install(TARGETS ${CPGI_EXPORTED_LIBRARIES} EXPORT cpgiTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/cpgi)
install(TARGETS cpgi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(PROGRAMS ${CMAKE_BINARY_DIR}/apps/cpgi-dask DESTINATION ${CMAKE_INSTALL_BINDIR})
# Every header of the libraries: bake.h reaches most of them through bake_settings.h.
install(DIRECTORY core decomposition radiosity DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/cpgi
        FILES_MATCHING PATTERN "*.h"
        PATTERN "web" EXCLUDE)

install(EXPORT cpgiTargets NAMESPACE cpgi:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/cpgi)
configure_package_config_file(cmake/cpgiConfig.cmake.in ${CMAKE_BINARY_DIR}/cpgiConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/cpgi)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cpgiConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cpgiConfig.cmake ${CMAKE_BINARY_DIR}/cpgiConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/cpgi)
