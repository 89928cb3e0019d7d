# app: what the two applications add to the library: the option table, banner, exit codes,
# the MPI session of a -parallel run, and their reports (text, JSON). The morph itself is
# morph/morph_case.h, a library call. Depends on every other module.
set(MESHMORPH_APP_SOURCES
    meshmorph/app/options.cpp
    meshmorph/app/exit_status.cpp
    meshmorph/app/banner.cpp
    meshmorph/app/check_mesh_case.cpp
    meshmorph/app/parallel_run.cpp
    meshmorph/app/design_commands.cpp
    meshmorph/app/morph_mesh.cpp
    meshmorph/app/morph_session.cpp
    meshmorph/app/morph_sensitivity.cpp
    meshmorph/app/process_memory.cpp
)
meshmorph_add_component(app
    SOURCES ${MESHMORPH_APP_SOURCES}
    DEPENDS meshmorph::core meshmorph::io meshmorph::quality meshmorph::deform meshmorph::morph
            meshmorph::design nlohmann_json::nlohmann_json)
