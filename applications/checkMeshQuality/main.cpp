// SPDX-License-Identifier: GPL-3.0-or-later
// Description
//     Checks the validity and quality of an OpenFOAM polyMesh like OpenFOAM's checkMesh:
//     the same topology and geometry checks, formulas and report text (OpenFOAM v1912),
//     plus offending-element sets, per-cell quality fields (VTK) and a JSON summary.
//
// Usage
//     checkMeshQuality [-case DIR] [-time T | -latestTime] [-allGeometry] [-allTopology]
//                      [-meshQuality] [-writeSets] [-vtk | -vtkFile FILE] [-json FILE]
//                      [-quiet] [-help]
//
//     -vtk writes VTK/checkMeshQuality_[<region>_]<time>.vtu in the case.
//     Exit status: 0 mesh OK, 1 checks failed, 2 input error, 5 internal error.
#include <iostream>

#include "meshmorph/app/check_mesh_case.h"
#include "meshmorph/app/process_memory.h"
#include "meshmorph/io/temp_file.h"

int main(int argc, char* argv[])
{
    meshmorph::app::configure_process_memory(argv);
    meshmorph::io::remove_temps_on_interrupt(); // an interrupted write leaves no temporary
    return meshmorph::app::run_check_mesh_quality(argc, argv, std::cout, std::cerr);
}
