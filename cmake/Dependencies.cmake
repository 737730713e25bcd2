# All third-party dependencies, found through find_package (Debian 12 packages;
# scripts/setup.sh installs them).

find_package(embree 3.13 REQUIRED)
find_package(OpenImageIO REQUIRED)
find_package(OpenEXR REQUIRED)
# Debian ships OpenColorIOConfig.cmake directly in /usr/share/cmake.
find_package(OpenColorIO 2.1 REQUIRED PATHS /usr/share/cmake /usr/lib/cmake)
find_package(glm REQUIRED)
find_package(pugixml REQUIRED)  # the Mitsuba 3 XML importer (scene/)
find_package(ZLIB REQUIRED)     # Mitsuba's .serialized meshes (meshio/)
find_package(TBB REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)

# tinygltf (libtinygltf-dev) is used header-only: src/meshio/gltf_parse.cpp
# compiles its implementation without image decoding. Debian's TinyGLTF config
# would link its shared library, which decodes every image with stb_image, so
# only the header is taken (as a system header: its warnings are not ours). Its
# implementation includes <nlohmann/json.hpp>, found above.
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)
add_library(strahl::tinygltf INTERFACE IMPORTED)
set_target_properties(strahl::tinygltf PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${TINYGLTF_INCLUDE_DIR}")

# Two Debian packaging quirks leave imported targets with include directories
# that do not exist, which CMake refuses at generate time:
#  - OpenImageIO lists /usr/include/opencv4 although OpenCV is optional;
#  - OpenColorIO's config sits in /usr/share/cmake, so its relative prefix
#    resolves to "/" and its include directory to "/include".
# Drop the missing folders; OCIO's headers are then found in /usr/include.
function(strahl_drop_missing_include_dirs target)
  foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(_dirs ${target} ${_prop})
    if(_dirs)
      set(_kept "")
      foreach(_d IN LISTS _dirs)
        if(EXISTS "${_d}")
          list(APPEND _kept "${_d}")
        endif()
      endforeach()
      set_target_properties(${target} PROPERTIES ${_prop} "${_kept}")
    endif()
  endforeach()
endfunction()
strahl_drop_missing_include_dirs(OpenImageIO::OpenImageIO)
strahl_drop_missing_include_dirs(OpenColorIO::OpenColorIO)
