# morph: what turns a deformation of space into a valid mesh motion (local untangling of
# the cells a morph inverts). Depends on core and quality.
set(MESHMORPH_MORPH_SOURCES
    meshmorph/morph/local_untangle.cpp
)
meshmorph_add_component(morph
    SOURCES ${MESHMORPH_MORPH_SOURCES}
    DEPENDS meshmorph::core meshmorph::quality)
