# SPDX-License-Identifier: GPL-3.0-or-later
"""IDWarp's USMesh calls on meshmorph, so that a DAFoam/pyGeo script can try meshmorph.

The surface is the points of the wall patches (or `surface_patches`); every other boundary
patch keeps its morphDict entry (fixed without a morphDict). warpMesh() is an exact morph
(the case's method, rbf by default) from the mesh as read.

warpDeriv(dXv) returns dJ/dXs, as IDWarp does: the transpose of the last warpMesh's morph
(its field's choices held), one row per surface point, also kept for getdXs(). With
meshmorph's own design variables (morphDict designVariables, set up with setup_design),
designDeriv(dXv) returns dJ/da instead (what warpDeriv followed by pyGeo's
totalSensitivity gives).
"""
import numpy as np

from ._core import Case, DesignStudy, InputError


def _real_points(values, call):
    """values as (n, 3) floats, refused as the module's other calls refuse them: booleans,
    complex numbers, strings and objects are a TypeError (not converted: numpy would make
    True 1.0 and drop imaginary parts), NaN or infinite values an InputError."""
    a = np.asarray(values)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{call}: an array of real numbers is needed, not {a.dtype}")
    if a.size % 3 != 0:
        raise ValueError(f"{call}: {a.size} values are not (n, 3) coordinates")
    a = a.astype(float).reshape(-1, 3)
    if not np.isfinite(a).all():
        raise InputError(f"{call}: coordinates that are not finite (NaN or infinite)")
    return a


class USMesh:
    """IDWarp-style access to a case: getSurfaceCoordinates, setSurfaceCoordinates,
    warpMesh, getSolverGrid/getWarpGrid, warpDeriv, getdXs (and designDeriv for
    meshmorph's own design variables)."""

    def __init__(self, options=None, case=".", surface_patches=None, **case_kwargs):
        """Open a case as IDWarp's USMesh opens a grid: options["gridFile"] (or case) is
        the case directory; the surface is the points of surface_patches (default: every
        wall patch); case_kwargs go to Case (region, time, dict, ...)."""
        options = dict(options or {})
        case = options.pop("gridFile", case)
        self.case = Case(case, **case_kwargs)
        self._case_kwargs = case_kwargs
        self._case_dir = case
        patches = self.case.patches
        if surface_patches is None:
            surface_patches = [n for n, p in patches.items() if p["type"] == "wall"]
        if not surface_patches:
            raise InputError("no wall patches: give surface_patches")
        labels = [self.case.patch_points(name) for name in surface_patches]
        self.surface_patches = list(surface_patches)
        self._surface = np.unique(np.concatenate(labels))
        self._target = None
        self._study = None
        self._dXs = None
        self.report = None

    def getSurfaceCoordinates(self):
        """(n, 3) coordinates of the surface points (a copy), in ascending label order."""
        return self.case.points[self._surface].copy()

    def setSurfaceCoordinates(self, coordinates):
        """The surface points' new positions, in getSurfaceCoordinates' order."""
        xs = _real_points(coordinates, "setSurfaceCoordinates")
        if xs.shape[0] != self._surface.size:
            raise InputError(f"setSurfaceCoordinates: {xs.shape[0]} points given, "
                             f"the surface has {self._surface.size}")
        self._target = xs

    def warpMesh(self):
        """Move the volume points so that the surface reaches its set coordinates."""
        if self._target is None:
            raise InputError("warpMesh: call setSurfaceCoordinates first")
        d = self._target - self.case.initial_points[self._surface]
        self.report = self.case.morph(points={"surface": (self._surface, d)})
        return self.report

    def getSolverGrid(self):
        """The volume points, flat (3n,) as IDWarp returns them (a copy)."""
        return self.case.points.reshape(-1).copy()

    getWarpGrid = getSolverGrid

    def warpDeriv(self, dXv):
        """dJ/dXs for dJ/dXv ((n, 3) or flat), as IDWarp's warpDeriv: (nSurface, 3), in
        getSurfaceCoordinates' order, through the last warpMesh (call it first); kept for
        getdXs(). The exact transpose of that morph's field with its choices held."""
        if self.report is None:
            raise InputError("warpDeriv: call warpMesh first (the derivative is that of the "
                             "last warp)")
        self._dXs = self.case.sensitivity(dXv)[self._surface]
        return self._dXs

    def getdXs(self):
        """The last warpDeriv's dJ/dXs ((nSurface, 3), a copy)."""
        if self._dXs is None:
            raise InputError("getdXs: call warpDeriv first")
        return self._dXs.copy()

    def designDeriv(self, dXv):
        """dJ/da of meshmorph's design variables for dJ/dXv ((n, 3) or flat): the chain rule
        through the set-up's fields (setup_design must have been run on the case)."""
        if self._study is None:
            kwargs = {k: v for k, v in self._case_kwargs.items() if k != "method"}
            self._study = DesignStudy(self._case_dir, **kwargs)
        return self._study.transpose_product(dXv)
