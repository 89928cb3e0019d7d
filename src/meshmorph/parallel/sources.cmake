# parallel: the ranks of a -parallel run (MPI when built with it, else one rank) and the
# collectives the morph and the checker need. Depends on core.
set(meshmorph_parallel_deps meshmorph::core)
if(MESHMORPH_WITH_MPI)
    list(APPEND meshmorph_parallel_deps MPI::MPI_CXX)
endif()
meshmorph_add_component(parallel
    SOURCES meshmorph/parallel/communicator.cpp meshmorph/parallel/collective.cpp
    DEPENDS ${meshmorph_parallel_deps})
