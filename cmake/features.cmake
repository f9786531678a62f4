# Optional features. Each is a cache string AUTO | ON | OFF:
#   AUTO  built when its package is found (the default);
#   ON    configure fails when the package is not found, saying what is missing;
#   OFF   the package is not looked for, so a node without it (a cluster node without Mesa or VTK)
#         builds the rest.
# What a feature's absence means at run time: a scene that needs it is refused with the option's
# name (common/build_features.h), and its tests are skipped naming the option (tests/features.cmake).
# The summary at the end of configure (sortlast_feature_summary) lists each one, on or off, and why.
#
# Results: SORTLAST_HAVE_<FEATURE> (TRUE/FALSE), the reason in SORTLAST_WHY_<FEATURE>, and the
# targets the feature's code links: sortlast::vtk (VTK's libraries), sortlast::hdf5, sortlast::netcdf,
# OpenEXR::OpenEXR, Boost::headers (Beast), PkgConfig::EGL, and OSMESA_INCLUDE_DIRS (OSMesa is
# opened at run time: its header alone).

set(SORTLAST_FEATURES VTK HDF5 NETCDF EXR SERVICE OSMESA EGL SUBDIV_REFERENCE BENCH PYTHON)
set(SORTLAST_FEATURE_DOC_VTK "VTK's .vti/.vtk volumes and .vtk/.vtp/.vtu particles")
set(SORTLAST_FEATURE_DOC_HDF5 "HDF5 volumes and particles (a parallel HDF5: collective MPI-IO reads)")
set(SORTLAST_FEATURE_DOC_NETCDF "NetCDF volumes (a netCDF with parallel I/O)")
set(SORTLAST_FEATURE_DOC_EXR "OpenEXR float frames and surface images (.exr)")
set(SORTLAST_FEATURE_DOC_SERVICE "`sortlast serve` and the in-situ live view (Boost.Beast)")
set(SORTLAST_FEATURE_DOC_OSMESA "the OSMesa GL backend (render.backend: osmesa)")
set(SORTLAST_FEATURE_DOC_EGL "the EGL GL backend (render.backend: egl)")
set(SORTLAST_FEATURE_DOC_SUBDIV_REFERENCE "the subdivision tests against OpenSubdiv (tests only)")
set(SORTLAST_FEATURE_DOC_BENCH "the benchmarks' programs (bench/)")
set(SORTLAST_FEATURE_DOC_PYTHON "the Python module (python/: pybind11, numpy, mpi4py)")

# The cache variable of a feature: SORTLAST_WITH_<F>, except the Python module's older name.
function(sortlast_feature_option feature out)
  if(feature STREQUAL PYTHON)
    set(${out} SORTLAST_PYTHON PARENT_SCOPE)
  else()
    set(${out} SORTLAST_WITH_${feature} PARENT_SCOPE)
  endif()
endfunction()

foreach(feature IN LISTS SORTLAST_FEATURES)
  sortlast_feature_option(${feature} var)
  set(${var} AUTO CACHE STRING "${SORTLAST_FEATURE_DOC_${feature}}: AUTO (when found), ON or OFF")
  set_property(CACHE ${var} PROPERTY STRINGS AUTO ON OFF)
  string(TOUPPER "${${var}}" value)
  # A build directory from before these options holds SORTLAST_PYTHON as a BOOL (ON/TRUE/1).
  if(value MATCHES "^(TRUE|YES|1)$")
    set(value ON)
  elseif(value MATCHES "^(FALSE|NO|0)$")
    set(value OFF)
  endif()
  if(NOT value MATCHES "^(AUTO|ON|OFF)$")
    message(FATAL_ERROR "${var}=${${var}}: expected AUTO, ON or OFF")
  endif()
  set(SORTLAST_WANT_${feature} ${value})
endforeach()

# sortlast_feature_result(FEATURE found reason): records whether FEATURE is on; ON without the
# package stops configure here, naming what was not found.
macro(sortlast_feature_result feature found reason)
  sortlast_feature_option(${feature} _sl_var)
  if(${found})
    set(SORTLAST_HAVE_${feature} TRUE)
  else()
    set(SORTLAST_HAVE_${feature} FALSE)
    if(SORTLAST_WANT_${feature} STREQUAL ON)
      message(FATAL_ERROR "${_sl_var}=ON, but ${reason} "
        "(install it, point CMAKE_PREFIX_PATH at it, or configure with -D${_sl_var}=OFF)")
    endif()
  endif()
  set(SORTLAST_WHY_${feature} "${reason}")
