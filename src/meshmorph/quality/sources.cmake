# quality: checkMesh-equivalent metrics and report; the paper's metrics (scaled Jacobian,
# mean curvature). One source per line.
#
# checkMesh's three tiers: metric fields (one topic per file: face_*, cell_*, edge_*, ...),
# checks (*_checks.cpp: field -> CheckResult), report (check_mesh.cpp drives, report_text.cpp
# and quality_json.cpp walk the results).
set(MESHMORPH_QUALITY_SOURCES
    meshmorph/quality/scaled_jacobian.cpp
    meshmorph/quality/mean_curvature.cpp
    meshmorph/quality/cell_closedness.cpp
    meshmorph/quality/cell_concavity.cpp
    meshmorph/quality/cell_determinant.cpp
    meshmorph/quality/cell_edge_usage.cpp
    meshmorph/quality/cell_regions.cpp
    meshmorph/quality/cell_validity.cpp
    meshmorph/quality/symmetry_plane_planarity.cpp
    meshmorph/quality/edge_alignment.cpp
    meshmorph/quality/edge_lengths.cpp
    meshmorph/quality/face_concavity.cpp
    meshmorph/quality/face_face_connectivity.cpp
    meshmorph/quality/face_flatness.cpp
    meshmorph/quality/face_orthogonality.cpp
    meshmorph/quality/face_pyramids.cpp
    meshmorph/quality/inversion_step.cpp
    meshmorph/quality/face_skewness.cpp
    meshmorph/quality/face_tets.cpp
    meshmorph/quality/face_twist.cpp
    meshmorph/quality/face_weights.cpp
    meshmorph/quality/coupled_points.cpp
    meshmorph/quality/processor_regions.cpp
    meshmorph/quality/check_reduction.cpp
    meshmorph/quality/parallel_report.cpp
    meshmorph/quality/mesh_edges.cpp
    meshmorph/quality/point_nearness.cpp
    meshmorph/quality/wedge_alignment.cpp
    meshmorph/quality/zone_topology.cpp
    meshmorph/quality/check_result.cpp
    meshmorph/quality/topology_checks.cpp
    meshmorph/quality/geometry_checks.cpp
    meshmorph/quality/mesh_quality_checks.cpp
    meshmorph/quality/check_mesh.cpp
    meshmorph/quality/quality_report.cpp
    meshmorph/quality/report_text.cpp
    meshmorph/quality/quality_json.cpp
    meshmorph/quality/quality_summary.cpp
)
meshmorph_add_component(quality
    SOURCES ${MESHMORPH_QUALITY_SOURCES}
    DEPENDS meshmorph::core meshmorph::parallel meshmorph::mesh nlohmann_json::nlohmann_json)
if(MESHMORPH_QUALITY_SOURCES)
    # Bit-level agreement with OpenFOAM's checkMesh: never contract a*b+c into an FMA.
    target_compile_options(meshmorph_quality PRIVATE -ffp-contract=off)
    # mesh/foam_vector8.h returns 64-byte vectors: without AVX-512 GCC notes the ABI differs
    # from an AVX-512 build's (no object of one build mixes the two).
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
        target_compile_options(meshmorph_quality PRIVATE -Wno-psabi)
    endif()
endif()
