# core: types, mesh container, addressing, errors, logging, progress, triangle surfaces and
# pure geometry. No file I/O (that is io/).
meshmorph_add_component(core
    SOURCES
        meshmorph/core/poly_mesh.cpp
        meshmorph/core/log.cpp
        meshmorph/core/progress.cpp
        meshmorph/core/stopwatch.cpp
        meshmorph/core/cell_shapes.cpp
        meshmorph/core/triangle_surface.cpp
        meshmorph/core/memory_budget.cpp
        meshmorph/core/number_format.cpp
        meshmorph/core/cubic_first_root.cpp
        meshmorph/core/heap_reuse.cpp
        # (one file per line)
    DEPENDS Eigen3::Eigen OpenMP::OpenMP_CXX)
