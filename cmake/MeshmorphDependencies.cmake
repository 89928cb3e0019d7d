# SPDX-License-Identifier: GPL-3.0-or-later
# Finds meshMorph's dependencies; all come from Debian packages (see scripts/install-deps.sh).

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(ZLIB REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)

# LAPACK (OpenBLAS on Debian) provides the blocked Cholesky dpotrf and the dgemm rate.
set(BLA_VENDOR OpenBLAS)
find_package(BLAS)
find_package(LAPACK)
if(NOT LAPACK_FOUND)
    unset(BLA_VENDOR)
    find_package(BLAS REQUIRED)
    find_package(LAPACK REQUIRED)
endif()

if(MESHMORPH_WITH_VTK)
    find_package(VTK 9 COMPONENTS CommonCore CommonDataModel IOXML IOLegacy)
    if(NOT VTK_FOUND)
        message(WARNING "VTK 9 not found: building without the VTK exporters")
        set(MESHMORPH_WITH_VTK OFF)
    endif()
endif()

if(MESHMORPH_WITH_MPI)
    find_package(MPI COMPONENTS CXX)
    if(NOT MPI_CXX_FOUND)
        message(WARNING "MPI not found: building without -parallel (install libopenmpi-dev)")
        set(MESHMORPH_WITH_MPI OFF)
    endif()
endif()

if(BUILD_TESTING OR NOT DEFINED BUILD_TESTING)
    find_package(GTest)
endif()
if(MESHMORPH_BUILD_BENCHMARKS)
    find_package(benchmark)
    if(NOT benchmark_FOUND)
        message(WARNING "Google Benchmark not found: benchmarks disabled")
        set(MESHMORPH_BUILD_BENCHMARKS OFF)
    endif()
endif()
