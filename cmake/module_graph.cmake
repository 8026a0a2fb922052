# The library's module graph, checked on every build: a module (a folder of
# lib/include/mocapdb and lib/src) may include only the modules listed before it below, so the
# dependencies form no cycle. An upward include fails the build, naming the file and the rule.
#
# One namespace rule, checked here too: the vocabulary modules, whose types every layer passes around
# (Clip, Skeleton, MotionSet, AlignedSet, Tensor3, Database), declare their names in `mocapdb`; every
# other module declares its names in `mocapdb::<module>`. A public header of such a module opens
# `namespace mocapdb {` only for forward declarations (`class Database;`).
# Run: cmake -DLIB_DIR=<repo>/lib -P cmake/module_graph.cmake
set(MOCAPDB_MODULE_ORDER
    core motion io kriging tensor gp procedural dataset compression packing synthesis store
    workflow eval)
set(MOCAPDB_VOCABULARY_MODULES core motion io dataset store)

if(NOT LIB_DIR)
  message(FATAL_ERROR "module_graph.cmake: pass -DLIB_DIR=<repo>/lib")
endif()

set(violations "")
set(seen_modules "")
foreach(module IN LISTS MOCAPDB_MODULE_ORDER)
  list(APPEND seen_modules ${module})
  file(GLOB_RECURSE files "${LIB_DIR}/include/mocapdb/${module}/*" "${LIB_DIR}/src/${module}/*")
  foreach(file IN LISTS files)
    file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"mocapdb/[a-z_]+/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"mocapdb/([a-z_]+)/.*$" "\\1" target "${line}")
      list(FIND seen_modules ${target} allowed)
      if(allowed EQUAL -1)
        file(RELATIVE_PATH rel "${LIB_DIR}/.." "${file}")
        list(FIND MOCAPDB_MODULE_ORDER ${target} known)
        if(known EQUAL -1)
          string(APPEND violations "  ${rel}: includes mocapdb/${target}/, which is not a module of cmake/module_graph.cmake\n")
        else()
          string(APPEND violations "  ${rel}: module '${module}' includes mocapdb/${target}/, a module above it (a cycle or an upward dependency)\n")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

# The namespace rule, on the public headers.
foreach(module IN LISTS MOCAPDB_MODULE_ORDER)
  list(FIND MOCAPDB_VOCABULARY_MODULES ${module} vocabulary)
  file(GLOB headers "${LIB_DIR}/include/mocapdb/${module}/*.hpp")
  foreach(header IN LISTS headers)
    file(RELATIVE_PATH rel "${LIB_DIR}/.." "${header}")
    file(READ "${header}" text)
    if(vocabulary EQUAL -1)
      if(NOT text MATCHES "namespace mocapdb::${module} {")
        string(APPEND violations "  ${rel}: declares nothing in namespace mocapdb::${module} (the namespace of module '${module}')\n")
      endif()
      # Blocks of plain `namespace mocapdb {`: only forward declarations (and nested ones) may be inside.
      # (";" separates CMake list elements: stand-in first.)
      string(REPLACE ";" "@SEMICOLON@" text "${text}")
      string(REGEX MATCHALL "namespace mocapdb {[^}]*}" blocks "${text}")
      foreach(block IN LISTS blocks)
        string(REGEX REPLACE "//[^\n]*" "" rest "${block}")
        string(REGEX REPLACE "(class|struct) [A-Za-z0-9_]+@SEMICOLON@" "" rest "${rest}")
        string(REGEX REPLACE "namespace [a-z_:]+ {" "" rest "${rest}")
        string(REGEX REPLACE "[ \t\n{}]" "" rest "${rest}")
        if(NOT rest STREQUAL "")
          string(APPEND violations "  ${rel}: declares names in namespace mocapdb; module '${module}' declares in mocapdb::${module} (only forward declarations may open mocapdb)\n")
        endif()
      endforeach()
    elseif(text MATCHES "namespace mocapdb::${module} {")
      string(APPEND violations "  ${rel}: module '${module}' is vocabulary: its names belong in namespace mocapdb, not mocapdb::${module}\n")
    endif()
  endforeach()
endforeach()

# Every module folder must be in the order.
file(GLOB dirs LIST_DIRECTORIES true RELATIVE "${LIB_DIR}/src" "${LIB_DIR}/src/*")
foreach(dir IN LISTS dirs)
  if(IS_DIRECTORY "${LIB_DIR}/src/${dir}")
    list(FIND MOCAPDB_MODULE_ORDER ${dir} known)
    if(known EQUAL -1)
      string(APPEND violations "  lib/src/${dir}: a module missing from MOCAPDB_MODULE_ORDER in cmake/module_graph.cmake\n")
    endif()
  endif()
endforeach()

if(violations)
  string(REPLACE ";" " " order "${MOCAPDB_MODULE_ORDER}")
  message(FATAL_ERROR "module graph: a module may include only the modules before it in: ${order}; "
                      "vocabulary modules (${MOCAPDB_VOCABULARY_MODULES}) declare in mocapdb, the others in mocapdb::<module>\n${violations}")
endif()
