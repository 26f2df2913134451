#!/usr/bin/env python3
"""Picture of one point field of a sealfe VTU on the dam (outside CI; needs python3-vtk9 and
matplotlib, e.g. /usr/bin/python3 on Debian).

usage: plot_field.py solution.vtu field output.png [title]
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def main():
    vtu, field, png = sys.argv[1:4]
    title = sys.argv[4] if len(sys.argv) > 4 else field
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(vtu)
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData())
    values = vtk_to_numpy(grid.GetPointData().GetArray(field))
    triangles = []
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        q = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        if len(q) == 4:  # VTK quad: counter-clockwise
            triangles += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    tri = mtri.Triangulation(points[:, 0] * 1e3, points[:, 1] * 1e3, triangles)
    fig, ax = plt.subplots(figsize=(6, 5.4))
    image = ax.tripcolor(tri, values, shading="gouraud", cmap="viridis")
    fig.colorbar(image, ax=ax, label=field)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
