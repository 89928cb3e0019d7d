# quality: checkMesh-equivalent metrics and report; the paper's metrics (scaled Jacobian,
# mean curvature). Owners add their files to the list (one per line).
set(MESHMORPH_QUALITY_SOURCES
    meshmorph/quality/scaled_jacobian.cpp
    meshmorph/quality/mean_curvature.cpp
    meshmorph/quality/mesh_geometry.cpp
    meshmorph/quality/cell_validity.cpp
    meshmorph/quality/check_mesh.cpp
    meshmorph/quality/mesh_quality_checks.cpp
    meshmorph/quality/quality_json.cpp
)
meshmorph_add_component(quality
    SOURCES ${MESHMORPH_QUALITY_SOURCES}
    DEPENDS meshmorph::core nlohmann_json::nlohmann_json)
if(MESHMORPH_QUALITY_SOURCES)
    # Bit-level agreement with OpenFOAM's checkMesh: never contract a*b+c into an FMA.
    target_compile_options(meshmorph_quality PRIVATE -ffp-contract=off)
endif()
