# deform: space deformations on point arrays (RBF, FFD, DM-FFD, greedy, handle basis).
# Sees Eigen arrays only: no mesh, no files.
set(MESHMORPH_DEFORM_SOURCES
)
meshmorph_add_component(deform
    SOURCES ${MESHMORPH_DEFORM_SOURCES}
    DEPENDS meshmorph::core
    PRIVATE_DEPENDS LAPACK::LAPACK BLAS::BLAS)
