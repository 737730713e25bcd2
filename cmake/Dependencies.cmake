# All third-party dependencies, found through find_package (Debian 12 packages;
# scripts/setup.sh installs them).

find_package(embree 3.13 REQUIRED)
find_package(OpenImageIO REQUIRED)
find_package(OpenEXR REQUIRED)
# Debian ships OpenColorIOConfig.cmake directly in /usr/share/cmake.
find_package(OpenColorIO 2.1 REQUIRED PATHS /usr/share/cmake /usr/lib/cmake)
find_package(glm REQUIRED)
find_package(TBB REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)

# Debian's OpenImageIO target lists /usr/include/opencv4 among its include
# directories although OpenCV is optional and the folder is usually absent; CMake
# refuses to generate with a missing imported include directory, so drop it.
foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
  get_target_property(_dirs OpenImageIO::OpenImageIO ${_prop})
  if(_dirs)
    set(_kept "")
    foreach(_d IN LISTS _dirs)
      if(NOT _d MATCHES "opencv4" OR EXISTS "${_d}")
        list(APPEND _kept "${_d}")
      endif()
    endforeach()
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${_prop} "${_kept}")
  endif()
endforeach()
