# The include order of the project's folders, checked at every build.
#
# Included (top-level CMakeLists.txt), it defines
#   glint_layering(TARGET FOLDER [ON targets...] [FILES files...])
# TARGET's files (FILES, or every .h and .cpp in FOLDER) may include headers
# of FOLDER and of the folders of the targets it is ON, and of theirs; an
# include of any other folder of the project fails the build, naming the file
# and the include. The target is made to wait for the check.
#
# Run as a script (-P), it is that check:
#   cmake -DFOLDER=f -DALLOWED=folders -DFILES=files -DSTAMP=file -P layering.cmake
cmake_policy(VERSION 3.16)  # if(... IN_LIST ...)

if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(GLINT_LAYERING_SCRIPT ${CMAKE_CURRENT_LIST_FILE})
  function(glint_layering target folder)
    cmake_parse_arguments(PARSE_ARGV 2 ARG "" "" "ON;FILES")
    set(allowed ${folder})
    foreach(dep IN LISTS ARG_ON)
      get_property(dep_allowed GLOBAL PROPERTY glint_folders_${dep})
      if(NOT dep_allowed)
        message(FATAL_ERROR "glint_layering(${target}): ${dep} has no layering yet (declare it first)")
      endif()
      list(APPEND allowed ${dep_allowed})
    endforeach()
    list(REMOVE_DUPLICATES allowed)
    set_property(GLOBAL PROPERTY glint_folders_${target} ${allowed})
    list(TRANSFORM ARG_FILES PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/ REGEX "^[^/]")  # relative to the caller's folder
    set(files ${ARG_FILES})
    if(NOT files)
      file(GLOB files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${folder}/*.h ${PROJECT_SOURCE_DIR}/${folder}/*.cpp)
    endif()
    set(stamp ${CMAKE_CURRENT_BINARY_DIR}/${target}_layering.stamp)
    string(JOIN "|" allowed_arg ${allowed})  # lists cross the command line joined with |
    string(JOIN "|" files_arg ${files})
    add_custom_command(OUTPUT ${stamp}
      COMMAND ${CMAKE_COMMAND} -DFOLDER=${folder} -DALLOWED=${allowed_arg} -DFILES=${files_arg} -DSTAMP=${stamp}
              -P ${GLINT_LAYERING_SCRIPT}
      DEPENDS ${files} ${GLINT_LAYERING_SCRIPT}
      COMMENT "Checking that ${folder} includes only its own headers and those of the folders below it" VERBATIM)
    add_custom_target(${target}_layering DEPENDS ${stamp})
    add_dependencies(${target} ${target}_layering)
  endfunction()
  return()
endif()

# ALLOWED and FILES come joined with |.
string(REPLACE "|" ";" ALLOWED "${ALLOWED}")
string(REPLACE "|" ";" FILES "${FILES}")
set(broken "")
foreach(file IN LISTS FILES)
  file(STRINGS ${file} includes REGEX "^#include \"(common|proto|server|client|tests)/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([a-z_/]+)/[^/\"]+\".*$" "\\1" included "${line}")
    if(NOT included IN_LIST ALLOWED)
      string(APPEND broken "\n  ${file}: ${line}")
    endif()
  endforeach()
endforeach()
if(broken)
  list(REMOVE_ITEM ALLOWED ${FOLDER})
  list(JOIN ALLOWED ", " below)
  if(NOT below)
    set(below "no other folder")
  endif()
  message(FATAL_ERROR "${FOLDER} may include its own headers and those of ${below}; these includes break "
                      "the order (move the code, or state the dependency where ${FOLDER}'s target is "
                      "declared):${broken}")
endif()
file(TOUCH ${STAMP})
