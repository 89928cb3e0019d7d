# deform: space deformations on point arrays (RBF, FFD, DM-FFD, greedy, handle basis).
# Sees Eigen arrays only: no mesh, no files.
set(MESHMORPH_DEFORM_SOURCES
    meshmorph/deform/space_deformation.cpp
    meshmorph/deform/field_io.cpp
    meshmorph/deform/rbf_evaluator.cpp
    meshmorph/deform/rbf_settings.cpp
    meshmorph/deform/rbf_setup.cpp
    meshmorph/deform/rbf_deformation.cpp
    meshmorph/deform/bspline_basis.cpp
    meshmorph/deform/ffd_deformation.cpp
    meshmorph/deform/dmffd_deformation.cpp
    meshmorph/deform/jump_detection.cpp
    meshmorph/deform/dense_kernels.cpp
    meshmorph/deform/row_panel_factor.cpp
    meshmorph/deform/greedy_system.cpp
    meshmorph/deform/greedy_centres.cpp
    meshmorph/deform/greedy_rbf_deformation.cpp
    meshmorph/deform/handle_basis.cpp
    meshmorph/deform/idw_split.cpp
    meshmorph/deform/idw_tree.cpp
    meshmorph/deform/idw_tree_transpose.cpp
    meshmorph/deform/idw_deformation.cpp
    meshmorph/deform/corrected_deformation.cpp
    meshmorph/deform/held_fit.cpp
)
# sqrt in the blocked RBF evaluator vectorises only without errno semantics.
set_source_files_properties(meshmorph/deform/rbf_evaluator.cpp meshmorph/deform/idw_tree.cpp
    meshmorph/deform/idw_tree_transpose.cpp
    PROPERTIES COMPILE_OPTIONS "-fno-math-errno")
meshmorph_add_component(deform
    SOURCES ${MESHMORPH_DEFORM_SOURCES}
    DEPENDS meshmorph::core
    PRIVATE_DEPENDS LAPACK::LAPACK BLAS::BLAS ${CMAKE_DL_LIBS})
# deform/triharmonic8.h (core/simd8.h) passes 64-byte vectors: without AVX-512 GCC notes
# the ABI differs from an AVX-512 build's (no object of one build mixes the two).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(meshmorph_deform PRIVATE -Wno-psabi)
endif()
