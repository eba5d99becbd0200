# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""vtkManifoldHarmonicBasis from Python: output arrays, spectrum of a sphere, orthonormality."""

import sys

import numpy as np
from vtkmodules.vtkFiltersCore import vtkCleanPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.util.numpy_support import vtk_to_numpy

from manifoldharmonics import vtkManifoldHarmonicBasis


def main():
    sphere = vtkSphereSource()
    sphere.SetRadius(1.0)
    sphere.SetThetaResolution(40)
    sphere.SetPhiResolution(40)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(sphere.GetOutputPort())

    m = 9
    basis = vtkManifoldHarmonicBasis()
    basis.SetInputConnection(clean.GetOutputPort())
    basis.SetNumberOfHarmonics(m)
    assert basis.GetMassMatrix() == vtkManifoldHarmonicBasis.LUMPED
    basis.Update()

    output = basis.GetOutput()
    n = output.GetNumberOfPoints()
    points = output.GetPointData()
    H = vtk_to_numpy(points.GetArray(vtkManifoldHarmonicBasis.HarmonicsArrayName()))
    D = vtk_to_numpy(points.GetArray(vtkManifoldHarmonicBasis.MassArrayName()))
    lam = vtk_to_numpy(
        output.GetFieldData().GetArray(vtkManifoldHarmonicBasis.EigenvaluesArrayName()))

    assert H.shape == (n, m), H.shape
    assert D.shape == (n,), D.shape
    assert lam.shape == (m,), lam.shape
    assert np.all(np.diff(lam) >= 0), lam
    assert abs(lam[0]) < 1e-8, lam
    # Unit sphere: 0, 2 (x3), 6 (x5), up to the discretization error of a UV sphere.
    assert np.allclose(lam[1:4], 2.0, rtol=0.03), lam
    assert np.allclose(lam[4:9], 6.0, rtol=0.03), lam
    gram = H.T @ (D[:, None] * H)
    error = np.abs(gram - np.eye(m)).max()
    assert error < 1e-10, error
    return 0


if __name__ == "__main__":
    sys.exit(main())
