# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""A denoised point cloud: the bunny's points without its triangles, noisy, then low-passed.

Usage: pvpython cloud_demo.py MESH OUTPUT_DIR [HARMONICS] [--random-directions]
       (or python3 with build/env.sh sourced)

Takes the points of MESH (Testing/Data/bunny.ply) without its cells (a point cloud), moves each
along the surface normal by a Gaussian amount of RMS 0.5 mean nearest-neighbour spacings (a
scanner's depth error; fixed seed; the triangles give the normals and are then dropped; with
--random-directions, by 0.5 spacings along random directions instead), computes
HARMONICS (default 300) harmonics of the noisy cloud's point-cloud Laplacian with Manifold
Harmonic Basis, low-passes the coordinates (Manifold Harmonic Transform + Spectral Filter, the
lowest 80% of the computed frequencies kept), prints the RMS distance of the noisy and of the
denoised points to the clean surface (the bunny's triangles; in mean spacings; an error unless
denoising divides it by REDUCTION) and writes OUTPUT_DIR/denoised-cloud.png: the noisy and the denoised cloud, same camera.
"""

import math
import os
import sys

from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import mutable, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellLocator, vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkFiltersCore import vtkGlyph3D, vtkPolyDataNormals
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (text rendering)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (registers the OpenGL back end)

from manifoldharmonics import (vtkManifoldHarmonicBasis, vtkManifoldHarmonicTransform,
                               vtkSpectralFilter)

import numpy as np

NOISE = 0.5  # RMS of the noise along the normals, in mean nearest-neighbour spacings
SEED = 25
# The least noise reduction accepted (measured here: 1.76 for noise along the normals, 1.66
# along random directions, whose tangential part only moves points along the surface).
REDUCTION = 1.5


def mean_spacing(points):
    """The mean distance from each point to its nearest other point (brute force)."""
    best = np.full(len(points), np.inf)
    for start in range(0, len(points), 512):
        block = points[start:start + 512]
        d = np.linalg.norm(block[:, None, :] - points[None, :, :], axis=2)
        d[np.arange(len(block)), np.arange(start, start + len(block))] = np.inf
        best[start:start + len(block)] = d.min(axis=1)
    return float(best.mean())


def cloud(points):
    """A vtkPolyData with these points and no cells: a point cloud for the filters."""
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.ascontiguousarray(points), deep=True))
    data = vtkPolyData()
    data.SetPoints(vtk_points)
    return data


def spheres(points, radius, color):
    """An actor drawing each point as a small sphere."""
    source = vtkSphereSource()
    source.SetRadius(radius)
    source.SetThetaResolution(8)
    source.SetPhiResolution(6)
    glyphs = vtkGlyph3D()
    glyphs.SetInputData(cloud(points))
    glyphs.SetSourceConnection(source.GetOutputPort())
    glyphs.ScalingOff()
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(glyphs.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*color)
    return actor


def main():
    random_directions = "--random-directions" in sys.argv
    if random_directions:
        sys.argv.remove("--random-directions")
    if len(sys.argv) < 3:
        print("usage: cloud_demo.py MESH OUTPUT_DIR [HARMONICS]")
        return 2
    output = sys.argv[2]
    harmonics = int(sys.argv[3]) if len(sys.argv) > 3 else 300
    os.makedirs(output, exist_ok=True)
    reader = vtkPLYReader()
    reader.SetFileName(sys.argv[1])
    reader.Update()
    clean = vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)
    if len(clean) < 2:
        print("ERROR: %s has no points" % sys.argv[1])
        return 1
    normals = vtkPolyDataNormals()
    normals.SetInputData(reader.GetOutput())
    normals.SplittingOff()
    normals.ComputePointNormalsOn()
    normals.Update()
    normal = vtk_to_numpy(normals.GetOutput().GetPointData().GetNormals()).astype(np.float64)
    if len(normal) != len(clean):
        print("ERROR: %s needs triangles to give its points normals" % sys.argv[1])
        return 1
    spacing = mean_spacing(clean)
    rng = np.random.default_rng(SEED)
    if random_directions:
        directions = rng.normal(size=clean.shape)
        noisy = clean + NOISE * spacing * directions / np.linalg.norm(directions, axis=1)[:, None]
    else:
        noisy = clean + NOISE * spacing * rng.normal(size=(len(clean), 1)) * normal

    basis = vtkManifoldHarmonicBasis()
    basis.SetInputData(cloud(noisy))
    basis.SetNumberOfHarmonics(harmonics)
    basis.Update()
    values = basis.GetOutput().GetFieldData().GetArray(
        vtkManifoldHarmonicBasis.EigenvaluesArrayName())
    if values is None:
        print("ERROR: the basis of the noisy cloud could not be computed")
        return 1
    m = values.GetNumberOfTuples()
    cutoff = math.sqrt(values.GetValue((4 * m) // 5))
    transform = vtkManifoldHarmonicTransform()
    transform.SetInputConnection(basis.GetOutputPort())
    lowpass = vtkSpectralFilter()
    lowpass.SetInputConnection(transform.GetOutputPort())
    lowpass.SetFilterKindToLowPass()
    lowpass.SetCutoffUnitsToAbsoluteFrequency()
    lowpass.SetCutoff(cutoff)
    lowpass.SetTransition(0.3)
    lowpass.Update()
    denoised = vtk_to_numpy(lowpass.GetOutput().GetPoints().GetData()).astype(np.float64)

    # The distance of each point to the clean surface (the bunny's triangles): what denoising is
    # for. (Points also drift along the surface; that changes the sampling, not the shape.)
    locator = vtkCellLocator()
    locator.SetDataSet(reader.GetOutput())
    locator.BuildLocator()

    def rms(points):
        closest = [0.0, 0.0, 0.0]
        cell, sub, distance2 = mutable(0), mutable(0), mutable(0.0)
        total = 0.0
        for p in points:
            locator.FindClosestPoint(p.tolist(), closest, cell, sub, distance2)
            total += float(distance2)
        return math.sqrt(total / len(points)) / spacing

    before, after = rms(noisy), rms(denoised)
    print("point cloud: %d points of %s, no cells, mean nearest-neighbour spacing %.4g"
          % (len(clean), os.path.basename(sys.argv[1]), spacing))
    print("  noise: %.2f spacings %s (seed %d)" % (
        NOISE, "along random directions" if random_directions
        else "RMS along the normals (Gaussian)", SEED))
    print("  low-pass: %d harmonics, %d neighbours, cutoff omega = %.3g (lambda_%d)"
          % (m, basis.GetNumberOfNeighbors(), cutoff, (4 * m) // 5))
    print("  RMS distance to the clean surface: noisy %.3f, denoised %.3f spacings (%.2fx smaller)"
          % (before, after, before / after if after > 0 else float("inf")))
    if not after * REDUCTION <= before:
        print("ERROR: denoising did not divide the RMS distance to the clean surface by %g"
              % REDUCTION)
        return 1

    # Side by side, same camera: the noisy cloud | the denoised cloud.
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(1000, 500)
    camera = None
    for i, (points, title, color) in enumerate((
            (noisy, "noisy (%.2f spacings RMS)" % before, (0.80, 0.35, 0.25)),
            (denoised, "manifold harmonics low-pass (%.2f)" % after, (0.25, 0.45, 0.80)))):
        renderer = vtkRenderer()
        renderer.SetViewport(0.5 * i, 0.0, 0.5 * (i + 1), 1.0)
        renderer.SetBackground(1.0, 1.0, 1.0)
        renderer.AddActor(spheres(points, 0.3 * spacing, color))
        text = vtkTextActor()
        text.SetInput(title)
        text.GetTextProperty().SetColor(0.1, 0.1, 0.1)
        text.GetTextProperty().SetFontSize(18)
        text.SetPosition(10, 10)
        renderer.AddActor2D(text)
        if camera is None:
            renderer.ResetCamera()
            camera = renderer.GetActiveCamera()
            camera.Zoom(1.3)
        else:
            renderer.SetActiveCamera(camera)
        window.AddRenderer(renderer)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    path = os.path.join(output, "denoised-cloud.png")
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("wrote " + path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
