# Tests of optional features (cmake/features.cmake). sortlast_add_test(NAME name COMMAND ...) is
# add_test, except that a test needing a feature this build has not gets a stand-in of the same
# name that prints which option builds it and exits 77, which ctest reports as skipped
# (SKIP_RETURN_CODE): so `ctest -R NAME` still says why, and the labels and properties set on the
# name later apply. What a test needs is read from its name and its script, below.

# Scripts whose every mode needs a feature (tests/<folder>/<script>).
set(SORTLAST_SCRIPT_NEEDS
  # surface images (--surface-out) and float frames are OpenEXR files
  "mpi/anisotropic.sh:EXR" "mpi/compositing_options.sh:EXR" "mpi/glow.sh:EXR" "mpi/isosurface.sh:EXR"
  "mpi/outputs.sh:EXR" "mpi/particles.sh:EXR" "mpi/particles_slices.sh:EXR" "mpi/projection.sh:EXR"
  "mpi/surfaces.sh:EXR" "python/run.sh:EXR"
  # .vti and legacy .vtk volumes, VTK particles
  "mpi/volume_formats.sh:VTK" "mpi/vtk_input.sh:VTK"
  # float frames of every renderer, an EGL frame, a service frame
  "golden/check.sh:EXR" "golden/check.sh:EGL" "golden/check.sh:SERVICE"
  "soak/service_soak.sh:SERVICE" "cluster/correctness.sh:SERVICE" "cluster/faults.sh:SERVICE")
# Tests (regular expressions on the name) needing a feature beyond their script's.
set(SORTLAST_NAME_NEEDS
  "^service_:SERVICE" "^surfaces_serve$:SERVICE" "^insitu_live$:SERVICE"
  "^volume_formats_hdf5$:HDF5" "^volume_formats_particles$:HDF5" "^volume_formats_netcdf$:NETCDF"
  "egl:EGL" "osmesa:OSMESA" "^particles_grid_:OSMESA"
  # the GL unit tests open an OSMesa context
  "^(subdiv_gl|glow_glsl|gl_program|isosurface_gl)$:OSMESA" "^subdiv$:SUBDIV_REFERENCE")

# sortlast_missing_features(OUT NAME COMMAND...): the features test NAME needs that this build lacks.
function(sortlast_missing_features out name)
  set(missing)
  # (A MATCHES resets CMAKE_MATCH_<n>: each rule's two parts are copied out first.)
  foreach(rule IN LISTS SORTLAST_NAME_NEEDS)
    string(REGEX MATCH "^(.*):([A-Z0-9_]+)$" _ "${rule}")
    set(pattern "${CMAKE_MATCH_1}")
    set(feature ${CMAKE_MATCH_2})
    if(NOT SORTLAST_HAVE_${feature} AND name MATCHES "${pattern}")
      list(APPEND missing ${feature})
    endif()
  endforeach()
  foreach(arg IN LISTS ARGN)
    foreach(rule IN LISTS SORTLAST_SCRIPT_NEEDS)
      string(REGEX MATCH "^(.*):([A-Z0-9_]+)$" _ "${rule}")
      set(script "${CMAKE_MATCH_1}")
      set(feature ${CMAKE_MATCH_2})
      if(NOT SORTLAST_HAVE_${feature} AND arg MATCHES "/tests/${script}$")
        list(APPEND missing ${feature})
      endif()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES missing)
  set(${out} ${missing} PARENT_SCOPE)
endfunction()

function(sortlast_add_test NAME name COMMAND)
  sortlast_missing_features(missing ${name} ${ARGN})
  if(NOT missing)
    add_test(NAME ${name} COMMAND ${ARGN})
    return()
  endif()
  set(why)
  foreach(feature IN LISTS missing)
    sortlast_feature_option(${feature} var)
    list(APPEND why "-D${var}=ON")
  endforeach()
  list(JOIN why " " why)
  add_test(NAME ${name} COMMAND sh -c "echo '${name}: skipped: this build lacks what it needs (configure with ${why})'; exit 77")
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77)
endfunction()
