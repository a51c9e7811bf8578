#!/usr/bin/env bash
# Installs every Debian package neomesh needs, then configures and builds it (Release) in
# ./build. Run as root on Debian 12 (or with sudo available). Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config clang-format
  libpetsc-real-dev            # DMPlex, Vec/Mat/KSP, hypre, MUMPS, SuiteSparse, MPI
  # An optimized BLAS/LAPACK for MUMPS (--linear-solver direct, --thesis), in place of the
  # reference one PETSc pulls in: factorizations 2-5x faster (docs/benchmarks.md).
  libopenblas0-openmp
  libeigen3-dev libcli11-dev libfmt-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcairo2-dev libmuparser-dev libpugixml-dev libmetis-dev zlib1g-dev
  libexodusii-dev              # Exodus II .exo/.e/.ex2 (over netCDF)
  libcgns-dev                  # CGNS .cgns (over HDF5)
  python3 python3-numpy python3-meshio python3-pytest gmsh  # tests: reader, runner, meshes
  python3-netcdf4              # tests: meshio's Exodus II reader and writer
  cgns-convert                 # tests: tetgen_to_cgns writes .cgns files
  python3-vtk9                 # tests: VTK's own readers read neomesh's .vtu and .vtk
  pybind11-dev python3-dev     # the Python package (python/)
  python3-petsc4py python3-mpi4py  # Python: DMPlex objects and communicators in and out
  python3-matplotlib python3-gmsh  # examples/python: Gmsh's API, pictures
)
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  $sudo apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
# The Python package into Debian's python3 path (/usr/local/lib/python3.X/dist-packages), so
# that `import neomesh` works from any folder.
$sudo cmake --install build --component python
