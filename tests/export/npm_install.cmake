# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the Khronos glTF validator into PREFIX with NPM; never fails the build (offline builds
# skip the validation test instead).
file(MAKE_DIRECTORY ${PREFIX})
execute_process(
  COMMAND ${NPM} install --no-audit --no-fund --loglevel=error --prefix ${PREFIX}
          gltf-validator@2.0.0-dev.3.10
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET TIMEOUT 300)
if(NOT rc EQUAL 0)
  message(WARNING "npm could not install gltf-validator; the glTF validation test will be skipped")
endif()
file(TOUCH ${PREFIX}/install.stamp)
