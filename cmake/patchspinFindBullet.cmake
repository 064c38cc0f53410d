# patchspin_find_bullet(<double> [GLOBAL] [REQUIRED] [QUIET]) defines the
# imported target patchspin::bullet_engine: Bullet's dynamics part
# (LinearMath, collision, dynamics; no soft bodies) from Debian's pkg-config
# module `bullet` (float) or `bullet-float64` (double). The double build's
# compile definitions carry BT_USE_DOUBLE_PRECISION to every user.
#
# The build (bullet_integration/CMakeLists.txt) and the installed
# patchspinConfig.cmake both call it, so the exported patchspin::bullet names
# this target and holds no library path of the machine that built it
# (checked by tests/consumer/run_consumer.cmake). Sets
# patchspin_bullet_engine_FOUND in the caller's scope.
function(patchspin_find_bullet double)
  cmake_parse_arguments(arg "GLOBAL;REQUIRED;QUIET" "" "" ${ARGN})
  if(TARGET patchspin::bullet_engine)
    set(patchspin_bullet_engine_FOUND TRUE PARENT_SCOPE)
    return()
  endif()
  set(patchspin_bullet_engine_FOUND FALSE PARENT_SCOPE)
  set(quiet "")
  if(arg_QUIET)
    set(quiet QUIET)
  endif()
  set(required "")
  if(arg_REQUIRED)
    set(required REQUIRED)
  endif()
  if(double)
    set(module bullet-float64)
  else()
    set(module bullet)
  endif()
  find_package(PkgConfig ${quiet} ${required})
  if(NOT PKG_CONFIG_FOUND)
    return()
  endif()
  pkg_check_modules(PATCHSPIN_BULLET_PC ${quiet} ${required} ${module})
  if(NOT PATCHSPIN_BULLET_PC_FOUND)
    return()
  endif()

  # LinearMath, collision and dynamics only
  set(libs "")
  foreach(lib IN LISTS PATCHSPIN_BULLET_PC_LINK_LIBRARIES)
    if(NOT lib MATCHES "SoftBody")
      list(APPEND libs ${lib})
    endif()
  endforeach()
  set(defs "")
  foreach(flag IN LISTS PATCHSPIN_BULLET_PC_CFLAGS_OTHER)
    if(flag MATCHES "^-D(.+)$")
      list(APPEND defs ${CMAKE_MATCH_1})
    endif()
  endforeach()
  if(double AND NOT "BT_USE_DOUBLE_PRECISION" IN_LIST defs)
    list(APPEND defs BT_USE_DOUBLE_PRECISION)
  endif()

  if(arg_GLOBAL)
    add_library(patchspin::bullet_engine INTERFACE IMPORTED GLOBAL)
  else()
    add_library(patchspin::bullet_engine INTERFACE IMPORTED)
  endif()
  # include directories of an imported target are system headers: no
  # warnings from Bullet's headers in our build or in a user's
  set_target_properties(patchspin::bullet_engine PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${PATCHSPIN_BULLET_PC_INCLUDE_DIRS}"
    INTERFACE_COMPILE_DEFINITIONS "${defs}"
    INTERFACE_LINK_LIBRARIES "${libs}")
  set(patchspin_bullet_engine_FOUND TRUE PARENT_SCOPE)
endfunction()
