# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian packages (docs/packaging.md), made by `cpack` in a build folder configured with
# -DCMAKE_INSTALL_PREFIX=/usr (scripts/make-packages does both and runs lintian):
#   dform          the command, its man page and bash completion, the templates, the user docs
#   libdform-dev   the static libraries, public headers and CMake package, the API reference
#   python3-dform  the Python module for Debian's python3, its dist-info and reference
# each with /usr/share/doc/<package>/copyright (DEP-5) and changelog.gz, and a -dbgsym package of
# the debug symbols split off the command and the module. One install component per package
# (the install() calls name it): cli, dev, python.
include(GNUInstallDirs)

set(DFORM_MAINTAINER "dform maintainers <maintainers@users.noreply.h-seed-d3f04227.example>")
set(DFORM_DEBIAN_DIR ${PROJECT_SOURCE_DIR}/packaging/debian)

# The Debian changelog's newest entry is the version being packaged.
file(STRINGS ${DFORM_DEBIAN_DIR}/changelog changelog_top LIMIT_COUNT 1)
if(NOT changelog_top MATCHES "^dform \\(${PROJECT_VERSION}\\) ")
  message(FATAL_ERROR "packaging/debian/changelog: its newest entry '${changelog_top}' is not "
                      "version ${PROJECT_VERSION} of CMakeLists.txt")
endif()

# changelog.gz as dh_installchangelogs and dh_compress make it: gzip -9n (no name or time), so
# the same changelog gives the same bytes.
set(packaging_dir ${PROJECT_BINARY_DIR}/packaging)
# Made here: a build without the Python module (the sanitizer's) makes nothing else in it first.
file(MAKE_DIRECTORY ${packaging_dir})
add_custom_command(OUTPUT ${packaging_dir}/changelog.gz
  COMMAND gzip -9nc ${DFORM_DEBIAN_DIR}/changelog > ${packaging_dir}/changelog.gz
  DEPENDS ${DFORM_DEBIAN_DIR}/changelog
  COMMENT "Compressing the Debian changelog")
add_custom_target(dform_debian_changelog ALL DEPENDS ${packaging_dir}/changelog.gz)

set(dform_components cli dev)
set(package_cli dform)
set(package_dev libdform-dev)
if(TARGET dform_python)
  list(APPEND dform_components python)
  set(package_python python3-dform)
endif()
foreach(component ${dform_components})
  install(FILES ${DFORM_DEBIAN_DIR}/copyright ${packaging_dir}/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package_${component}} COMPONENT ${component})
endforeach()

# The docs each package installs beside its copyright (the man page names them).
set(docs ${PROJECT_SOURCE_DIR}/docs)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${docs}/cli.md ${docs}/cli-output.schema.json
              ${docs}/io.md ${docs}/export.md ${docs}/report.md ${docs}/validation.md
              ${docs}/variants.md ${docs}/exact.md ${docs}/ruled.md ${docs}/inverse.md
              ${docs}/meshing.md ${docs}/sweep.md ${docs}/batch.md ${docs}/studio.md
              ${docs}/samples.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/dform COMPONENT cli)
install(DIRECTORY ${docs}/images DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/dform COMPONENT cli)
install(FILES ${docs}/api.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/libdform-dev COMPONENT dev)
if(TARGET dform_python)
  install(FILES ${docs}/python.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/python3-dform
          COMPONENT python)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL ${dform_components})
set(CPACK_PACKAGE_NAME dform)
set(CPACK_PACKAGE_VENDOR dform)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_PRE_BUILD_SCRIPTS ${PROJECT_SOURCE_DIR}/packaging/prepare.cmake)
set(CPACK_POST_BUILD_SCRIPTS ${PROJECT_SOURCE_DIR}/packaging/finish.cmake)  # the -dbgsym packages
set(CPACK_DFORM_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})  # read by prepare.cmake
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${DFORM_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_SOURCE dform)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)

# dform: the command. dpkg-shlibdeps names the shared libraries it loads; the exporter reads the
# Hershey fonts of hershey-fonts-data at run time.
set(CPACK_DEBIAN_CLI_PACKAGE_NAME dform)
set(CPACK_DEBIAN_CLI_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_CLI_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_CLI_DEBUGINFO_PACKAGE ON)
set(CPACK_DEBIAN_CLI_PACKAGE_DEPENDS hershey-fonts-data)
set(CPACK_DEBIAN_CLI_PACKAGE_SUGGESTS "libdform-dev, python3-dform")
set(CPACK_COMPONENT_CLI_DESCRIPTION "design and cut D-Forms from two flat pieces
A D-Form is made by cutting two flat pieces with the same perimeter and
zipping their edges together: the sheet bends into a 3D shape without
stretching. The dform command computes that shape from two outlines
(forward), the two pieces of a closed 3D seam curve (inverse), checks it
against a quality gate and writes cut-ready patterns (SVG, DXF, PDF), STL
and glTF previews and an HTML report. dform studio designs one in the
browser.")

# libdform-dev: what a C++ project builds against. The static libraries carry their private
# dependencies into the consumer's link line, where dformConfig.cmake finds them again, so it
# depends on those -dev packages; the templates the libraries read come with dform.
set(CPACK_DEBIAN_DEV_PACKAGE_NAME libdform-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "dform (= ${PROJECT_VERSION}), libeigen3-dev, \
nlohmann-json3-dev, libboost-dev, libcgal-dev, libsuitesparse-dev, libssl-dev, libtinygltf-dev, \
libcairo2-dev, libpolyclipping-dev, libdxflib-dev, pkg-config")
set(CPACK_COMPONENT_DEV_DESCRIPTION "C++ libraries of dform, the D-Form toolchain
A D-Form is made by zipping two flat pieces of equal perimeter into a 3D
shape. These static libraries and their headers make one from outlines in
memory or from files, measure it, check it against a quality gate and write
its cutting patterns and report, as the dform command does. A CMake project
finds them with find_package(dform) and links dform::dform.")

if(TARGET dform_python)
  # python3-dform: the module, built for this python3 only (as dh_python3 says it).
  execute_process(COMMAND ${DFORM_PYTHON3} -c "import sys; major, minor = sys.version_info[:2]; \
print('%d.%d;%d.%d' % (major, minor, major, minor + 1), end='')"
                  OUTPUT_VARIABLE python_versions COMMAND_ERROR_IS_FATAL ANY)
  list(GET python_versions 0 python_version)
  list(GET python_versions 1 python_next)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-dform)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SHLIBDEPS ON)
  set(CPACK_DEBIAN_PYTHON_DEBUGINFO_PACKAGE ON)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "dform (= ${PROJECT_VERSION}), \
python3 (>= ${python_version}~), python3 (<< ${python_next}), python3-numpy")
  # py3compile on install, py3clean before removal (as dh_python3's maintainer scripts).
  foreach(script postinst prerm)
    configure_file(${DFORM_DEBIAN_DIR}/python3-dform.${script} ${packaging_dir}/python3-dform/${script}
                   COPYONLY)
    list(APPEND CPACK_DEBIAN_PYTHON_PACKAGE_CONTROL_EXTRA ${packaging_dir}/python3-dform/${script})
  endforeach()
  set(CPACK_COMPONENT_PYTHON_DESCRIPTION "Python module of dform, the D-Form toolchain
A D-Form is made by zipping two flat pieces of equal perimeter into a 3D
shape. import dform gives dform.forward (two outlines as numpy arrays to
the D-Form they make) and dform.inverse (a closed 3D seam curve to the two
pieces), results that print, compare and pickle, and the result folder
written as the dform command writes it.")
endif()

include(CPack)
