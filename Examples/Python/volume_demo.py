# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""A volume harmonic: the harmonics of a tetrahedral unit ball, shown on three slices.

Usage: pvpython volume_demo.py OUTPUT_DIR [N]   (or python3 with build/env.sh sourced)

Builds the unit ball from a cube of N^3 cells (default 24), each split into six tetrahedra, mapped
radially onto the ball (an unstructured grid), computes its 12 lowest Neumann harmonics with
Manifold Harmonic Basis, prints the eigenvalues next to the analytic ones (an error beyond 5%) (squares of the zeros
of the derivatives of the spherical Bessel functions, for l = 1 and l = 2) and writes
OUTPUT_DIR/volume-harmonic.png: Phi_5 (an l = 2 harmonic) on three orthogonal slices.
"""

import math
import os
import sys

from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, vtkCellArray, vtkPlane, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkCutter
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (registers the OpenGL back end)

from manifoldharmonics import vtkManifoldHarmonicBasis

import numpy as np


def tetrahedral_ball(n):
    """The cube [-1, 1]^3 of n^3 cells in Kuhn tetrahedra, mapped radially onto the unit ball."""
    axis = np.linspace(-1.0, 1.0, n + 1)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    norm = np.linalg.norm(points, axis=1)
    scale = np.where(norm > 0, np.abs(points).max(axis=1) / np.where(norm > 0, norm, 1), 0)
    points *= scale[:, None]

    def pid(i, j, k):
        return (k * (n + 1) + j) * (n + 1) + i

    i, j, k = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    i, j, k = i.ravel(), j.ravel(), k.ravel()
    tets = []
    for order in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
        step = [i.copy(), j.copy(), k.copy()]
        corners = [pid(*step)]
        for axis_index in order:
            step[axis_index] = step[axis_index] + 1
            corners.append(pid(*step))
        tets.append(np.column_stack(corners))
    tets = np.vstack(tets)
    grid = vtkUnstructuredGrid()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points, deep=True))
    grid.SetPoints(vtk_points)
    connectivity = np.hstack([np.full((len(tets), 1), 4), tets]).ravel()
    cells = vtkCellArray()
    cells.SetCells(len(tets), numpy_to_vtkIdTypeArray(connectivity.astype(np.int64), deep=True))
    grid.SetCells(VTK_TETRA, cells)
    return grid


def spherical_bessel_derivative_zero(l, guess):
    """The zero of j_l' near `guess`, by bisection on [guess - 0.5, guess + 0.5]."""
    def derivative(x):
        j = [math.sin(x) / x, math.sin(x) / x ** 2 - math.cos(x) / x]
        for m in range(1, l + 1):
            j.append((2 * m + 1) / x * j[m] - j[m - 1])
        return j[l - 1] - (l + 1) / x * j[l]
    lo, hi = guess - 0.5, guess + 0.5
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if (derivative(mid) < 0) == (derivative(lo) < 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    output = sys.argv[1] if len(sys.argv) > 1 else "demo-output"
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 24
    os.makedirs(output, exist_ok=True)
    basis = vtkManifoldHarmonicBasis()
    basis.SetInputData(tetrahedral_ball(n))
    basis.SetNumberOfHarmonics(12)
    basis.Update()
    data = basis.GetOutput()
    lam = data.GetFieldData().GetArray("ManifoldHarmonicsEigenvalues")
    exact = {1: spherical_bessel_derivative_zero(1, 2.08) ** 2,
             2: spherical_bessel_derivative_zero(2, 3.34) ** 2}
    print("volume harmonics of the unit ball: %d points, %d tetrahedra (%s)"
          % (data.GetNumberOfPoints(), data.GetNumberOfCells(), data.GetClassName()))
    failed = False
    for k in range(9):
        l = 0 if k == 0 else (1 if k < 4 else 2)
        print("  lambda_%d = %8.4f   analytic %8.4f (l = %d)"
              % (k, lam.GetValue(k), exact.get(l, 0.0), l))
        if l > 0 and abs(lam.GetValue(k) - exact[l]) > 0.05 * exact[l]:
            print("ERROR: lambda_%d is not within 5%% of the ball's" % k)
            failed = True
    if failed:
        return 1

    # Phi_5 as the active scalars, cut by three orthogonal planes through the centre.
    phi = vtk_to_numpy(data.GetPointData().GetArray("ManifoldHarmonics"))[:, 5].copy()
    scalars = numpy_to_vtk(phi, deep=True)
    scalars.SetName("Phi_5")
    data.GetPointData().SetScalars(scalars)
    top = float(np.abs(phi).max())
    colors = vtkColorTransferFunction()
    colors.SetColorSpaceToDiverging()
    colors.AddRGBPoint(-top, 0.23, 0.30, 0.75)
    colors.AddRGBPoint(0.0, 0.87, 0.87, 0.87)
    colors.AddRGBPoint(top, 0.71, 0.02, 0.15)
    renderer = vtkRenderer()
    renderer.SetAmbient(1.0, 1.0, 1.0)
    renderer.SetBackground(1.0, 1.0, 1.0)
    for normal in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
        plane = vtkPlane()
        plane.SetNormal(*normal)
        cutter = vtkCutter()
        cutter.SetCutFunction(plane)
        cutter.SetInputData(data)
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(cutter.GetOutputPort())
        mapper.SetLookupTable(colors)
        mapper.SetScalarRange(-top, top)
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetAmbient(0.35)
        actor.GetProperty().SetDiffuse(0.7)
        renderer.AddActor(actor)
    surface = vtkGeometryFilter()
    surface.SetInputData(data)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    mapper.ScalarVisibilityOff()
    shell = vtkActor()
    shell.SetMapper(mapper)
    shell.GetProperty().SetRepresentationToWireframe()
    shell.GetProperty().SetColor(0.3, 0.3, 0.3)
    shell.GetProperty().SetOpacity(0.06)
    renderer.AddActor(shell)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(3.2, 2.4, 2.2)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCameraClippingRange()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(900, 700)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    path = os.path.join(output, "volume-harmonic.png")
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("wrote " + path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
