#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws the README's picture from the pipe tutorial's own output.

tutorials/pipe/Allrun runs `morphMesh -vtk`, which writes VTK/morphMesh_1.vtu: the morphed
mesh with the point data `displacement` and the cell data `nonOrthogonality`. This script
cuts that mesh, and the mesh before the morph (the points minus their displacement), with
the plane x = 0 through the pipe's axis and draws both cuts side by side, the morphed cells
coloured by their largest face non-orthogonality.

    docs/images/render_pipe.py [VTU] [PNG]
      (defaults: tutorials/pipe/VTK/morphMesh_1.vtu, docs/images/pipe-venturi.png)

Needs Debian's python3-vtk9 (reading and cutting only, no rendering window) and
python3-matplotlib.
"""
import sys
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection
import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

REPO = Path(__file__).resolve().parents[2]


def read_grid(path):
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() == 0:
        sys.exit(f"render_pipe: {path}: no cells (run tutorials/pipe/Allrun first)")
    return grid


def moved_back(grid):
    """A copy of `grid` with every point moved back by its displacement: the mesh before."""
    before = vtk.vtkUnstructuredGrid()
    before.DeepCopy(grid)
    x = vtk_to_numpy(grid.GetPoints().GetData())
    d = vtk_to_numpy(grid.GetPointData().GetArray("displacement"))
    points = vtk.vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x - d), deep=True))
    before.SetPoints(points)
    return before


def axial_cut(grid):
    """The polygons where the plane x = 0 cuts the cells, as (y, z) outlines, and their
    cells' non-orthogonality."""
    plane = vtk.vtkPlane()
    plane.SetOrigin(0.0, 0.0, 0.0)
    plane.SetNormal(1.0, 0.0, 0.0)
    cutter = vtk.vtkCutter()
    cutter.SetCutFunction(plane)
    cutter.GenerateTrianglesOff()   # the cut polygons as they are, not triangulated
    cutter.SetInputData(grid)
    cutter.Update()
    cut = cutter.GetOutput()
    x = vtk_to_numpy(cut.GetPoints().GetData())
    outlines = []
    for c in range(cut.GetNumberOfCells()):
        ids = cut.GetCell(c).GetPointIds()
        outlines.append([(x[ids.GetId(k), 2], x[ids.GetId(k), 1])
                         for k in range(ids.GetNumberOfIds())])
    return outlines, vtk_to_numpy(cut.GetCellData().GetArray("nonOrthogonality"))


def draw(ax, outlines, title, values=None, norm=None):
    faces = PolyCollection(outlines, edgecolors="0.15", linewidths=0.3,
                           facecolors="0.85" if values is None else None,
                           cmap="viridis", norm=norm)
    if values is not None:
        faces.set_array(values)
    ax.add_collection(faces)
    ax.set_xlim(-0.02, 2.02)
    ax.set_ylim(-0.52, 0.52)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(title, fontsize=9)
    return faces


def main():
    vtu = Path(sys.argv[1]) if len(sys.argv) > 1 else REPO / "tutorials/pipe/VTK/morphMesh_1.vtu"
    png = Path(sys.argv[2]) if len(sys.argv) > 2 else REPO / "docs/images/pipe-venturi.png"
    after = read_grid(vtu)
    before_cut, _ = axial_cut(moved_back(after))
    after_cut, non_ortho = axial_cut(after)

    fig, axes = plt.subplots(1, 2, figsize=(9.0, 2.6))
    draw(axes[0], before_cut, "constant/polyMesh: the pipe")
    norm = matplotlib.colors.Normalize(vmin=0.0, vmax=max(float(non_ortho.max()), 1.0))
    faces = draw(axes[1], after_cut, "1/polyMesh: the wall on the venturi STL", non_ortho, norm)
    bar = fig.colorbar(faces, ax=axes, shrink=0.8, pad=0.01)
    bar.set_label("max non-orthogonality [deg]", fontsize=8)
    bar.ax.tick_params(labelsize=7)
    fig.savefig(png, dpi=110, bbox_inches="tight")
    print(f"render_pipe: wrote {png}")


if __name__ == "__main__":
    main()
