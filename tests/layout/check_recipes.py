#!/usr/bin/env python3
"""The build recipes that cannot be run here (neither Spack nor Apptainer is packaged in Debian 12),
checked for what can be checked without them, and scripts/install-deps on a machine with ParaView.

Usage: check_recipes.py REPO_ROOT

1. packaging/spack/packages/sortlast/package.py parses, and runs against a stand-in for Spack's
   `spack.package` module that records the directives: its variants are one-to-one with the CMake
   options (cmake/features.cmake's SORTLAST_FEATURES), and cmake_args() passes each option, ON or OFF as its variant.
2. packaging/apptainer/sortlast.def bootstraps Debian 12 and its %post runs scripts/install-deps
   and the build.
3. scripts/install-deps, with apt-get and dpkg-query replaced by stand-ins, on a machine where apt
   cannot add libvtk9-dev (Debian's paraview installed): it goes on, says that it skips it, and
   installs the rest; where apt can, it installs libvtk9-dev with the rest.
Exits 1 naming every failure.
"""
import ast
import os
import re
import subprocess
import sys
import tempfile
import types

# The CMake options of the optional features, read from cmake/features.cmake (its
# SORTLAST_FEATURES list: SORTLAST_WITH_<F>, the Python module's SORTLAST_PYTHON).
def cmake_options(root):
    text = open(os.path.join(root, "cmake/features.cmake")).read()
    m = re.search(r"set\(SORTLAST_FEATURES ([A-Z0-9_ ]+)\)", text)
    if not m:
        print("FAIL: cmake/features.cmake: no set(SORTLAST_FEATURES ...) list")
        sys.exit(1)
    return ["SORTLAST_PYTHON" if f == "PYTHON" else "SORTLAST_WITH_" + f for f in m.group(1).split()]


failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message)


def stub_spack():
    """A `spack.package` module whose directives record what the recipe declares."""
    record = {"variants": {}, "depends_on": [], "conflicts": []}
    mod = types.ModuleType("spack.package")

    class CMakePackage:
        run_tests = False

        def define(self, name, value):
            if isinstance(value, bool):
                return "-D{0}:BOOL={1}".format(name, "ON" if value else "OFF")
            return "-D{0}:STRING={1}".format(name, value)

    def variant(name, default=None, description="", **kw):
        if name in record["variants"]:
            fail("package.py: variant {0} declared twice".format(name))
        record["variants"][name] = default

    whens = []  # the conditions of the `with when(...)` blocks around a directive

    class When:
        def __init__(self, condition):
            self.condition = condition

        def __enter__(self):
            whens.append(self.condition)
            return self

        def __exit__(self, *a):
            whens.pop()
            return False

    ignored = lambda *a, **kw: None
    mod.CMakePackage = CMakePackage
    mod.variant = variant
    mod.depends_on = lambda spec, **kw: record["depends_on"].append(
        (spec, " ".join(whens + [kw.get("when") or ""]).strip() or None))
    mod.conflicts = lambda *a, **kw: record["conflicts"].append(a)
    mod.when = When
    for name in ("version", "extends", "maintainers", "license", "patch", "provides", "resource"):
        setattr(mod, name, ignored)
    mod.__all__ = [n for n in vars(mod) if not n.startswith("_")]
    spack = types.ModuleType("spack")
    spack.package = mod
    sys.modules["spack"] = spack
    sys.modules["spack.package"] = mod
    return record


class FakeSpec:
    """Enough of a concrete spec for cmake_args(): which variants are on."""

    def __init__(self, on):
        self.on = on

    def satisfies(self, constraint):
        m = re.fullmatch(r"([+~])(\w+)", constraint)
        if not m:
            raise ValueError("the stand-in spec understands +variant and ~variant only: " + constraint)
        return (m.group(2) in self.on) == (m.group(1) == "+")

    def __getitem__(self, name):
        return types.SimpleNamespace(command=types.SimpleNamespace(path="/usr/bin/" + name))


def check_spack(root):
    CMAKE_OPTIONS = cmake_options(root)
    path = os.path.join(root, "packaging/spack/packages/sortlast/package.py")
    source = open(path).read()
    try:
        ast.parse(source, path)
    except SyntaxError as e:
        fail("package.py does not parse: {0}".format(e))
        return
    if not os.path.isfile(os.path.join(root, "packaging/spack/repo.yaml")):
        fail("packaging/spack/repo.yaml is missing: Spack needs it to add the repository")
    record = stub_spack()
    scope = {}
    exec(compile(source, path, "exec"), scope)
    variants = record["variants"]
    mapping = scope.get("SORTLAST_OPTIONS", {})
    if set(variants) != set(mapping):
        fail("package.py: variants {0} but SORTLAST_OPTIONS maps {1}".format(sorted(variants), sorted(mapping)))
    if sorted(mapping.values()) != sorted(CMAKE_OPTIONS) or len(set(mapping.values())) != len(mapping):
        fail("package.py: SORTLAST_OPTIONS sets {0}, not one variant for each of {1}".format(
            sorted(mapping.values()), sorted(CMAKE_OPTIONS)))
    # Each variant with a dependency where it needs one: at least one depends_on(..., when=+v)
    # for the features that need a package.
    for v in ("vtk", "hdf5", "netcdf", "exr", "osmesa", "egl", "subdiv_reference", "python"):
        if not any(w and "+" + v in w for _, w in record["depends_on"]):
            fail("package.py: +{0} adds no dependency".format(v))
    cls = scope.get("Sortlast")
    if cls is None:
        fail("package.py: no class Sortlast")
        return
    for on in (set(variants), set()):
        pkg = cls.__new__(cls)
        pkg.spec = FakeSpec(on)
        args = pkg.cmake_args()
        for variant, option in mapping.items():
            want = "ON" if variant in on else "OFF"
            got = [a for a in args if re.match(r"-D{0}(:\w+)?=".format(option), a)]
            if len(got) != 1 or not got[0].endswith("=" + want):
                fail("package.py: cmake_args() with {0} {1}: {2} (expected {3}={4} once)".format(
                    variant, "on" if variant in on else "off", got, option, want))
    print("ok: package.py: {0} variants, one for each CMake option, passed as ON/OFF".format(len(variants)))


