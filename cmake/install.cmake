# `cmake --install build` installs the libraries, their headers and a CMake package, so
# that another project can write
#   find_package(kintsugi REQUIRED)
#   target_link_libraries(app PRIVATE kintsugi::kintsugi)
# (examples/consumer/ is such a project; tests/package/ builds it against an install).
# kintsugi::kintsugi links every component; each is also there alone
# (kintsugi::kernel, kintsugi::repair, kintsugi::api, ...).
include(CMakePackageConfigHelpers)

set(KINTSUGI_COMPONENTS kintsugi_geometry kintsugi_kernel kintsugi_invariants kintsugi_problems kintsugi_zoo
                        kintsugi_io kintsugi_view kintsugi_repair kintsugi_audit kintsugi_cli)
if(TARGET kintsugi_occt)
  list(APPEND KINTSUGI_COMPONENTS kintsugi_occt)
endif()
foreach(lib ${KINTSUGI_COMPONENTS})
  string(REPLACE "kintsugi_" "" short ${lib})
  if(short STREQUAL "cli")
    set(short api)  # apps/api.h is the stable entry point of that library
  endif()
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${short})
endforeach()

# The umbrella target; its name is taken by the program, so the library is kintsugi_all
# exported as kintsugi::kintsugi (and aliased so in-tree code can use the same name).
add_library(kintsugi_all INTERFACE)
target_link_libraries(kintsugi_all INTERFACE ${KINTSUGI_COMPONENTS})
set_target_properties(kintsugi_all PROPERTIES EXPORT_NAME kintsugi)
add_library(kintsugi::kintsugi ALIAS kintsugi_all)

install(TARGETS ${KINTSUGI_COMPONENTS} kintsugi_all EXPORT kintsugiTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/kintsugi)
install(TARGETS kintsugi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir geometry kernel invariants problems zoo io view repair audit apps)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/kintsugi
          FILES_MATCHING PATTERN "*.h")
endforeach()

set(KINTSUGI_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/kintsugi)
install(EXPORT kintsugiTargets NAMESPACE kintsugi:: DESTINATION ${KINTSUGI_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/kintsugiConfig.cmake.in
  ${PROJECT_BINARY_DIR}/kintsugiConfig.cmake INSTALL_DESTINATION ${KINTSUGI_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/kintsugiConfigVersion.cmake
  VERSION 0.1.0 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/kintsugiConfig.cmake ${PROJECT_BINARY_DIR}/kintsugiConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/kintsugi_occt_fixup.cmake
        DESTINATION ${KINTSUGI_CMAKE_DIR})
