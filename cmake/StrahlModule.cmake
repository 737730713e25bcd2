# strahl_module(<name> DEPS <public deps...> PRIVATE_DEPS <private deps...>)
# Builds src/<name>/*.cpp into the static library strahl_<name>; its public
# headers live in include/strahl/<name>/.

function(strahl_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion)
  if(STRAHL_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# With STRAHL_UNITY_SRC, compiles the target's sources 8 to a translation
# unit: few enough that an edit rebuilds little, and enough batches to keep
# both cores of a CI machine busy.
function(strahl_unity target)
  if(STRAHL_UNITY_SRC)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()

function(strahl_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB _sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.cpp)
  file(GLOB _headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/include/strahl/${name}/*.h)
  add_library(strahl_${name} STATIC ${_sources} ${_headers})
  set_target_properties(strahl_${name} PROPERTIES LINKER_LANGUAGE CXX)
  target_include_directories(strahl_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(strahl_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  strahl_warnings(strahl_${name})
  strahl_unity(strahl_${name})
endfunction()