def check_apptainer(root):
    path = os.path.join(root, "packaging/apptainer/sortlast.def")
    text = open(path).read()
    header = dict(re.findall(r"^(Bootstrap|From):\s*(\S+)", text, re.M))
    if header.get("Bootstrap") != "docker" or header.get("From") != "debian:12":
        fail("sortlast.def: not bootstrapped from debian:12 ({0})".format(header))
    # The sections: %name lines; %post's body runs to the next one.
    sections = {}
    name = None
    for line in text.splitlines():
        m = re.match(r"^%(\w+)", line)
        if m:
            name = m.group(1)
            sections[name] = []
        elif name:
            sections[name].append(line)
    post = [l.strip() for l in sections.get("post", []) if l.strip() and not l.strip().startswith("#")]
    if not any(re.match(r"^(bash\s+)?(\./)?scripts/install-deps(\s|$)", l) for l in post):
        fail("sortlast.def: %post does not run scripts/install-deps")
    if not any(l.startswith("cmake --build") for l in post) or not any(l.startswith("cmake --install") for l in post):
        fail("sortlast.def: %post does not build and install")
    if "files" not in sections:
        fail("sortlast.def: no %files section copying the source in")
    print("ok: sortlast.def: Debian 12, %post runs scripts/install-deps, builds and installs")


STUB_DPKG = """#!/bin/bash
# dpkg-query -W -f='${Package} ${Status}\\n' PACKAGE...: every package installed except
# libvtk9-dev and python3 (not known to dpkg: no line, exit status 1)
shift 2
rc=0
for p in "$@"; do
  case $p in libvtk9-dev|python3) rc=1 ;; *) echo "$p install ok installed" ;; esac
done
exit $rc
"""
STUB_APT = """#!/bin/bash
echo "$*" >>"$LOG"
for a in "$@"; do [ "$a" = update ] && exit 0; done
for a in "$@"; do
  if [ "$a" = -s ]; then
    case " $* " in *" libvtk9-dev "*) [ "$VTK_OK" = 1 ] && exit 0
      echo "E: Error, pkgProblemResolver::Resolve generated breaks" >&2; exit 100 ;; esac
    exit 0
  fi
done
exit 0
"""


def check_install_deps(root):
    for vtk_ok in (0, 1):
        with tempfile.TemporaryDirectory() as tmp:
            for name, text in (("dpkg-query", STUB_DPKG), ("apt-get", STUB_APT),
                               ("npm", "#!/bin/sh\nexit 0\n"), ("node", "#!/bin/sh\nexit 0\n")):
                p = os.path.join(tmp, name)
                open(p, "w").write(text)
                os.chmod(p, 0o755)
            log = os.path.join(tmp, "apt.log")
            env = dict(os.environ, PATH=tmp + ":" + os.environ["PATH"], LOG=log, VTK_OK=str(vtk_ok))
            r = subprocess.run(["bash", os.path.join(root, "scripts/install-deps")], env=env,
                               capture_output=True, text=True, timeout=60)
            calls = open(log).read().splitlines() if os.path.exists(log) else []
            installs = [c for c in calls if " install " in " " + c + " " and "-s" not in c.split()]
            what = "install-deps where apt {0} add libvtk9-dev".format("can" if vtk_ok else "cannot")
            if r.returncode != 0:
                fail("{0}: exit status {1}: {2}".format(what, r.returncode, r.stderr[-400:]))
                continue
            if len(installs) != 1 or "python3" not in installs[0].split():
                fail("{0}: the other missing package not installed once: {1}".format(what, installs))
                continue
            has_vtk = "libvtk9-dev" in installs[0].split()
            said = "skipping libvtk9-dev" in r.stderr and "SORTLAST_WITH_VTK=OFF" in r.stderr
            if vtk_ok and (not has_vtk or said):
                fail("{0}: libvtk9-dev not installed ({1}; {2})".format(what, installs[0], r.stderr.strip()))
            elif not vtk_ok and (has_vtk or not said):
                fail("{0}: installed it or did not say so: {1}; stderr: {2}".format(what, installs[0], r.stderr.strip()))
            else:
                print("ok: {0}: {1}".format(what, "installed with the rest" if vtk_ok else r.stderr.strip()))


def main():
    root = sys.argv[1]
    check_spack(root)
    check_apptainer(root)
    check_install_deps(root)
    if failures:
        print("{0} failure(s)".format(len(failures)))
        return 1
    print("recipes passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
