# morph: the morph domain between deform and app. morphDict prescriptions (motion,
# morph_setup) -> which entry moves each patch (patch_assignment) -> claims per point
# (claims, handle_selection; refused when they cannot be done: prescription_checks) -> one
# prescription per point (conflict_resolution) -> the
# constraint set (constraints; refused at once when it folds faces over: folded_faces); one
# fit and evaluation (point_morph), the step loop (morph_steps) and the repair of cells a
# step inverts (local_untangle). 2D cases keep their empty planes (empty_planes); slip and
# wedge patches their plane (patch_plane).
# A -parallel run resolves the constraints on the master (distributed_constraints). The
# deformation methods, one row each (deformation_methods; settings read by deformation_dict,
# memory by fit_memory), and the whole morph of a case as one call (morph_case: its stages'
# parts in surface_projector, point_displacement_input, distributed_case, morph_log,
# morph_output). Depends on core, parallel, mesh, io, quality and deform.
set(MESHMORPH_MORPH_SOURCES
    meshmorph/morph/motion.cpp
    meshmorph/morph/new_check_failures.cpp
    meshmorph/morph/invalid_cells_location.cpp
    meshmorph/morph/folded_faces.cpp
    meshmorph/morph/morph_setup.cpp
    meshmorph/morph/patch_assignment.cpp
    meshmorph/morph/empty_planes.cpp
    meshmorph/morph/patch_plane.cpp
    meshmorph/morph/wedge_symmetry.cpp
    meshmorph/morph/claims.cpp
    meshmorph/morph/conflict_resolution.cpp
    meshmorph/morph/handle_selection.cpp
    meshmorph/morph/prescription_checks.cpp
    meshmorph/morph/decomposition.cpp
    meshmorph/morph/constraint_steps.cpp
    meshmorph/morph/constraints.cpp
    meshmorph/morph/cyclic_coupling.cpp
    meshmorph/morph/duplicate_points.cpp
    meshmorph/morph/distributed_constraints.cpp
    meshmorph/morph/jump_band_graph.cpp
    meshmorph/morph/jump_smoothing.cpp
    meshmorph/morph/jump_smoothing_guard.cpp
    meshmorph/morph/jump_smoothing_parallel.cpp
    meshmorph/morph/point_morph.cpp
    meshmorph/morph/morph_sensitivity.cpp
    meshmorph/morph/morph_steps.cpp
    meshmorph/morph/local_untangle.cpp
    meshmorph/morph/non_ortho_repair.cpp
    meshmorph/morph/deformation_dict.cpp
    meshmorph/morph/deformation_methods.cpp
    meshmorph/morph/fit_memory.cpp
    meshmorph/morph/surface_projector.cpp
    meshmorph/morph/distributed_case.cpp
    meshmorph/morph/point_displacement_input.cpp
    meshmorph/morph/morph_log.cpp
    meshmorph/morph/morph_output.cpp
    meshmorph/morph/before_check.cpp
    meshmorph/morph/morph_stages.cpp
    meshmorph/morph/morph_case.cpp
)
meshmorph_add_component(morph
    SOURCES ${MESHMORPH_MORPH_SOURCES}
    DEPENDS meshmorph::core meshmorph::parallel meshmorph::mesh meshmorph::io meshmorph::quality meshmorph::deform)
