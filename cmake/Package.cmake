# SPDX-License-Identifier: Apache-2.0
# The Debian package (bash deploy/rig.sh package -> build/flatsat_<version>_amd64.deb):
# the executables under /usr/bin, data, scenarios and device descriptions under
# /usr/share/flatsat (found from the executable's place: bus/InstallPaths.hpp),
# man pages made from each --help, and bash completion. Its dependencies come
# from the shared libraries the executables link (dpkg-shlibdeps).
install(FILES ${PROJECT_SOURCE_DIR}/deploy/package/flatsat.bash-completion
        DESTINATION share/bash-completion/completions RENAME flatsat)
# Made by the `deb` target before packing; absent from a plain `cmake --install`
# when help2man was never run.
install(DIRECTORY ${CMAKE_BINARY_DIR}/man/ DESTINATION share/man/man1 OPTIONAL)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME flatsat)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "flight-network attitude and orbit control rig on Fast DDS")
set(CPACK_PACKAGE_DESCRIPTION
    "Every box of a spacecraft ADCS as its own process on Fast DDS, closed by a dynamics server: sensor emulators, estimator, controllers, thruster sequencer; lockstep or paced, hardware in the loop, recordings (MCAP export), Foxglove bridge.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "flatsat developers <flatsat@example.invalid>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The review figures (flatsat plot) and the discovery server of the Docker rigs.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox, fastdds-tools")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "bash-completion")
include(CPack)

add_custom_target(deb
  COMMAND bash ${PROJECT_SOURCE_DIR}/deploy/package/make-man.sh ${CMAKE_BINARY_DIR}/bin ${CMAKE_BINARY_DIR}/man
  COMMAND ${CMAKE_CPACK_COMMAND} -G DEB --config ${CMAKE_BINARY_DIR}/CPackConfig.cmake
  WORKING_DIRECTORY ${CMAKE_BINARY_DIR}
  COMMENT "Debian package (man pages from each --help, then cpack)")
get_property(flatsat_nodes GLOBAL PROPERTY FLATSAT_NODE_LIBRARIES)
add_dependencies(deb flatsat)
foreach(node ${flatsat_nodes})
  string(REGEX REPLACE "^flatsat_(.*)_node$" "flatsat-\\1" executable ${node})
  add_dependencies(deb ${executable})
endforeach()
