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

file(GLOB TARN_FUZZ_REF_SRC ${CMAKE_SOURCE_DIR}/reference/*.c)
add_library(tarn_fuzz_core STATIC
  ${CMAKE_SOURCE_DIR}/viewer/glib.c ${CMAKE_SOURCE_DIR}/viewer/shader_src.c
  ${CMAKE_SOURCE_DIR}/viewer/scene.c ${CMAKE_SOURCE_DIR}/uniforms/unif.c ${TARN_FUZZ_REF_SRC})
target_include_directories(tarn_fuzz_core PUBLIC
  ${CMAKE_SOURCE_DIR}/viewer ${CMAKE_SOURCE_DIR}/uniforms ${CMAKE_SOURCE_DIR}/reference)
target_compile_options(tarn_fuzz_core PRIVATE ${TARN_WARNINGS} -fsanitize=fuzzer-no-link ${TARN_FUZZ_SAN})
find_package(Threads REQUIRED)
target_link_libraries(tarn_fuzz_core PUBLIC Threads::Threads m)

enable_testing()
foreach(t glib shader preset)
  add_executable(fuzz_${t} ${CMAKE_SOURCE_DIR}/tests/fuzz/fuzz_${t}.c)
  target_compile_options(fuzz_${t} PRIVATE ${TARN_WARNINGS} -fsanitize=fuzzer ${TARN_FUZZ_SAN})
  target_link_options(fuzz_${t} PRIVATE -fsanitize=fuzzer ${TARN_FUZZ_SAN})
  target_link_libraries(fuzz_${t} PRIVATE tarn_fuzz_core)
  add_test(NAME fuzz_${t}_run
    COMMAND ${CMAKE_SOURCE_DIR}/tests/fuzz/run.sh $<TARGET_FILE:fuzz_${t}> ${t} ${TARN_FUZZ_SECONDS}
            ${CMAKE_SOURCE_DIR}/tests/fuzz
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
  set_tests_properties(fuzz_${t}_run PROPERTIES TIMEOUT 600)
endforeach()
