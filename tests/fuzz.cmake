# The fuzz targets (tests/fuzz/) replayed in every build: each seed corpus
# and every input a fuzzer crashed on (tests/fuzz/regress_<target>/, kept
# as regression tests). The fuzzing itself is a TARN_FUZZ build (clang).
foreach(t glib shader preset obj)
  add_executable(fuzz_replay_${t} ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/fuzz_${t}.c
                                  ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/replay_main.c)
  if(t STREQUAL "obj")
    # the viewer's OBJ meshes (gfx/geom_obj.c on gfx/geom_build.c) are pure
    # C: compiled into the target as the fuzz build must (it has no GL layer)
    target_sources(fuzz_replay_obj PRIVATE ${CMAKE_SOURCE_DIR}/viewer/gfx/geom_obj.c
                                           ${CMAKE_SOURCE_DIR}/viewer/gfx/geom_build.c)
    target_include_directories(fuzz_replay_obj PRIVATE ${CMAKE_SOURCE_DIR}/viewer/gfx)
  endif()
  target_compile_options(fuzz_replay_${t} PRIVATE ${TARN_WARNINGS})
  target_link_libraries(fuzz_replay_${t} PRIVATE tarn_scene)
  set(dirs ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/corpus_${t})
  if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/regress_${t})
    list(APPEND dirs ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/regress_${t})
  endif()
  # the repository's own files of the target's kind are seeds too, as they
  # are now (tests/fuzz/run.sh does the same for the fuzzing)
  set(exts)
  if(t STREQUAL "glib")
    set(exts glib)
  elseif(t STREQUAL "shader")
    set(exts vert frag geom glsl tesc tese)
  elseif(t STREQUAL "obj")
    set(exts obj)
  endif()
  foreach(ext ${exts})
    foreach(root packs scenes tests/data data)
      file(GLOB_RECURSE found ${CMAKE_SOURCE_DIR}/${root}/*.${ext})
      list(APPEND dirs ${found})
    endforeach()
  endforeach()
  add_test(NAME fuzz_replay_${t} COMMAND fuzz_replay_${t} ${dirs})
  set_tests_properties(fuzz_replay_${t} PROPERTIES TIMEOUT 300 LABELS "fuzz;unit")
endforeach()
