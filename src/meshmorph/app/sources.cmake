# app: option table, banner, exit codes, the two applications' case-level runs and reports,
# the deformation factory (morphDict method settings). Depends on every other module.
set(MESHMORPH_APP_SOURCES
    meshmorph/app/options.cpp
    meshmorph/app/exit_status.cpp
    meshmorph/app/banner.cpp
    meshmorph/app/check_mesh_case.cpp
    meshmorph/app/decomposed_case.cpp
    meshmorph/app/morph_mesh.cpp
    meshmorph/app/deformation_factory.cpp
    meshmorph/app/fit_memory.cpp
)
meshmorph_add_component(app
    SOURCES ${MESHMORPH_APP_SOURCES}
    DEPENDS meshmorph::core meshmorph::io meshmorph::quality meshmorph::deform meshmorph::morph
            nlohmann_json::nlohmann_json)
