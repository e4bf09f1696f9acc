# Checks that every library includes only headers of the libraries it links (radiosity/CMakeLists.txt has
# the picture). The links already stop a wrong-way call from linking; this also catches a header-only use
# (an inline function, a struct) that the linker never sees. Run by CTest: cmake -DROOT=<repo> -P layering.cmake
cmake_minimum_required(VERSION 3.22)
set(allowed_core core)
# report.html's writer (core/html_report/CMakeLists.txt); its generated viewer header is core/html_report/ too.
set(allowed_core/html_report core core/html_report)
set(allowed_scenes core scenes)
set(allowed_decomposition core decomposition)
set(allowed_radiosity/metrics radiosity/metrics)
set(allowed_radiosity/lightmap core radiosity/lightmap)
set(allowed_radiosity/solve core radiosity/lightmap radiosity/solve)
set(allowed_radiosity/cpu core radiosity/lightmap radiosity/solve radiosity/cpu)
set(allowed_radiosity/gpu core radiosity/lightmap radiosity/solve radiosity/gpu)
set(allowed_radiosity/cells core radiosity/lightmap radiosity/solve radiosity/cells)
set(allowed_radiosity/reference core radiosity/lightmap radiosity/metrics radiosity/reference)
set(allowed_radiosity/bake core core/html_report decomposition radiosity/lightmap radiosity/solve radiosity/cpu
    radiosity/gpu radiosity/cells radiosity/bake)

set(failures "")
foreach(library core core/html_report scenes decomposition radiosity/metrics radiosity/lightmap radiosity/solve
        radiosity/cpu radiosity/gpu radiosity/cells radiosity/reference radiosity/bake)
  file(GLOB sources ${ROOT}/${library}/*.h ${ROOT}/${library}/*.cpp)
  foreach(source IN LISTS sources)
    file(STRINGS ${source} includes REGEX "^#include \"")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([^\"]*)\".*" "\\1" header "${line}")
      get_filename_component(dir "${header}" DIRECTORY)
      if(NOT dir IN_LIST allowed_${library})
        file(RELATIVE_PATH name ${ROOT} ${source})
        string(APPEND failures "  ${name} includes ${header}, outside ${library}'s links\n")
      endif()
    endforeach()
  endforeach()
endforeach()
# radiosity/ itself holds only the sub-libraries.
file(GLOB top ${ROOT}/radiosity/*.h ${ROOT}/radiosity/*.cpp)
foreach(source IN LISTS top)
  string(APPEND failures "  ${source}: sources belong in a sub-library of radiosity/\n")
endforeach()
if(failures)
  message(FATAL_ERROR "layering:\n${failures}")
endif()
message(STATUS "layering: every include follows the links")
