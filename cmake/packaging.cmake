# Packaging of the in-situ library (target sortlast_insitu, in the top-level CMakeLists.txt):
#   <prefix>/lib/libsortlast.so*                    the library (only its API symbols exported)
#   <prefix>/include/sortlast/insitu.h, insitu_c.h  its C++ and C API
#   <prefix>/lib/cmake/sortlast/                    find_package(sortlast CONFIG): sortlast::insitu
#   <prefix>/lib/pkgconfig/sortlast.pc              pkg-config sortlast
# (tests/install/ builds programs against an installed copy: test install_package.)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

target_include_directories(sortlast_insitu PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
# Only the API leaves the library: the version script keeps sortlast::InSitu, InSituError and the
# sortlast_insitu_* functions global and everything else (sortlast's internals, and the template
# code of the libraries it is built from) local, so nothing clashes with the simulation's own.
set(SORTLAST_INSITU_VERSION_SCRIPT ${PROJECT_SOURCE_DIR}/cmake/sortlast_insitu.map)
target_link_options(sortlast_insitu PRIVATE
  -Wl,--version-script=${SORTLAST_INSITU_VERSION_SCRIPT} -Wl,--no-undefined)
set_target_properties(sortlast_insitu PROPERTIES
  OUTPUT_NAME sortlast
  VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR}
  LINK_DEPENDS ${SORTLAST_INSITU_VERSION_SCRIPT}
  EXPORT_NAME insitu)

install(TARGETS sortlast_insitu EXPORT sortlastTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(FILES include/sortlast/insitu.h include/sortlast/insitu_c.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sortlast)

# find_package(sortlast CONFIG): sortlast::insitu. The config file finds MPI itself (for the
# languages the consumer enabled), so the installed target names no build-machine MPI paths.
set(SORTLAST_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/sortlast)
install(EXPORT sortlastTargets NAMESPACE sortlast:: DESTINATION ${SORTLAST_CMAKE_DIR})
configure_package_config_file(cmake/sortlastConfig.cmake.in
  ${PROJECT_BINARY_DIR}/sortlastConfig.cmake INSTALL_DESTINATION ${SORTLAST_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/sortlastConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/sortlastConfig.cmake ${PROJECT_BINARY_DIR}/sortlastConfigVersion.cmake
  DESTINATION ${SORTLAST_CMAKE_DIR})

# pkg-config sortlast. Paths are relative to the .pc file, so `cmake --install --prefix` anywhere
# works. It requires the MPI implementation's own module (Open MPI: ompi-c, MPICH: mpich).
if(NOT SORTLAST_PC_REQUIRES)
  foreach(module IN ITEMS ompi-c mpich mpi-c)
    execute_process(COMMAND ${PKG_CONFIG_EXECUTABLE} --exists ${module} RESULT_VARIABLE missing)
    if(NOT missing)
      set(SORTLAST_PC_REQUIRES ${module})
      break()
    endif()
  endforeach()
endif()
set(SORTLAST_PC_REQUIRES "${SORTLAST_PC_REQUIRES}" CACHE STRING
  "pkg-config module(s) of MPI that sortlast.pc requires")
# The prefix seen from <prefix>/<libdir>/pkgconfig (any absolute stand-in for the prefix will do).
file(RELATIVE_PATH SORTLAST_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" SORTLAST_PC_TO_PREFIX "${SORTLAST_PC_TO_PREFIX}")
foreach(dir IN ITEMS LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE ${CMAKE_INSTALL_${dir}})
    set(SORTLAST_PC_${dir} ${CMAKE_INSTALL_${dir}})
  else()
    set(SORTLAST_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
configure_file(cmake/sortlast.pc.in ${PROJECT_BINARY_DIR}/sortlast.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/sortlast.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

