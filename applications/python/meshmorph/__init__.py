# SPDX-License-Identifier: GPL-3.0-or-later
"""meshmorph: morph OpenFOAM meshes in memory, check them, and use design variables.

    import meshmorph
    case = meshmorph.Case("motorBike")                 # reads constant/polyMesh
    report = case.morph()                              # system/morphDict, in memory
    report = case.morph(patches={"wing": d})           # or prescribed displacements
    case.check()["maxNonOrthogonality"], case.is_valid()
    case.write()                                       # 1/polyMesh/points, atomically

    meshmorph.setup_design("motorBike")                # morphMesh -variables
    study = meshmorph.DesignStudy("motorBike")
    x = study.points(a); study.evaluate(a); study.write()
    dJda = study.transpose_product(dJdx)               # morphMesh -sensitivity

Results are those of the applications, bit for bit (same library, same code paths).
Log lines go to Python's logging (logger "meshmorph"; logging.basicConfig(level="INFO")
shows morphMesh's log). Errors raise meshmorph.Error and its kinds ParseError,
InputError, IoError and SolverError with the applications' messages. See docs/python.md.
"""
from ._requirements import core_not_loading, missing_numpy

# Raised here, so that the traceback is one line of this file above the message.
_problem = missing_numpy()
if _problem:
    raise ImportError(_problem)
try:
    from ._core import (Case, DesignStudy, Error, InputError, IoError, ParseError,  # noqa: F401
                        SolverError, setup_design)
except ImportError as error:
    raise ImportError(core_not_loading(error)) from None
from ._build_info import VERSION as __version__  # noqa: E402
from .idwarp import USMesh  # noqa: F401

__all__ = ["Case", "DesignStudy", "setup_design", "USMesh", "Error", "ParseError",
           "InputError", "IoError", "SolverError"]
