#!/usr/bin/env python3
"""Picture of one point field of a sealfe VTU on the dam (outside CI; needs python3-vtk9 and
matplotlib, e.g. /usr/bin/python3 on Debian).

usage: plot_field.py solution.{vtu,pvtu,pvd} field output.png [title]

A .pvd shows its first data set (its last with --last); cells may be straight quads or VTK
Lagrange quadrilaterals of any degree (what sealfe writes).
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def lagrange_index(i, j, p):
    """Position of lattice point (i, j) in a VTK Lagrange quadrilateral of order p
    (vtkHigherOrderQuadrilateral::PointIndexFromIJK)."""
    ibdy, jbdy = i in (0, p), j in (0, p)
    if ibdy and jbdy:
        return (2 if j else 1) if i else (3 if j else 0)
    if jbdy:
        return 4 + (i - 1) + ((p - 1) + (p - 1) if j else 0)
    if ibdy:
        return 4 + (j - 1) + ((p - 1) if i else 2 * (p - 1) + (p - 1))
    return 4 + 4 * (p - 1) + (i - 1) + (p - 1) * (j - 1)


def read(path, last):
    """The unstructured grid of a .vtu, .pvtu or (the first or last data set of) a .pvd."""
    if path.endswith(".pvd"):
        sets = ET.parse(path).getroot().findall(".//DataSet")
        if not sets:
            sys.exit(f"plot_field.py: {path} lists no data set")
        path = os.path.join(os.path.dirname(path), sets[-1 if last else 0].get("file"))
    reader = (vtk.vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
              else vtk.vtkXMLUnstructuredGridReader())
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def main():
    args = [a for a in sys.argv[1:] if a != "--last"]
    if len(args) < 3:
        sys.exit(__doc__)
    vtu, field, png = args[:3]
    title = args[3] if len(args) > 3 else field
    grid = read(vtu, "--last" in sys.argv)
    points = vtk_to_numpy(grid.GetPoints().GetData())
    array = grid.GetPointData().GetArray(field)
    if array is None:
        sys.exit(f"plot_field.py: no point field '{field}' in {vtu}")
    values = vtk_to_numpy(array)
    triangles = []
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        q = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        p = round(math.sqrt(len(q))) - 1
        if len(q) == 4:  # VTK quad: counter-clockwise
            triangles += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
        elif p >= 1 and (p + 1) ** 2 == len(q):  # Lagrange quadrilateral of order p
            at = lambda i, j: q[lagrange_index(i, j, p)]  # noqa: E731
            for j in range(p):
                for i in range(p):
                    triangles += [[at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                                  [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
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
