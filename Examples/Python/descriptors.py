# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""Spectral shape analysis of a surface: heat kernel signature, biharmonic distance, ShapeDNA.

Usage (pvpython or python3, with the build tree's env.sh sourced):

    pvpython descriptors.py input.(ply|obj|stl|vtp) output.vtp [--harmonics M] [--time T]
        [--source ID] [--shapedna shapedna.csv] [--picture hks.png]

Writes the mesh with the point arrays HeatKernelSignature (the default 16 times and T, if
given), WaveKernelSignature, GlobalPointSignature and SpectralDistance (biharmonic, from point
ID), prints where the signature at the smallest time is highest (the tips of the shape), writes
the ShapeDNA table as CSV and, with --picture, renders the signature at the smallest time.
Run by CTest on Testing/Data/bunny.ply.
"""

import argparse
import math
import os
import sys

from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

from manifoldharmonics import vtkManifoldHarmonicBasis, vtkSpectralDescriptors

READERS = {".ply": vtkPLYReader, ".obj": vtkOBJReader, ".stl": vtkSTLReader,
           ".vtp": vtkXMLPolyDataReader}


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1, not %d" % value)
    return value


def positive_float(text):
    value = float(text)
    if not value > 0.0 or math.isinf(value):
        raise argparse.ArgumentTypeError("must be a finite number > 0, not %s" % text)
    return value


def render(mesh, array, component, path):
    """The mesh coloured by one component of a point array, written as a PNG."""
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction,
                                             vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                             vtkWindowToImageFilter)
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (registers the OpenGL back end)

    values = mesh.GetPointData().GetArray(array)
    # The signature is large at tips: log scale, clipped to the 2nd-98th percentile.
    logs = sorted(math.log(values.GetComponent(i, component))
                  for i in range(values.GetNumberOfTuples()))
    low, high = logs[len(logs) // 50], logs[-1 - len(logs) // 50]
    shown = vtkDoubleArray()
    shown.SetName("shown")
    shown.SetNumberOfTuples(values.GetNumberOfTuples())
    for i in range(values.GetNumberOfTuples()):
        shown.SetValue(i, math.log(values.GetComponent(i, component)))
    view = mesh.NewInstance()
    view.ShallowCopy(mesh)
    view.GetPointData().AddArray(shown)
    normals = vtkPolyDataNormals()
    normals.SetInputData(view)
    normals.SplittingOff()
    lut = vtkColorTransferFunction()
    lut.SetColorSpaceToDiverging()
    lut.AddRGBPoint(low, 0.23, 0.30, 0.75)
    lut.AddRGBPoint(0.5 * (low + high), 0.87, 0.87, 0.87)
    lut.AddRGBPoint(high, 0.71, 0.02, 0.15)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("shown")
    mapper.SetLookupTable(lut)
    mapper.UseLookupTableScalarRangeOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetSpecular(0.2)
    renderer = vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(800, 700)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    camera = renderer.GetActiveCamera()
    camera.Azimuth(30)
    camera.Elevation(10)
    camera.Zoom(1.4)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--harmonics", type=positive_int, default=200)
    parser.add_argument("--time", type=positive_float, default=None,
                        help="an extra heat kernel time after the 16 default ones")
    parser.add_argument("--source", type=int, default=0, help="source point of the distance")
    parser.add_argument("--shapedna", default=None, help="CSV file for the ShapeDNA table")
    parser.add_argument("--picture", default=None, help="PNG of the HKS at the smallest time")
    args = parser.parse_args()
    extension = os.path.splitext(args.input)[1].lower()
    if extension not in READERS:
        parser.error("input must be one of %s" % ", ".join(sorted(READERS)))
    if os.path.splitext(args.output)[1].lower() != ".vtp":
        parser.error("output must be a .vtp file")

    reader = READERS[extension]()
    reader.SetFileName(args.input)
    basis = vtkManifoldHarmonicBasis()
    basis.SetInputConnection(reader.GetOutputPort())
    basis.SetNumberOfHarmonics(args.harmonics)
    basis.Update()
    descriptors = vtkSpectralDescriptors()
    descriptors.SetInputConnection(basis.GetOutputPort())
    descriptors.ComputeWaveKernelSignatureOn()
    descriptors.ComputeGlobalPointSignatureOn()
    descriptors.ComputeSpectralDistanceOn()
    descriptors.SetDistanceKindToBiharmonic()
    descriptors.SetSourcePoint(args.source)
    descriptors.Update()
    output = descriptors.GetOutput()
    if output.GetNumberOfPoints() == 0:
        print("ERROR: the descriptors failed (see the messages above)")
        return 1
    times = output.GetFieldData().GetArray(vtkSpectralDescriptors.HeatKernelTimesArrayName())
    if args.time is not None:
        descriptors.RemoveAllHeatKernelTimes()
        for j in range(times.GetNumberOfTuples()):
            descriptors.AddHeatKernelTime(times.GetValue(j))
        descriptors.AddHeatKernelTime(args.time)
        descriptors.Update()
        output = descriptors.GetOutput()
        times = output.GetFieldData().GetArray(vtkSpectralDescriptors.HeatKernelTimesArrayName())
    print("heat kernel times: %s" % " ".join("%.4g" % times.GetValue(j)
                                             for j in range(times.GetNumberOfTuples())))

    # Where the signature at the smallest time is highest: the 2% of points at the tips.
    hks = output.GetPointData().GetArray(vtkSpectralDescriptors.HeatKernelSignatureArrayName())
    n = output.GetNumberOfPoints()
    bounds = output.GetBounds()
    ranked = sorted(range(n), key=lambda i: -hks.GetComponent(i, 0))[:max(1, n // 50)]
    print("HKS(t = %.4g): range [%.4g, %.4g]; its highest 2%% of the points (%d) lie at" % (
        times.GetValue(0), min(hks.GetComponent(i, 0) for i in range(n)),
        hks.GetComponent(ranked[0], 0), len(ranked)))
    for i in ranked[:8]:
        p = output.GetPoint(i)
        print("  point %5d: (%s) of the bounding box" % (i, ", ".join(
            "%.2f" % ((p[a] - bounds[2 * a]) / (bounds[2 * a + 1] - bounds[2 * a]))
            for a in range(3))))
    distance = output.GetPointData().GetArray("SpectralDistance")
    print("biharmonic distance from point %d: largest %.4g" % (
        args.source, distance.GetRange()[1]))
    table = descriptors.GetShapeDNAOutput()
    scaled = table.GetColumnByName(vtkSpectralDescriptors.ScaledEigenvalueColumnName())
    print("ShapeDNA (lambda * area), first 6: %s" % " ".join(
        "%.4g" % scaled.GetValue(k) for k in range(min(6, scaled.GetNumberOfTuples()))))

    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(args.output)
    writer.SetInputData(output)
    writer.SetDataModeToBinary()
    writer.Write()
    print("wrote %s" % args.output)
    if args.shapedna:
        with open(args.shapedna, "w") as csv:
            columns = [table.GetColumn(c) for c in range(table.GetNumberOfColumns())]
            csv.write(",".join(column.GetName() for column in columns) + "\n")
            for k in range(table.GetNumberOfRows()):
                csv.write(",".join(repr(column.GetValue(k)) for column in columns) + "\n")
        print("wrote %s" % args.shapedna)
    if args.picture:
        render(output, vtkSpectralDescriptors.HeatKernelSignatureArrayName(), 0, args.picture)
        print("wrote %s" % args.picture)
    return 0


if __name__ == "__main__":
    sys.exit(main())
