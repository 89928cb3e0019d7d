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
    meshmorph/io/point_field_writer.cpp
    meshmorph/io/surface_io.cpp
)
# The VTK writer prepares plain arrays; VTK itself is in a module loaded only when a run
# writes VTK (vtk_export.h: linking VTK cost every start of the applications ~30 ms).
set(MESHMORPH_IO_VTK_SOURCES
    meshmorph/io/vtk_writer.cpp
    meshmorph/io/vtk_module_loader.cpp
)
set(meshmorph_io_private_deps ZLIB::ZLIB)
if(MESHMORPH_WITH_VTK)
    list(APPEND MESHMORPH_IO_SOURCES ${MESHMORPH_IO_VTK_SOURCES})
    list(APPEND meshmorph_io_private_deps ${CMAKE_DL_LIBS})
endif()
meshmorph_add_component(io
    SOURCES ${MESHMORPH_IO_SOURCES}
    DEPENDS meshmorph::core meshmorph::parallel
    PRIVATE_DEPENDS ${meshmorph_io_private_deps})
if(MESHMORPH_WITH_VTK)
    include(GNUInstallDirs)
    add_library(meshmorph_vtk MODULE meshmorph/io/vtk_module.cpp)
    meshmorph_target_defaults(meshmorph_vtk)
    target_include_directories(meshmorph_vtk PRIVATE ${MESHMORPH_SRC_DIR})
    target_link_libraries(meshmorph_vtk PRIVATE ${VTK_LIBRARIES})
    set_target_properties(meshmorph_vtk PROPERTIES
        LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib
        CXX_VISIBILITY_PRESET hidden)
    vtk_module_autoinit(TARGETS meshmorph_vtk MODULES ${VTK_LIBRARIES})
    install(TARGETS meshmorph_vtk LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/meshmorph)
    target_compile_definitions(meshmorph_io PRIVATE
        MESHMORPH_VTK_MODULE_BUILD_PATH="$<TARGET_FILE:meshmorph_vtk>"
        MESHMORPH_VTK_MODULE_INSTALL_PATH="${CMAKE_INSTALL_FULL_LIBDIR}/meshmorph/$<TARGET_FILE_NAME:meshmorph_vtk>"
        MESHMORPH_VTK_MODULE_INSTALL_SUBPATH="${CMAKE_INSTALL_LIBDIR}/meshmorph/$<TARGET_FILE_NAME:meshmorph_vtk>")
    # Whatever links the writer can load the module.
    add_dependencies(meshmorph_io meshmorph_vtk)
endif()
