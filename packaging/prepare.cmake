# SPDX-License-Identifier: GPL-3.0-or-later
# Run by cpack (CPACK_PRE_BUILD_SCRIPTS, packaging/debian.cmake) on the staged files of every
# package before it is packed: what debhelper's dh_strip does to static libraries (their debug
# sections and compiler notes removed, the archive made deterministic). CPackDeb itself splits the
# debug symbols of the command and the module into the -dbgsym packages and strips them.
if(NOT CPACK_DFORM_INSTALL_PREFIX STREQUAL "/usr")
  message(FATAL_ERROR "the Debian packages install under /usr, and the libraries look for their "
                      "templates under the prefix they were configured with: configure the build "
                      "with -DCMAKE_INSTALL_PREFIX=/usr (it has ${CPACK_DFORM_INSTALL_PREFIX})")
endif()
find_program(strip_program strip REQUIRED)
file(GLOB_RECURSE archives "${CPACK_TEMPORARY_INSTALL_DIRECTORY}/*.a")
foreach(archive ${archives})
  execute_process(COMMAND ${strip_program} --strip-debug --remove-section=.comment
                          --remove-section=.note --enable-deterministic-archives ${archive}
                  COMMAND_ERROR_IS_FATAL ANY)
endforeach()
