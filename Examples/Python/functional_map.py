# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""Correspondence between two scans of one object and a label carried from one to the other.

Usage (pvpython or python3, with the build tree's env.sh sourced):

    pvpython functional_map.py input.(ply|obj|stl|vtp) output.vtp [--harmonics M]
        [--reduction R] [--source-output source.vtp]

The input is the first scan (the SOURCE). The second scan (the TARGET) is made from it: a
coarser triangulation (vtkDecimatePro keeps a fraction 1 - R of the points, R = 0.5 by default)
moved rigidly, as a scanner at another resolution and position would give it. The source gets an
integer label, `Part` (1 on the top fifth of the object along its longest axis, 0 elsewhere).
vtkFunctionalMap (the ParaView filter "Functional Map": Input = target, Source = source) finds
for each target point its source point (`CorrespondingPointIds`) with its default settings and
carries `Part` to the target through that point map, exactly (an integer array). Writes the
target with `CorrespondingPointIds` and `Part`, prints the mean distance between matched points
and their true counterparts (relative to the object's size) and the share of target points
whose transferred label is their true one. Run by CTest on Testing/Data/bunny.ply.
"""

import argparse
import math
import os
import sys

from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkDecimatePro, vtkTriangleFilter
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

from manifoldharmonics import vtkFunctionalMap

READERS = {".ply": vtkPLYReader, ".obj": vtkOBJReader, ".stl": vtkSTLReader,
           ".vtp": vtkXMLPolyDataReader}


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1, not %d" % value)
    return value


def reduction(text):
    value = float(text)
    if not 0.0 <= value < 1.0:
        raise argparse.ArgumentTypeError("must be in [0, 1), not %s" % text)
    return value


def read(path):
    reader = READERS[os.path.splitext(path)[1].lower()]()
    reader.SetFileName(path)
    clean = vtkCleanPolyData()  # one point per position, so that both scans share positions
    clean.SetInputConnection(reader.GetOutputPort())
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(clean.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def label_top(mesh, axis, threshold):
    """The integer label Part: 1 above `threshold` along `axis`, 0 below."""
    part = vtkIntArray()
    part.SetName("Part")
    for i in range(mesh.GetNumberOfPoints()):
        part.InsertNextValue(1 if mesh.GetPoint(i)[axis] > threshold else 0)
    return part


def write(mesh, path):
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetDataModeToBinary()  # inline binary: ParaView 5.11 reads it back
    writer.SetInputData(mesh)
    if not writer.Write():
        sys.exit("cannot write %s" % path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--harmonics", type=positive_int, default=100,
                        help="harmonics of each scan's basis (default 100)")
    parser.add_argument("--reduction", type=reduction, default=0.5,
                        help="share of the points the second scan lacks (default 0.5)")
    parser.add_argument("--source-output", help="also write the source scan with Part")
    args = parser.parse_args()

    source = read(args.input)
    bounds = source.GetBounds()
    extents = [bounds[2 * d + 1] - bounds[2 * d] for d in range(3)]
    axis = extents.index(max(extents))
    threshold = bounds[2 * axis + 1] - 0.2 * extents[axis]
    source.GetPointData().AddArray(label_top(source, axis, threshold))

    # The second scan: fewer points (a subset of the first's, so the truth is known), moved.
    decimate = vtkDecimatePro()
    decimate.SetInputData(source)
    decimate.SetTargetReduction(args.reduction)
    decimate.PreserveTopologyOn()
    decimate.Update()
    coarse = decimate.GetOutput()
    truth = coarse.GetPoints().GetData().NewInstance()
    truth.DeepCopy(coarse.GetPoints().GetData())  # where each target point really is
    coarse.GetPointData().Initialize()  # the target carries no label of its own
    motion = vtkTransform()
    motion.RotateWXYZ(40.0, 1.0, 2.0, 0.5)
    motion.Translate(0.3 * extents[0], -0.2 * extents[1], 0.1 * extents[2])
    move = vtkTransformPolyDataFilter()
    move.SetInputData(coarse)
    move.SetTransform(motion)
    move.Update()
    target = move.GetOutput()

    fmap = vtkFunctionalMap()
    fmap.SetInputData(target)
    fmap.SetSourceData(source)
    fmap.SetNumberOfHarmonics(args.harmonics)
    fmap.Update()
    result = fmap.GetOutput()
    ids = result.GetPointData().GetArray(vtkFunctionalMap.CorrespondingPointIdsArrayName())
    part = result.GetPointData().GetArray("Part")
    if ids is None or part is None:
        sys.exit("the functional map failed (see the errors above)")

    size = math.sqrt(sum(e * e for e in extents))
    error = 0.0
    right = 0
    for j in range(result.GetNumberOfPoints()):
        where = truth.GetTuple3(j)
        error += math.dist(source.GetPoint(ids.GetValue(j)), where)
        right += part.GetValue(j) == (1 if where[axis] > threshold else 0)
    n = result.GetNumberOfPoints()
    print("source %d points, target %d points, map %d x %d" % (
        source.GetNumberOfPoints(), n, fmap.GetOutputDataObject(1).GetNumberOfRows(),
        fmap.GetOutputDataObject(1).GetNumberOfColumns()))
    print("mean distance to the true point: %.2f%% of the object's size" % (100.0 * error / n / size))
    print("label Part right on %.1f%% of the target points" % (100.0 * right / n))
    write(result, args.output)
    if args.source_output:
        write(source, args.source_output)
    print("wrote %s" % args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
