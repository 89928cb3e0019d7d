# io: OpenFOAM tokenizer, dictionaries, polyMesh/field readers and writers, surface (STL/OBJ)
# readers, VTK export. One source per line.
set(MESHMORPH_IO_SOURCES
    meshmorph/io/foam_tokenizer.cpp
    meshmorph/io/foam_header.cpp
    meshmorph/io/foam_dictionary.cpp
    meshmorph/io/foam_dictionary_parser.cpp
    meshmorph/io/foam_compound.cpp
    meshmorph/io/boundary_io.cpp
    meshmorph/io/foam_file.cpp
    meshmorph/io/temp_file.cpp
    meshmorph/io/foam_lists.cpp
    meshmorph/io/foam_list_locate.cpp
    meshmorph/io/foam_list_start.cpp
    meshmorph/io/foam_list_kernels.cpp
    meshmorph/io/foam_list_binary.cpp
    meshmorph/io/foam_face_lists.cpp
    meshmorph/io/foam_list_writers.cpp
    meshmorph/io/case_instance.cpp
    meshmorph/io/decomposed_case.cpp
    meshmorph/io/read_poly_mesh.cpp
    meshmorph/io/write_poly_mesh.cpp
    meshmorph/io/point_field.cpp
    meshmorph/io/surface_io.cpp
)
set(MESHMORPH_IO_VTK_SOURCES
    meshmorph/io/vtk_writer.cpp
)
set(meshmorph_io_private_deps ZLIB::ZLIB)
if(MESHMORPH_WITH_VTK)
    list(APPEND MESHMORPH_IO_SOURCES ${MESHMORPH_IO_VTK_SOURCES})
    list(APPEND meshmorph_io_private_deps ${VTK_LIBRARIES})
endif()
meshmorph_add_component(io
    SOURCES ${MESHMORPH_IO_SOURCES}
    DEPENDS meshmorph::core meshmorph::parallel
    PRIVATE_DEPENDS ${meshmorph_io_private_deps})
if(MESHMORPH_WITH_VTK AND TARGET meshmorph_io AND MESHMORPH_IO_VTK_SOURCES)
    get_target_property(meshmorph_io_type meshmorph_io TYPE)
    if(NOT meshmorph_io_type STREQUAL "INTERFACE_LIBRARY")
        vtk_module_autoinit(TARGETS meshmorph_io MODULES ${VTK_LIBRARIES})
    endif()
endif()
