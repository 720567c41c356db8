# SPDX-License-Identifier: GPL-3.0-or-later
# Run by cpack (CPACK_POST_BUILD_SCRIPTS, packaging/debian.cmake) once the packages are made: each
# -dbgsym package (.ddeb) is made again as debhelper makes one. CPackDeb writes its md5sums with
# the staging folder's absolute paths and gives it no documentation; here md5sums lists its files
# relative to /, and /usr/share/doc/<package>-dbgsym is a link to the documentation (copyright,
# changelog) of the package it depends on, as dh_strip does it.
find_program(dpkg_deb dpkg-deb REQUIRED)
foreach(package_file ${CPACK_PACKAGE_FILES})
  if(NOT package_file MATCHES "/([a-z0-9.+-]+)-dbgsym_[^/]*\\.ddeb$")
    continue()
  endif()
  set(main ${CMAKE_MATCH_1})
  set(tree ${package_file}.tree)
  file(REMOVE_RECURSE ${tree})
  execute_process(COMMAND ${dpkg_deb} --raw-extract ${package_file} ${tree} COMMAND_ERROR_IS_FATAL ANY)
  file(GLOB_RECURSE files RELATIVE ${tree} LIST_DIRECTORIES false ${tree}/usr/*)
  list(SORT files)
  set(md5sums "")
  foreach(file ${files})
    file(MD5 ${tree}/${file} sum)
    string(APPEND md5sums "${sum}  ${file}\n")
  endforeach()
  file(WRITE ${tree}/DEBIAN/md5sums "${md5sums}")
  file(MAKE_DIRECTORY ${tree}/usr/share/doc)
  file(CREATE_LINK ${main} ${tree}/usr/share/doc/${main}-dbgsym SYMBOLIC)
  execute_process(COMMAND ${dpkg_deb} --root-owner-group -Zxz --build ${tree} ${package_file}
                  OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
  file(REMOVE_RECURSE ${tree})
endforeach()
