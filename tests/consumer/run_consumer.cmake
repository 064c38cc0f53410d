# Builds and runs the user project of tests/consumer against patchspin, in one
# of two modes (MODE):
#  * install: installs the already-built patchspin into a clean scratch prefix,
#    fails if an installed patchspin*.cmake names an absolute path outside that
#    prefix (a Bullet library of the build machine, say), then configures,
#    builds and runs the consumer with find_package(patchspin);
#  * embed: the consumer embeds the source tree with add_subdirectory, with a
#    pkg-config search path that holds Bullet's modules and nothing else, so
#    that a need for OSMesa or cairo fails the configure; the configure log and
#    cache must name none of the renderer's or the apps' dependencies.
# Inputs: MODE, SOURCE_DIR, BINARY_DIR (install), WORK_DIR, CONSUMER_DIR,
# BULLET, BULLET_DOUBLE, LAUNCHER (compiler launcher, may be empty).
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(env "")
set(extra "")
if(LAUNCHER)
  list(APPEND extra -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()

if(MODE STREQUAL "install")
  execute_process(COMMAND ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${prefix} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install failed (${rc})")
  endif()
  # absolute paths in the installed package files: only inside the prefix
  file(GLOB package_files ${prefix}/*/cmake/patchspin/*.cmake)
  if(NOT package_files)
    message(FATAL_ERROR "no installed package files under ${prefix}/*/cmake/patchspin")
  endif()
  set(foreign "")
  foreach(f ${package_files})
    file(STRINGS ${f} lines)
    foreach(line IN LISTS lines)
      if(line MATCHES "^[ \t]*#")
        continue()
      endif()
      string(REGEX MATCHALL "[^ \t\"'()]+" tokens "${line}")
      foreach(token IN LISTS tokens)
        if(token MATCHES "^/." AND NOT token MATCHES "^${prefix}/")
          list(APPEND foreign "${f}: ${token}")
        endif()
      endforeach()
    endforeach()
  endforeach()
  if(foreign)
    list(JOIN foreign "\n  " foreign)
    message(FATAL_ERROR "installed package files name absolute paths outside the prefix:\n  ${foreign}")
  endif()
  list(LENGTH package_files n)
  message(STATUS "${n} installed package files, no absolute path outside ${prefix}")
  list(APPEND extra -DCMAKE_PREFIX_PATH=${prefix} -DCONSUMER_PREFIX=${prefix})
elseif(MODE STREQUAL "embed")
  # Bullet's pkg-config modules alone on the search path
  set(pcdir ${WORK_DIR}/pkgconfig)
  file(MAKE_DIRECTORY ${pcdir})
  execute_process(COMMAND pkg-config --variable=pcfiledir bullet OUTPUT_VARIABLE bullet_pcdir
                  OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config cannot find bullet")
  endif()
  foreach(pc bullet bullet-float64)
    if(EXISTS ${bullet_pcdir}/${pc}.pc)
      file(COPY ${bullet_pcdir}/${pc}.pc DESTINATION ${pcdir})
    endif()
  endforeach()
  set(env ${CMAKE_COMMAND} -E env PKG_CONFIG_LIBDIR=${pcdir} PKG_CONFIG_PATH=)
  list(APPEND extra -DCONSUMER_EMBED_SOURCE=${SOURCE_DIR} -DPATCHSPIN_BULLET_DOUBLE=${BULLET_DOUBLE}
       -DPATCHSPIN_BUILD_BULLET=${BULLET})
else()
  message(FATAL_ERROR "MODE must be install or embed, not '${MODE}'")
endif()

execute_process(COMMAND ${env} ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build
                -DCMAKE_BUILD_TYPE=Release -DCONSUMER_WITH_BULLET=${BULLET}
                -DCONSUMER_BULLET_DOUBLE=${BULLET_DOUBLE} ${extra}
                RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
message(STATUS "consumer configure:\n${log}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer configure failed (${rc})")
endif()
if(MODE STREQUAL "embed")
  # nothing of the renderer, the demos, the tools, the tests or the benchmarks
  file(READ ${WORK_DIR}/build/CMakeCache.txt cache)
  foreach(dep osmesa OSMESA cairo CAIRO Freetype FREETYPE PNG_ DejaVu FONT_FILE gnuplot GNUPLOT CLI11 nlohmann
              GTest benchmark_DIR)
    if(log MATCHES "${dep}" OR cache MATCHES "${dep}")
      message(FATAL_ERROR "the embedded configure looked for '${dep}' (an app or renderer dependency)")
    endif()
  endforeach()
  message(STATUS "embedded configure: no renderer or app dependency in its log or cache")
  # the libraries' targets, and none of the apps'; not built again here (the
  # same sources are built and tested by the top-level build), which keeps
  # the CI run short
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build --target help RESULT_VARIABLE rc
                  OUTPUT_VARIABLE targets)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "listing the embedded build's targets failed (${rc})")
  endif()
  set(expected patchspin_core)
  if(BULLET)
    list(APPEND expected patchspin_bullet)
  endif()
  foreach(target ${expected})
    if(NOT targets MATCHES "\\.\\.\\. ${target}\n")
      message(FATAL_ERROR "the embedded build has no target ${target}:\n${targets}")
    endif()
  endforeach()
  foreach(target patchspin_render patchspin_scenes patchspin_tool coin blocks determinism_test bench_bullet_world)
    if(targets MATCHES "\\.\\.\\. ${target}\n")
      message(FATAL_ERROR "the embedded build has the app target ${target}")
    endif()
  endforeach()
  message(STATUS "embedded build: targets ${expected}, no renderer, scene, tool, demo, test or benchmark target")
  return()
endif()

execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j2 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer build failed (${rc})")
endif()
set(programs consumer_core)
if(BULLET)
  list(APPEND programs consumer_bullet consumer_bounce consumer_robot_foot consumer_precision)
endif()
foreach(program ${programs})
  execute_process(COMMAND ${WORK_DIR}/build/${program} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${program} failed (${rc}): ${out}")
  endif()
  message(STATUS "${program} ran: ${out}")
endforeach()
