# `cmake --install build --prefix DIR` and `cpack -G DEB` (in the build directory).
#
# Layout, relative to the prefix:
#   lib/cbrbench/cbrbench          the program
#   lib/cbrbench/libcbr_oiio.so    its OpenImageIO module, loaded from beside the program's real
#                                  path (metrics/image_io.cpp; /proc/self/exe resolves links)
#   bin/cbrbench                   a relative link to ../lib/cbrbench/cbrbench
#   share/doc/cbrbench/            README.md and the reference pages
# Nothing else is read at run time: the shaders are SPIR-V compiled into the program, the
# report's HTML, CSS and scripts are strings in it, and the display models are a table.
# Optional, from the system: the Khronos validation layer (--validate), Debian's
# assimp-testmodels (stress's glTF cases, or CBR_ASSIMP_MODELS).
include(GNUInstallDirs)
# Installing builds nothing: `cmake --install` never does, and `cpack` would otherwise build
# every target first, the test suite included (8.5 minutes on 2 cores). Build, then install.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

set(CBR_PRIVATE_DIR ${CMAKE_INSTALL_LIBDIR}/cbrbench)
install(TARGETS cbrbench RUNTIME DESTINATION ${CBR_PRIVATE_DIR})
if(CBR_WITH_OIIO)
  install(TARGETS cbr_oiio LIBRARY DESTINATION ${CBR_PRIVATE_DIR})
endif()

# The link is made here and installed as a link (file(INSTALL) keeps links), so that it is
# in install_manifest.txt and in the package like any file.
file(RELATIVE_PATH cbr_link_target ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR}/cbrbench/cbrbench)
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/install-links)
file(CREATE_LINK ${cbr_link_target} ${CMAKE_BINARY_DIR}/install-links/cbrbench SYMBOLIC)
install(FILES ${CMAKE_BINARY_DIR}/install-links/cbrbench DESTINATION ${CMAKE_INSTALL_BINDIR})

install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES docs/reference/command-line.md docs/reference/exit-codes.md docs/reference/outputs.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/reference)

# The Debian package: `cpack -G DEB` in the build directory writes cbrbench_VERSION_ARCH.deb.
set(CBR_PACKAGE_CONTACT "cbrbench maintainers <cbrbench@localhost>" CACHE STRING
    "Maintainer of the Debian package (Name <email>)")
set(CPACK_PACKAGE_NAME cbrbench)
set(CPACK_PACKAGE_VENDOR "cbrbench")
set(CPACK_PACKAGE_CONTACT ${CBR_PACKAGE_CONTACT})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "checkerboard rendering benchmark and quality analysis on Vulkan")
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "cbrbench flies a scripted camera through a scene on Vulkan (headless), renders\n"
       "every frame with native, dynamic-resolution, checkerboard and temporal-upsampling\n"
       "variants, times every pass with GPU timestamps, scores every frame against the\n"
       "native reference (PSNR, SSIM, FLIP, edge crawl, ColorVideoVDP) and writes CSV,\n"
       "JSON and a self-contained HTML report. It also judges runs for regressions\n"
       "(compare, ab) and scores frames captured from other engines (score, score-seq).")
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# Depends: libvulkan1, OpenImageIO, OpenCV, ... read from the ELF files by dpkg-shlibdeps.
find_program(CBR_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(CBR_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
else()
  message(STATUS "dpkg-shlibdeps not found (dpkg-dev): a Debian package would have no Depends")
endif()
# lavapipe is the default device; without any Vulkan driver the program lists no device.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "mesa-vulkan-drivers | vulkan-icd")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "vulkan-validationlayers, assimp-testmodels")
include(CPack)
