# design: design variables for optimisers, on top of morph. The designVariables of a
# morphDict (design_variables), their unit constraint sets (variable_constraints), a
# lattice's box cutting its patches (lattice_box_cut), the
# fingerprints that tie a set-up to its case (case_fingerprint), the stored set-up
# (design_basis), what every design command reads (design_case), the set-up itself
# (design_setup), variants (design_variant, with their amplitudes: amplitude_table) and the
# transpose product (design_sensitivity). Depends on core, parallel, mesh, io, quality,
# deform and morph.
set(MESHMORPH_DESIGN_SOURCES
    meshmorph/design/design_variables.cpp
    meshmorph/design/variable_constraints.cpp
    meshmorph/design/lattice_box_cut.cpp
    meshmorph/design/case_fingerprint.cpp
    meshmorph/design/design_basis.cpp
    meshmorph/design/design_case.cpp
    meshmorph/design/design_storage.cpp
    meshmorph/design/shared_design_fit.cpp
    meshmorph/design/design_setup.cpp
    meshmorph/design/amplitude_table.cpp
    meshmorph/design/design_variant.cpp
    meshmorph/design/valid_step.cpp
    meshmorph/design/variant_repair.cpp
    meshmorph/design/design_sensitivity.cpp)
meshmorph_add_component(design
    SOURCES ${MESHMORPH_DESIGN_SOURCES}
    DEPENDS meshmorph::core meshmorph::io meshmorph::quality meshmorph::deform meshmorph::morph
            PRIVATE_DEPENDS nlohmann_json::nlohmann_json)