endmacro()

# sortlast_feature_skipped(FEATURE out): out is true when FEATURE is OFF (recorded as such, nothing looked for).
macro(sortlast_feature_skipped feature out)
  set(${out} FALSE)
  if(SORTLAST_WANT_${feature} STREQUAL OFF)
    sortlast_feature_option(${feature} _sl_var)
    sortlast_feature_result(${feature} FALSE "${_sl_var}=OFF")
    set(${out} TRUE)
  endif()
endmacro()

# --- VTK: only .vti/.vtk volumes and VTK particles need it (about 500 MB installed).
sortlast_feature_skipped(VTK skipped)
if(NOT skipped)
  find_package(VTK QUIET COMPONENTS CommonCore CommonDataModel IOLegacy IOXML)
  if(VTK_FOUND)
    sortlast_feature_result(VTK TRUE "VTK ${VTK_VERSION}")
    add_library(sortlast_vtk INTERFACE)
    target_link_libraries(sortlast_vtk INTERFACE ${VTK_LIBRARIES})
    add_library(sortlast::vtk ALIAS sortlast_vtk)
  else()
    sortlast_feature_result(VTK FALSE "VTK (CommonCore, CommonDataModel, IOLegacy, IOXML) not found")
  endif()
endif()

# --- HDF5: FindHDF5 (h5pcc/h5cc or HDF5's own CMake config, wherever CMAKE_PREFIX_PATH or
# HDF5_ROOT points: Spack's, a module's, Debian's libhdf5-openmpi). The session reads bricks
# collectively through MPI-IO (session/hdf5_loading.cpp), so only a parallel HDF5 will do; preferring
# it finds Debian's openmpi flavour where the serial one is installed beside it.
sortlast_feature_skipped(HDF5 skipped)
if(NOT skipped)
  set(HDF5_PREFER_PARALLEL TRUE)
  find_package(HDF5 QUIET COMPONENTS C)
  if(HDF5_FOUND AND HDF5_IS_PARALLEL)
    sortlast_feature_result(HDF5 TRUE "parallel HDF5 ${HDF5_VERSION} (${HDF5_C_INCLUDE_DIRS})")
    add_library(sortlast_hdf5 INTERFACE)
    # A parallel hdf5.h includes mpi.h: the files that include it (io/) see MPI's headers too.
    target_include_directories(sortlast_hdf5 SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS})
    target_compile_definitions(sortlast_hdf5 INTERFACE ${HDF5_C_DEFINITIONS})
    target_link_libraries(sortlast_hdf5 INTERFACE ${HDF5_C_LIBRARIES} MPI::MPI_C)
    add_library(sortlast::hdf5 ALIAS sortlast_hdf5)
  elseif(HDF5_FOUND)
    sortlast_feature_result(HDF5 FALSE
      "the HDF5 found (${HDF5_VERSION}, ${HDF5_C_INCLUDE_DIRS}) is serial; a parallel HDF5 is needed")
  else()
    sortlast_feature_result(HDF5 FALSE "HDF5 (C) not found")
  endif()
endif()

