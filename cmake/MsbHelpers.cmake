# Helpers that apply the project's standard, warnings and layout to every target.

# msb_set_options(<target>): C++20, -Wall -Wextra -Wpedantic -Wshadow (errors with MSB_WERROR),
# no -march=native / -ffast-math.
function(msb_set_options target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  if(MSB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# msb_add_library(<name> ALIAS <alias> SOURCES ... DEPS ...): a static module library whose
# headers are included as "core/..." or "sim/..." from the project root.
function(msb_add_library name)
  cmake_parse_arguments(ARG "" "ALIAS" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  add_library(msb::${ARG_ALIAS} ALIAS ${name})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  msb_set_options(${name})
endfunction()

# msb_add_test(<name> SOURCES ... DEPS ...): one GoogleTest binary, discovered by ctest.
function(msb_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    MSB_SOURCE_DIR="${PROJECT_SOURCE_DIR}" MSB_BINARY_DIR="${PROJECT_BINARY_DIR}")
  msb_set_options(${name})
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()

# msb_add_method_folders(): every folder beside the calling CMakeLists.txt that has a
# CMakeLists.txt of its own (a method's folder: core/methods/<type>/),
# found by a CONFIGURE_DEPENDS glob, so adding or removing a method needs no edit outside its
# folder and the next build re-runs CMake itself.
macro(msb_add_method_folders)
  file(GLOB _msb_method_dirs LIST_DIRECTORIES true CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT _msb_method_dirs)
  foreach(_msb_dir IN LISTS _msb_method_dirs)
    if(IS_DIRECTORY ${_msb_dir} AND EXISTS ${_msb_dir}/CMakeLists.txt)
      add_subdirectory(${_msb_dir})
    endif()
  endforeach()
endmacro()

# msb_add_method(<name> SOURCES ... DEPS ...): the library of an exploration method kept in a
# folder of its own (core/methods/<type>/); it is linked into the method table
# (tools/config) through the global property MSB_METHOD_LIBRARIES.
function(msb_add_method name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  # A method folder without its registration would build and never be known: refused here.
  set(registers FALSE)
  foreach(src IN LISTS ARG_SOURCES)
    file(READ "${CMAKE_CURRENT_SOURCE_DIR}/${src}" text)
    if(text MATCHES "registerMethod<")
      set(registers TRUE)
    endif()
  endforeach()
  if(NOT registers)
    file(RELATIVE_PATH rel "${PROJECT_SOURCE_DIR}" "${CMAKE_CURRENT_LIST_FILE}")
    message(FATAL_ERROR "${rel}: msb_add_method(${name}) has no source that registers a method "
                        "(registerMethod<...>, docs/architecture.md): msbench would never know it")
  endif()
  msb_add_library(${name} ALIAS ${name} SOURCES ${ARG_SOURCES} DEPS ${ARG_DEPS})
  set_property(GLOBAL APPEND PROPERTY MSB_METHOD_LIBRARIES ${name})
endfunction()
