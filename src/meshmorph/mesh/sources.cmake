# mesh: the polyMesh as OpenFOAM's primitiveMesh/polyMesh computes it: geometry (face and
# cell centres, areas, volumes, directions, wedge patches), addressing (point -> faces),
# coupled (cyclic) and processor patches and the patch predicates. Between core/parallel and
# io/quality/morph: the checker measures on it, the morph builds its constraints with it.
meshmorph_add_component(mesh
    SOURCES
        meshmorph/mesh/mesh_geometry.cpp
        meshmorph/mesh/wedge_geometry.cpp
        meshmorph/mesh/coupled_patches.cpp
        meshmorph/mesh/processor_faces.cpp
        meshmorph/mesh/point_faces.cpp
        meshmorph/mesh/patch_kinds.cpp
    DEPENDS meshmorph::core meshmorph::parallel)
# Bit-level agreement with OpenFOAM's checkMesh: the geometry must never contract a*b+c into
# an FMA (on FMA hardware it would stop matching checkMesh).
target_compile_options(meshmorph_mesh PRIVATE -ffp-contract=off)
# mesh/foam_vector8.h returns 64-byte vectors: without AVX-512 GCC notes the ABI differs
# from an AVX-512 build's (no object of one build mixes the two).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(meshmorph_mesh PRIVATE -Wno-psabi)
endif()
