# What `cmake --install` (and so the Debian package, scripts/package.sh) puts where: the two
# programs, the data they find under /usr/share/handlab (core/util/data_files.h), the app's
# desktop entry and icon, and the man pages and bash completion written from the programs'
# --help (cmake/cli_docs.cmake).
include(GNUInstallDirs)
set(handlab_data ${CMAKE_INSTALL_DATADIR}/handlab)

install(TARGETS handlab-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES studies/fine-manipulation-2021.json studies/fine-manipulation-2021-published.json
              studies/fine-manipulation-2021-effects.json
        DESTINATION ${handlab_data}/studies)
install(DIRECTORY studies/examples/ DESTINATION ${handlab_data}/studies/examples
        FILES_MATCHING PATTERN "*.json")
install(DIRECTORY data/leap/ DESTINATION ${handlab_data}/data/leap)

if(TARGET handlab)
  install(TARGETS handlab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES app/handlab.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
  install(FILES app/handlab.svg DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps)
  set(docs ${CMAKE_BINARY_DIR}/docs)
  add_custom_command(
    OUTPUT ${docs}/handlab-cli.1 ${docs}/handlab.1 ${docs}/handlab-cli.bash
    COMMAND ${CMAKE_COMMAND} -E make_directory ${docs}
    COMMAND ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:handlab-cli> -DGUI=$<TARGET_FILE:handlab>
            -DVERSION=${PROJECT_VERSION} -DOUT=${docs} -P ${CMAKE_SOURCE_DIR}/cmake/cli_docs.cmake
    DEPENDS handlab-cli handlab ${CMAKE_SOURCE_DIR}/cmake/cli_docs.cmake
    COMMENT "Man pages and bash completion from the programs' --help" VERBATIM)
  add_custom_target(handlab_cli_docs ALL
                    DEPENDS ${docs}/handlab-cli.1 ${docs}/handlab.1 ${docs}/handlab-cli.bash)
  install(FILES ${docs}/handlab-cli.1 ${docs}/handlab.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
  install(FILES ${docs}/handlab-cli.bash
          DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME handlab-cli)
endif()