# --- NetCDF with parallel I/O, found in this order: netCDF's CMake config (netCDF_HAS_PARALLEL);
# Debian's MPI build by its pkg-config name (netcdf-mpi: Debian's serial and MPI netCDF both install
# a netCDFConfig.cmake, and the serial one is found first); a netcdf.pc whose nc-config says
# --has-parallel4 (an autotools install: Spack's, a module's).
sortlast_feature_skipped(NETCDF skipped)
if(NOT skipped)
  find_package(PkgConfig QUIET)
  set(netcdf_found FALSE)
  set(netcdf_why "no netCDF found")
  find_package(netCDF QUIET CONFIG)
  if(netCDF_FOUND AND netCDF_HAS_PARALLEL STREQUAL "yes")
    add_library(sortlast_netcdf INTERFACE)
    target_link_libraries(sortlast_netcdf INTERFACE netCDF::netcdf MPI::MPI_C)
    set(netcdf_found TRUE)
    set(netcdf_why "netCDF ${NetCDFVersion} with parallel I/O (CMake config, ${netCDF_DIR})")
  elseif(netCDF_FOUND)
    set(netcdf_why "the netCDF found (${netCDF_DIR}) has no parallel I/O")
  endif()
  if(NOT netcdf_found AND PKG_CONFIG_FOUND)
    pkg_check_modules(NETCDF_MPI QUIET IMPORTED_TARGET netcdf-mpi)
    if(NETCDF_MPI_FOUND)
      add_library(sortlast_netcdf INTERFACE)
      target_link_libraries(sortlast_netcdf INTERFACE PkgConfig::NETCDF_MPI MPI::MPI_C)
      set(netcdf_found TRUE)
      set(netcdf_why "netCDF ${NETCDF_MPI_VERSION} with parallel I/O (pkg-config netcdf-mpi)")
    else()
      pkg_check_modules(NETCDF_PC QUIET IMPORTED_TARGET netcdf)
      if(NETCDF_PC_FOUND)
        pkg_get_variable(netcdf_prefix netcdf prefix)
        find_program(SORTLAST_NC_CONFIG nc-config HINTS ${netcdf_prefix}/bin NO_DEFAULT_PATH)
        execute_process(COMMAND ${SORTLAST_NC_CONFIG} --has-parallel4 OUTPUT_VARIABLE parallel4
          OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
        if(parallel4 STREQUAL "yes")
          add_library(sortlast_netcdf INTERFACE)
          target_link_libraries(sortlast_netcdf INTERFACE PkgConfig::NETCDF_PC MPI::MPI_C)
          set(netcdf_found TRUE)
          set(netcdf_why "netCDF ${NETCDF_PC_VERSION} with parallel I/O (pkg-config netcdf, nc-config)")
        else()
          set(netcdf_why "the netCDF in ${netcdf_prefix} has no parallel I/O (nc-config --has-parallel4)")
        endif()
      endif()
    endif()
  endif()
  if(netcdf_found)
    add_library(sortlast::netcdf ALIAS sortlast_netcdf)
  endif()
  sortlast_feature_result(NETCDF ${netcdf_found} "${netcdf_why}")
endif()

# --- OpenEXR 3: float frames and the surface images the tests compare.
sortlast_feature_skipped(EXR skipped)
if(NOT skipped)
  find_package(OpenEXR 3 QUIET CONFIG)
  if(OpenEXR_FOUND)
    sortlast_feature_result(EXR TRUE "OpenEXR ${OpenEXR_VERSION}")
  else()
    sortlast_feature_result(EXR FALSE "OpenEXR 3 not found")
  endif()
endif()

# --- The service: Boost.Beast and Asio (header-only). Boost's headers are needed anyway (the glow
# reference's Boost.Math quadrature, reference/glow_quadrature.cpp); Beast is checked for itself.
sortlast_feature_skipped(SERVICE skipped)
if(NOT skipped)
  find_path(SORTLAST_BEAST_INCLUDE_DIR boost/beast.hpp HINTS ${Boost_INCLUDE_DIRS})
  if(Boost_FOUND AND SORTLAST_BEAST_INCLUDE_DIR)
    sortlast_feature_result(SERVICE TRUE "Boost.Beast ${Boost_VERSION_STRING}")
  else()
    sortlast_feature_result(SERVICE FALSE "Boost.Beast (boost/beast.hpp) not found")
  endif()
endif()

# --- The GL backends: OSMesa is opened with dlopen at run time (its header alone is used), EGL is
# linked. At least one must be on.
sortlast_feature_skipped(OSMESA skipped)
if(NOT skipped)
  find_package(PkgConfig QUIET)
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(OSMESA QUIET osmesa)
  endif()
  if(OSMESA_FOUND)
    sortlast_feature_result(OSMESA TRUE "OSMesa ${OSMESA_VERSION} (opened at run time)")
  else()
    sortlast_feature_result(OSMESA FALSE "osmesa (pkg-config) not found")
  endif()
endif()
sortlast_feature_skipped(EGL skipped)
if(NOT skipped)
  find_package(PkgConfig QUIET)
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(EGL QUIET IMPORTED_TARGET egl)
  endif()
  if(EGL_FOUND)
    sortlast_feature_result(EGL TRUE "EGL ${EGL_VERSION}")
  else()
    sortlast_feature_result(EGL FALSE "egl (pkg-config) not found")
  endif()
endif()
if(NOT SORTLAST_HAVE_OSMESA AND NOT SORTLAST_HAVE_EGL)
  message(FATAL_ERROR "No GL backend: OSMesa (${SORTLAST_WHY_OSMESA}) and EGL (${SORTLAST_WHY_EGL}). "
    "sortlast renders through one of them: install Mesa's libosmesa6-dev or libegl-dev.")
endif()

# --- OpenSubdiv, the subdivision tests' reference (and the subdivision benchmark's). Debian 12's
# OpenSubdivConfig.cmake names static libraries the package does not ship, so the shared library
# and headers are found directly.
sortlast_feature_skipped(SUBDIV_REFERENCE skipped)
if(NOT skipped)
  find_library(OSD_CPU_LIBRARY osdCPU)
  find_path(OSD_INCLUDE_DIR opensubdiv/far/patchTable.h)
  if(OSD_CPU_LIBRARY AND OSD_INCLUDE_DIR)
    sortlast_feature_result(SUBDIV_REFERENCE TRUE "OpenSubdiv (${OSD_CPU_LIBRARY})")
  else()
    sortlast_feature_result(SUBDIV_REFERENCE FALSE "OpenSubdiv (osdCPU, opensubdiv/far) not found")
  endif()
endif()

# --- The benchmarks need nothing beyond the build, except the subdivision one (OpenSubdiv), which
# is left out without it.
sortlast_feature_skipped(BENCH skipped)
if(NOT skipped)
  sortlast_feature_result(BENCH TRUE "bench/ (subdivision benchmark: ${SORTLAST_WHY_SUBDIV_REFERENCE})")
endif()

# --- The Python module: Python's headers, pybind11, numpy and mpi4py. It is built for Debian's
# interpreter, which has numpy and mpi4py (python3-numpy, python3-mpi4py): /usr/bin/python3 unless
# -DPython3_EXECUTABLE names another, since a python3 earlier on PATH (a pyenv one) may have neither.
sortlast_feature_skipped(PYTHON skipped)
if(NOT skipped)
  if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The interpreter the Python module is built for")
  endif()
  find_package(Python3 QUIET COMPONENTS Interpreter Development.Module)
  find_package(pybind11 CONFIG QUIET)
  set(mpi4py_include "")
  if(Python3_FOUND)
    execute_process(COMMAND ${Python3_EXECUTABLE} -c "import numpy, mpi4py; print(mpi4py.get_include())"
      OUTPUT_VARIABLE mpi4py_include OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE missing ERROR_QUIET)
    if(missing)
      set(mpi4py_include "")
    endif()
  endif()
  if(NOT Python3_FOUND)
    sortlast_feature_result(PYTHON FALSE "Python 3 with its headers not found (python3-dev)")
  elseif(NOT pybind11_FOUND)
    sortlast_feature_result(PYTHON FALSE "pybind11 not found (pybind11-dev)")
  elseif(NOT mpi4py_include)
    sortlast_feature_result(PYTHON FALSE
      "${Python3_EXECUTABLE} cannot import numpy and mpi4py (python3-numpy, python3-mpi4py, or -DPython3_EXECUTABLE=/usr/bin/python3)")
  else()
    set(SORTLAST_MPI4PY_INCLUDE ${mpi4py_include})
    sortlast_feature_result(PYTHON TRUE "Python ${Python3_VERSION}, pybind11 ${pybind11_VERSION}")
  endif()
endif()

# The summary, printed once configure has decided everything.
function(sortlast_feature_summary)
  message(STATUS "sortlast optional features (AUTO | ON | OFF; docs/install.md):")
  foreach(feature IN LISTS SORTLAST_FEATURES)
    sortlast_feature_option(${feature} var)
    if(SORTLAST_HAVE_${feature})
      set(state "on ")
    else()
      set(state "off")
    endif()
    string(LENGTH "${var}" n)
    math(EXPR pad "31 - ${n}")
    string(REPEAT " " ${pad} spaces)
    message(STATUS "  ${var}${spaces}${state}  ${SORTLAST_WHY_${feature}}")
  endforeach()
endfunction()
