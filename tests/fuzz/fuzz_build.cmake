# TARN_FUZZ: the libFuzzer targets, built alone (no OpenGL, no C++ libraries)
# from the pure-C modules they exercise, every one instrumented. Included by
# the top-level CMakeLists.txt, which then stops.
#
#   cmake -S . -B build-fuzz -DTARN_FUZZ=ON -DCMAKE_C_COMPILER=clang
#   cmake --build build-fuzz && cd build-fuzz && ctest      # a short run of each
#   build-fuzz/fuzz_glib -max_total_time=600 CORPUS_DIR tests/fuzz/corpus_glib   # a long one
#
# ctest runs each target for TARN_FUZZ_SECONDS (tests/fuzz/run.sh) on a copy
# of its seed corpus and its regressions; a crash fails the test and leaves
# the input under build-fuzz/fuzz-artifacts/, to be added to
# tests/fuzz/regress_<target>/ (replayed by every normal build's ctest).
if(NOT CMAKE_C_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "TARN_FUZZ needs clang (libFuzzer): configure a fresh build directory with "
                      "-DCMAKE_C_COMPILER=clang (Debian: apt-get install clang libclang-rt-14-dev)")
endif()
set(TARN_FUZZ_SECONDS 20 CACHE STRING "Seconds each fuzz target runs in ctest")
set(TARN_FUZZ_SAN -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)

# The pure-C layers (base, reference, the uniform model, scene), every
# file instrumented: the same targets a normal build defines.
add_compile_options(-fsanitize=fuzzer-no-link ${TARN_FUZZ_SAN})
add_subdirectory(${CMAKE_SOURCE_DIR}/reference ${CMAKE_BINARY_DIR}/reference)
add_subdirectory(${CMAKE_SOURCE_DIR}/uniforms ${CMAKE_BINARY_DIR}/uniforms)
add_subdirectory(${CMAKE_SOURCE_DIR}/viewer ${CMAKE_BINARY_DIR}/viewer)

enable_testing()
foreach(t glib shader preset obj)
  add_executable(fuzz_${t} ${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_${t}.c)
  if(t STREQUAL "obj")   # the viewer's OBJ meshes: pure C, compiled in (tests/fuzz.cmake says why)
    target_sources(fuzz_obj PRIVATE ${CMAKE_SOURCE_DIR}/viewer/gfx/geom_obj.c ${CMAKE_SOURCE_DIR}/viewer/gfx/geom_build.c)
    target_include_directories(fuzz_obj PRIVATE ${CMAKE_SOURCE_DIR}/viewer/gfx)
  endif()
  target_compile_options(fuzz_${t} PRIVATE ${TARN_WARNINGS} -fsanitize=fuzzer ${TARN_FUZZ_SAN})
  target_link_options(fuzz_${t} PRIVATE -fsanitize=fuzzer ${TARN_FUZZ_SAN})
  target_link_libraries(fuzz_${t} PRIVATE tarn_scene)
  add_test(NAME fuzz_${t}_run
    COMMAND ${CMAKE_SOURCE_DIR}/tests/fuzz/run.sh $<TARGET_FILE:fuzz_${t}> ${t} ${TARN_FUZZ_SECONDS}
            ${CMAKE_SOURCE_DIR}/tests/fuzz
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
  set_tests_properties(fuzz_${t}_run PROPERTIES TIMEOUT 600 LABELS "fuzz;slow")
endforeach()
