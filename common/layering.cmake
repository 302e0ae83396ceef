# cmake -DLIBRARY=name -DALLOWED=libs -DFILES=files -DSTAMP=file -P layering.cmake
# Fails when one of FILES includes a header of common/ outside ALLOWED (the
# library itself and the libraries below it) or of the folders above common/,
# naming the file and the include.
cmake_policy(VERSION 3.16)  # if(... IN_LIST ...)

# ALLOWED and FILES come joined with |.
string(REPLACE "|" ";" ALLOWED "${ALLOWED}")
string(REPLACE "|" ";" FILES "${FILES}")
set(broken "")
foreach(file IN LISTS FILES)
  file(STRINGS ${file} includes REGEX "^#include \"(common|proto|server|client|tests)/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"common/([a-z_]+)/.*$" "\\1" library "${line}")
    if(NOT line MATCHES "^#include \"common/" OR NOT library IN_LIST ALLOWED)
      string(APPEND broken "\n  ${file}: ${line}")
    endif()
  endforeach()
endforeach()
if(broken)
  list(REMOVE_ITEM ALLOWED ${LIBRARY})
  list(JOIN ALLOWED ", " below)
  if(NOT below)
    set(below "no other library")
  endif()
  message(FATAL_ERROR "common/${LIBRARY} may include its own headers and those of ${below}; "
                      "these includes break the order (move the code, or state the dependency in "
                      "common/CMakeLists.txt):${broken}")
endif()
file(TOUCH ${STAMP})
