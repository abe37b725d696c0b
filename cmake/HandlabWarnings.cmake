# Warnings and sanitizers for every handlab target: call handlab_target_setup(tgt).
function(handlab_target_setup target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  # GCC 12 reports -Wrestrict on ordinary std::string concatenation at -O3 (GCC bug 105329).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  if(HANDLAB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR}/generated)
endfunction()

# In the sanitizer tree, a target whose own code runs little under the tests (the tests' own
# fixtures and assertions, the analysis, the studies' orchestration, the CLI's commands)
# compiles at -O1, a fifth to a third faster than at the build type's -O2; the simulator, the
# hands, the retargeting and the participant keep -O2. The code under test runs a little slower
# (the linker may keep an -O1 copy of an Eigen template these targets share with it); the
# figures: CHANGELOG.md, 2026-11-29 (fourteenth session).
function(handlab_compile_lightly_under_sanitizers target)
  if(HANDLAB_SANITIZE)
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()

if(HANDLAB_SANITIZE)
  # UBSan without three checks that cost half a simulated participant's time under the
  # sanitizers (docs/development.md says why each may go): after -fsanitize=undefined, as GCC
  # reads these flags in order.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
                      -fno-sanitize=alignment,null,pointer-overflow
                      # GCC's manual: sanitizers raise -Wmaybe-uninitialized's false positives
                      # (Release still warns).
                      -Wno-maybe-uninitialized
                      # Its debug information would name the build folder, which ccache then
                      # hashes too: mapped away, clones in other folders share the cache
                      # (ccache's manual, "Compiling in different directories").
                      -fdebug-prefix-map=${CMAKE_BINARY_DIR}=.)
  add_link_options(-fsanitize=address,undefined)
endif()

if(HANDLAB_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
