# Spack recipe for sortlast (docs/install.md), in a package repository of the layout Spack 0.23 reads
# (repo.yaml beside packages/; `from spack.package import *` brings CMakePackage). Add it:
#   spack repo add packaging/spack
# sortlast publishes no release tarball, so build a checkout in place:
#   spack env create -d . && spack env activate .   (spack develop works in an environment)
#   spack develop --path "$PWD" sortlast@=main && spack add sortlast@=main ~vtk && spack install
#
# Each variant is one CMake option (SORTLAST_OPTIONS below; tests/layout/check_recipes.py holds the
# two to each other). Spack passes each as ON or OFF, never AUTO: a Spack build must not pick up
# whatever the system happens to have.
#
# The versions are the lowest we build and test: Debian 12's (scripts/install-deps), since CI runs
# there. Newer ones are expected to work; older ones have never been tried.

from spack.package import *

# variant -> the CMake option it sets
SORTLAST_OPTIONS = {
    "vtk": "SORTLAST_WITH_VTK",
    "hdf5": "SORTLAST_WITH_HDF5",
    "netcdf": "SORTLAST_WITH_NETCDF",
    "exr": "SORTLAST_WITH_EXR",
    "service": "SORTLAST_WITH_SERVICE",
    "osmesa": "SORTLAST_WITH_OSMESA",
    "egl": "SORTLAST_WITH_EGL",
    "subdiv_reference": "SORTLAST_WITH_SUBDIV_REFERENCE",
    "bench": "SORTLAST_WITH_BENCH",
    "python": "SORTLAST_PYTHON",
}


class Sortlast(CMakePackage):
    """Distributed sort-last rendering of volumes, particles and subdivision surfaces with MPI and
    OpenGL: a batch renderer, a render service with a web viewer, an in-situ library and a Python
    module."""

    # No homepage or release URL yet: `spack develop` builds a checkout (above).

    version("main")

    variant("vtk", default=False, description="Volumes from VTK files (.vti, .vtk); VTK is large")
    variant("hdf5", default=True, description="Volumes from HDF5 files, read collectively (parallel HDF5)")
    variant("netcdf", default=True, description="Volumes from NetCDF files (netCDF-C with parallel I/O)")
    variant("exr", default=True, description="EXR frames and surface images (OpenEXR)")
    variant("service", default=True, description="sortlast serve: HTTP/WebSocket service (Boost.Beast)")
    variant("osmesa", default=True, description="Offscreen rendering on the CPU (Mesa's OSMesa, llvmpipe)")
    variant("egl", default=False, description="Headless rendering on a GPU through EGL (the driver's libEGL)")
    variant("subdiv_reference", default=False, description="The subdivision tests' reference (OpenSubdiv)")
    variant("bench", default=False, description="Build the benchmarks (bench/)")
    variant("python", default=False, description="The Python module (pybind11, numpy, mpi4py)")

    # One GL path at least: the renderer needs a context to draw into.
    conflicts("~osmesa ~egl", msg="sortlast needs a GL context: enable +osmesa or +egl")

    depends_on("c", type="build")
    depends_on("cxx", type="build")
    depends_on("cmake@3.25:", type="build")  # Debian 12: 3.25.1 (CMakeLists.txt needs 3.20)
    depends_on("pkgconfig", type="build")

    # Always needed (Debian 12's versions).
    depends_on("mpi")  # Open MPI 4.1.4 tested
    depends_on("gl")
    depends_on("glm@0.9.9.8:")
    depends_on("eigen@3.4.0:")
    depends_on("zlib-api")
    depends_on("libpng@1.6.39:")
    depends_on("jpeg")  # libjpeg-turbo 2.1.5 tested
    depends_on("libdeflate@1.14:")
    depends_on("freetype@2.12.1:")
    depends_on("ffmpeg@5.1:")
    depends_on("tinyobjloader@2.0.0-rc10:")
    depends_on("yaml-cpp@0.7.0:")
    depends_on("cli11@2.1.2:")
    depends_on("nlohmann-json@3.11.2:")
    depends_on("boost@1.74:")  # headers only: Boost.Math (glow quadrature), Beast/Asio (+service)

    # The optional features.
    depends_on("vtk@9.1.0:", when="+vtk")
    depends_on("hdf5@1.10.8:+mpi", when="+hdf5")
    depends_on("netcdf-c@4.9.0:+mpi", when="+netcdf")
    depends_on("openexr@3.1.5:", when="+exr")
    depends_on("mesa@22.3:+osmesa", when="+osmesa")  # 22.3.6 tested
    depends_on("egl", when="+egl")
    depends_on("opensubdiv@3.5.0:", when="+subdiv_reference")
    depends_on("opensubdiv@3.5.0:", when="+bench")  # the subdivision benchmark compares with it
    with when("+python"):
        depends_on("python@3.11:")
        depends_on("py-pybind11@2.10.3:", type="build")
        depends_on("py-numpy@1.24.2:", type=("build", "run"))
        depends_on("py-mpi4py@3.1.4:", type=("build", "run"))
        extends("python")

    depends_on("googletest@1.12.1:", type="test")

    def cmake_args(self):
        args = [
            self.define(option, "ON" if self.spec.satisfies("+" + variant) else "OFF")
            for variant, option in SORTLAST_OPTIONS.items()
        ]
        args.append(self.define("BUILD_TESTING", self.run_tests))
        # Each target's sources compiled eight to a file: half the build's time from scratch,
        # the same program (README).
        args.append(self.define("CMAKE_UNITY_BUILD", True))
        if self.spec.satisfies("+python"):
            args.append(self.define("Python3_EXECUTABLE", self.spec["python"].command.path))
        return args
