# app: option table, banner, case/time helpers, morph set-up (boundary constraints from
# morphDict), the deformation factory. Depends on every other module.
set(MESHMORPH_APP_SOURCES
    meshmorph/app/options.cpp
    meshmorph/app/exit_status.cpp
    meshmorph/app/banner.cpp
    meshmorph/app/check_mesh_case.cpp
    meshmorph/app/morph_setup.cpp
    meshmorph/app/point_morph.cpp
    meshmorph/app/morph_steps.cpp
    meshmorph/app/morph_mesh.cpp
    meshmorph/app/deformation_factory.cpp
)
meshmorph_add_component(app
    SOURCES ${MESHMORPH_APP_SOURCES}
    DEPENDS meshmorph::core meshmorph::io meshmorph::quality meshmorph::deform meshmorph::morph
            nlohmann_json::nlohmann_json)
