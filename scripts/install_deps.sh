#!/usr/bin/env bash
# Installs mcws's build and test dependencies from Debian 12 packages.
# Idempotent: runs apt-get only when a package is missing.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  ninja-build lld               # faster builds: Ninja keeps both cores busy, LLVM's linker
  libpcl-dev pcl-tools          # point clouds, PCD I/O, KdTreeFLANN, pcl_viewer & co.
  libeigen3-dev                 # linear algebra, poses
  libflann-dev                  # nearest-neighbour search behind pcl::KdTreeFLANN
  libboost-program-options-dev  # command-line parsing of the stage tools
  libboost-dev                  # Boost.Graph (Yen's k shortest paths), Boost.Math (chi-square)
  libyaml-cpp-dev               # robot description files
  liburdfdom-dev                # URDF robot files (urdfdom parser)
  libgtest-dev libgmock-dev     # unit tests (GoogleTest, GoogleMock)
  libbenchmark-dev              # benchmarks
  liborocos-kdl-dev             # independent kinematics oracle in tests
  nlohmann-json3-dev            # --json output of the stage tools
  gnuplot-nox                   # PNG pictures of clouds
  libcgal-dev                   # alpha shapes / Delaunay for areas and volumes
  libtbb-dev                    # CGAL's parallel 3-D Delaunay triangulation (mcws_measure)
  libnanoflann-dev              # k-nearest-neighbour kd-tree for the local spacing (mcws_measure)
  libfcl-dev                    # collision checking (FCL: OBBRSS mesh trees, primitives)
  libassimp-dev                 # the tests' oracle for mcws's COLLADA (.dae) reader (assimp)
  libompl-dev                   # motion planning roadmaps (OMPL's PRM) for mcws_plan
  graphviz                      # renders the behaviour state machines (mcws_behave --dot) to PNG
  time                          # /usr/bin/time -v in the benchmark scripts
  libpng-dev                    # the tests decode the tools' PNG pictures (tests/png_image.h)
  libssl-dev                    # SHA-256 of the robot file recorded in every cloud (libcrypto)
  libopenmpi-dev openmpi-bin    # mpirun -np K mcws_sample / mcws_refine: MPI and MPI-IO
  procps                        # pgrep: the test that kills one process of an MPI run
  python3                       # scripts/check_layers.py: the floors of docs/architecture.md (CTest)
  python3-dev python3-numpy     # the Python module mcws (python/): the interpreter's headers, NumPy
  pybind11-dev python3-pybind11 # its C++ bindings (pybind11's headers and CMake package)
  python3-pytest                # tests/python, run by CTest (python_api)
  libjs-three                   # three.js, inlined in the study report's 3-D view (mcws::report)
  chromium chromium-driver      # the report page's browser test: headless Chromium, its WebDriver
  python3-selenium python3-pil  # that test's browser driver and its screenshot decoding
  clang-14 libclang-rt-14-dev   # the sanitizer tree and the libFuzzer targets of fuzz/
  libomp-14-dev                 # clang's OpenMP runtime (the sanitizer tree)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "install_deps: installing ${missing[*]}" >&2
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
else
  echo "install_deps: all packages present" >&2
fi
