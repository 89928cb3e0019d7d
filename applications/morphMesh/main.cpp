// SPDX-License-Identifier: GPL-3.0-or-later
// Description
//     Morphs the polyMesh of an OpenFOAM case (for instance straight after snappyHexMesh)
//     without re-meshing: reads system/morphDict, prescribes displacements on boundary
//     points (fixed, translate, rotate, scale, pointDisplacement, surface, slip, free) and
//     optional handle points, fits a space deformation (RBF by default, DM-FFD or FFD),
//     moves every mesh point and checks the result with the built-in checkMesh.
//
// Usage
//     morphMesh [-case DIR] [-dict FILE] [-time T | -latestTime] [-overwrite]
//               [-method rbf|dmffd|ffd|idw] [-json FILE] [-vtk | -vtkFile FILE] [-force]
//               [-help]
//
//     Without -overwrite only <next time>/polyMesh/points is written (like moveMesh);
//     with it the instance's points are replaced atomically, in the same format.
//     Exit status: 0 written, 2 input error, 3 refused (new invalid cells), 4 fit failed,
//     5 internal error. See tutorials/ for morphDict examples.
#include <iostream>

#include "meshmorph/app/morph_mesh.h"
#include "meshmorph/app/process_memory.h"
#include "meshmorph/io/temp_file.h"

int main(int argc, char* argv[])
{
    meshmorph::app::configure_process_memory(argv);
    meshmorph::io::remove_temps_on_interrupt(); // an interrupted write leaves no temporary
    return meshmorph::app::run_morph_mesh(argc, argv, std::cout, std::cerr);
}
