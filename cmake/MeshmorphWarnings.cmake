# SPDX-License-Identifier: GPL-3.0-or-later
# meshmorph_target_defaults(target): language level and warnings for project targets.
# Extra warnings and -Werror are added by presets (CMakePresets.json) via CMAKE_CXX_FLAGS.
function(meshmorph_target_defaults target)
    target_compile_features(${target} PUBLIC cxx_std_20)
    set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
    if(MESHMORPH_NATIVE)
        target_compile_options(${target} PRIVATE -march=native)
    endif()
endfunction()
