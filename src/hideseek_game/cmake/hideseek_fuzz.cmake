# Fuzz targets and sanitizer builds (issue #49), for every package that builds on hideseek_game
# (catkin exports this file with it).
#
# hideseek_fuzz_target(NAME SOURCE CORPUS_DIR LIBRARIES...): SOURCE defines LLVMFuzzerTestOneInput.
#  - With testing on, NAME_replay is a gtest replaying every file of CORPUS_DIR once (make test):
#    SOURCE linked with fuzz_replay_main.cpp.
#  - With HIDESEEK_FUZZ on (a clang build: make fuzz), NAME is a libFuzzer binary.
# HIDESEEK_SANITIZE (a clang or gcc build: make test-sanitize, make fuzz) compiles everything with
# AddressSanitizer and UndefinedBehaviorSanitizer, stopping at the first error.
option(HIDESEEK_SANITIZE "build with -fsanitize=address,undefined" OFF)
option(HIDESEEK_FUZZ "build the libFuzzer targets (clang)" OFF)
if(HIDESEEK_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  # (add_link_options needs CMake 3.13; the packages ask for 3.10)
  string(APPEND CMAKE_EXE_LINKER_FLAGS " -fsanitize=address,undefined")
  string(APPEND CMAKE_SHARED_LINKER_FLAGS " -fsanitize=address,undefined")
  string(APPEND CMAKE_MODULE_LINKER_FLAGS " -fsanitize=address,undefined")
endif()
if(HIDESEEK_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)  # coverage of the libraries the targets call
endif()

# The replay's gtest, beside this file (in the source tree for the devel space, installed beside it).
set(HIDESEEK_FUZZ_REPLAY_MAIN "${CMAKE_CURRENT_LIST_DIR}/fuzz_replay_main.cpp")

function(hideseek_fuzz_target name source corpus)
  if(CATKIN_ENABLE_TESTING)
    catkin_add_gtest(${name}_replay ${source} ${HIDESEEK_FUZZ_REPLAY_MAIN})
    target_compile_definitions(${name}_replay PRIVATE HIDESEEK_FUZZ_CORPUS="${corpus}")
    target_link_libraries(${name}_replay ${ARGN} gtest_main)
  endif()
  if(HIDESEEK_FUZZ)
    add_executable(${name} ${source})
    target_link_libraries(${name} ${ARGN})
    set_property(TARGET ${name} APPEND_STRING PROPERTY LINK_FLAGS " -fsanitize=fuzzer")
  endif()
endfunction()
