# Installing on a board (docs/board-and-kms.md, "Installing on a board"), included by the top-level CMakeLists.txt.
# `cmake --install BUILD` puts the player, its systemd unit and the board files where the unit
# expects them; `cpack -G DEB` (tools/package) makes the same files a Debian package. Every rule is
# in the `player` component and the package takes only that one, so an install rule added later for
# a development tool does not end up on a board.
include(GNUInstallDirs)
# `install` and cpack install what is built and build nothing first: otherwise packaging would
# build the whole test suite and the tools (hours on a board), and the package test would rebuild
# the tree it runs in. tools/package builds the player, then runs cpack.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
set(board_source ${PROJECT_SOURCE_DIR}/board)
set(board_staging ${PROJECT_BINARY_DIR}/board-install)

# The unit names the binary and the demo playlist by their installed paths, written at install time
# from the prefix in effect then: cpack installs into /usr whatever prefix the build tree has, and
# `cmake --install --prefix P` gets a unit that runs P/bin/player.
foreach(unit_name ssao-player.service ssao-player-fleet.service ssao-player-content.service ssao-player-content.path)
  install(CODE "
    file(READ [[${board_source}/${unit_name}]] unit)
    string(REPLACE /usr/bin/player \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}/player\" unit \"\${unit}\")
    string(REPLACE /usr/share/ssao-player \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/ssao-player\" unit \"\${unit}\")
    string(REPLACE /usr/share/doc/ssao-player \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/doc/ssao-player\" unit \"\${unit}\")
    file(WRITE [[${board_staging}/${unit_name}]] \"\${unit}\")
  " COMPONENT player)
endforeach()
# systemd, sysusers and udev search <prefix>/lib/... for both /usr and /usr/local (not the multiarch libdir).
install(FILES ${board_staging}/ssao-player.service ${board_staging}/ssao-player-fleet.service ${board_staging}/ssao-player-content.service
              ${board_staging}/ssao-player-content.path DESTINATION lib/systemd/system COMPONENT player)
install(FILES ${board_source}/ssao-player.sysusers DESTINATION lib/sysusers.d RENAME ssao-player.conf COMPONENT player)
install(FILES ${board_source}/60-ssao-player-gpio.rules DESTINATION lib/udev/rules.d COMPONENT player)

# Configuration: /etc whatever the prefix, because the unit reads it there. The package marks these
# conffiles, so an upgrade keeps the board owner's changes. The Pi 4 file serves the Pi 5 too (the
# same line names; a camera that is not there is a warning, not a failure).
install(FILES ${board_source}/ssao-player.default DESTINATION /etc/default RENAME ssao-player COMPONENT player)
install(FILES ${board_source}/raspberry-pi-4.toml DESTINATION /etc/ssao-player RENAME board.toml COMPONENT player)
set(board_conffiles /etc/default/ssao-player /etc/ssao-player/board.toml)

# Board files to start from, the demo playlist a fresh install plays, and the documentation.
install(FILES ${board_source}/raspberry-pi-4.toml ${board_source}/raspberry-pi-5.toml ${board_source}/mock.toml
              ${board_source}/buttons.script
        DESTINATION ${CMAKE_INSTALL_DATADIR}/ssao-player/board COMPONENT player)
# The fleet agent's example configuration; the unit starts only once /etc/ssao-player/fleet.toml exists.
install(FILES ${board_source}/fleet.toml DESTINATION ${CMAKE_INSTALL_DATADIR}/ssao-player COMPONENT player)
install(DIRECTORY ${board_source}/displays DESTINATION ${CMAKE_INSTALL_DATADIR}/ssao-player/board COMPONENT player)
install(FILES ${board_source}/demo/playlist.toml DESTINATION ${CMAKE_INSTALL_DATADIR}/ssao-player/demo COMPONENT player)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/ssao-player COMPONENT player)
install(FILES ${board_source}/README.md DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/ssao-player RENAME board.md COMPONENT player)
# docs/ beside README.md, so the README's links resolve on the board too.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/ssao-player COMPONENT player
        FILES_MATCHING PATTERN "*.md")
# Where the board owner's content goes (/etc/default/ssao-player says how to play it): root's,
# read by the service, which may not write it.
install(DIRECTORY DESTINATION /var/lib/ssao-player COMPONENT player)

# The Debian package: tools/package builds the release preset and runs cpack into out/.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME ssao-player)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "ssao-player maintainers <ssao-player@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "kiosk glTF player with screen-space ambient occlusion for single-board computers")
set(CPACK_PACKAGE_DESCRIPTION "Plays glTF 2.0 scenes full screen on tty1 (OpenGL ES 3.1, KMS), with buttons,
status LEDs, a status file and a camera self-check, as the systemd service ssao-player.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL player)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# Library dependencies come from dpkg-shlibdeps on the installed binary (dpkg-dev); systemd for
# systemd-sysusers in postinst; tzdata for a board's opening hours in a named time zone (read at run
# time, which shlibdeps cannot see); Mesa's EGL and drivers are what the GPU is reached through.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "systemd, tzdata")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS libosmesa6)
string(JOIN "\n" conffiles_text ${board_conffiles})
file(WRITE ${board_staging}/conffiles "${conffiles_text}\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${board_source}/debian/postinst ${board_source}/debian/prerm ${board_source}/debian/postrm ${board_staging}/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
