# tests/layering/include_layers.cmake — fails on an include that points up the house.
#
# The layers, lowest first (docs/design.md "Layout and layering"):
#   0 core/
#   1 imaging/
#   2 legacy_gl/ modern/ reference/ interpose/ (never each other)
#   3 registry/
#   4 teach/ measure/ (never each other)
#   5 figures/ lab/ (never each other)
#   6 apps/ tools/ python/ (never each other)
# core/'s parts (core/base, core/gl, core/scene, core/technique) are one layer: the check
# keys on the first folder of a path, and files in sub-folders are checked too.
# A source file may include headers of its own folder and of lower layers only.
# Run: cmake -DSOURCE_DIR=<repo> -P include_layers.cmake   (a CTest test, label "core").
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "include_layers.cmake: pass -DSOURCE_DIR=<repository root>")
endif()

set(kLayer_core 0)
set(kLayer_imaging 1)
set(kLayer_legacy_gl 2)
set(kLayer_modern 2)
set(kLayer_reference 2)
set(kLayer_interpose 2)
set(kLayer_registry 3)
set(kLayer_teach 4)
set(kLayer_measure 4)
set(kLayer_figures 5)
set(kLayer_lab 5)
set(kLayer_apps 6)
set(kLayer_tools 6)
set(kLayer_python 6)
set(kModules core imaging legacy_gl modern reference interpose registry teach measure figures lab apps tools python)

set(violations "")
set(checked 0)
foreach(module IN LISTS kModules)
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${module}/*.cpp" "${SOURCE_DIR}/${module}/*.h"
       "${SOURCE_DIR}/${module}/*.inc")
  foreach(source IN LISTS sources)
    math(EXPR checked "${checked} + 1")
    file(STRINGS "${source}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([a-z_]+)/.*" "\\1" target "${line}")
      if(NOT DEFINED kLayer_${target})
        continue()  # a generated or third-party header, not one of our modules
      endif()
      if(target STREQUAL module)
        continue()
      endif()
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${source}")
      if(kLayer_${target} GREATER_EQUAL kLayer_${module})
        string(STRIP "${line}" line)
        list(APPEND violations "${rel}: ${line} (${module} is layer ${kLayer_${module}}, ${target} is layer ${kLayer_${target}})")
      endif()
    endforeach()
  endforeach()
endforeach()

if(NOT MIN_FILES)
  set(MIN_FILES 50)
endif()
if(checked LESS MIN_FILES)
  message(FATAL_ERROR "include_layers.cmake: only ${checked} files found under ${SOURCE_DIR}: wrong folder?")
endif()
if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "includes that point up or sideways in the house:\n  ${text}")
endif()
message(STATUS "include layers: ${checked} files, no include points up")
