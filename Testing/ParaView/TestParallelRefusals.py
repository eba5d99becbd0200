# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""What the basis filter says when several processes hold what the built-in solver cannot solve.

Run as `mpiexec -n 2 pvbatch --symmetric TestParallelRefusals.py` (every process runs it):

- a point cloud split over the processes: an error on every process that names the point cloud
  (neither solver takes a distributed cloud), and an empty output;
- a tetrahedral box split over the processes: an error on every process that points to the
  SLEPc solver, and an empty output;
- an empty vtkPolyData on every process: the serial warning that there is nothing to solve,
  from process 0 alone, and the input passed through, with no error.

Each process prints "PASS (process r)", or "ERROR: ..." for each failed check (which CTest's fail
expression catches) and raises.
"""

import sys

import numpy as np
from paraview import servermanager  # noqa: F401 (initializes MPI and the global controller)
from paraview.vtk.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkCommand, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, vtkPolyData, vtkUnstructuredGrid
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

import manifoldharmonics as mh


class Messages:
    """The texts of the errors and warnings of one VTK object."""

    def __init__(self):
        self.errors = []
        self.warnings = []


def observed(algorithm):
    """The Messages of `algorithm` from now on."""
    messages = Messages()

    @calldata_type(VTK_STRING)
    def on_error(caller, event, text):
        messages.errors.append(text)

    @calldata_type(VTK_STRING)
    def on_warning(caller, event, text):
        messages.warnings.append(text)

    algorithm.AddObserver(vtkCommand.ErrorEvent, on_error)
    algorithm.AddObserver(vtkCommand.WarningEvent, on_warning)
    return messages


def run(mesh, harmonics=10):
    basis = mh.vtkManifoldHarmonicBasis()
    basis.SetNumberOfHarmonics(harmonics)
    messages = observed(basis)
    observed(basis.GetExecutive())  # its "returned failure for request", expected here
    basis.SetInputData(mesh)
    basis.Update()
    return basis.GetOutputDataObject(0), messages


def cloud(rank, size):
    """This process's share of 2000 points on the unit sphere, without cells."""
    rng = np.random.default_rng(7)
    xyz = rng.normal(size=(2000, 3))
    xyz /= np.linalg.norm(xyz, axis=1)[:, None]
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(xyz[rank::size]), deep=1))
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    return mesh


def tetrahedra(rank):
    """A slab of Kuhn tetrahedra of a 4 x 4 x 4 cube, x in [rank, rank + 1]."""
    grid = vtkUnstructuredGrid()
    points = vtkPoints()
    index = {}
    for i in range(2):
        for j in range(5):
            for k in range(5):
                index[(i, j, k)] = points.InsertNextPoint(rank + i, j, k)
    grid.SetPoints(points)
    paths = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
    for j in range(4):
        for k in range(4):
            for path in paths:
                corner = [0, j, k]
                ids = [index[tuple(corner)]]
                for axis in path:
                    corner[axis] += 1
                    ids.append(index[tuple(corner)])
                grid.InsertNextCell(VTK_TETRA, 4, ids)
    return grid


def main():
    controller = vtkMultiProcessController.GetGlobalController()
    rank = controller.GetLocalProcessId()
    size = controller.GetNumberOfProcesses()
    failures = []

    def check(condition, what):
        if not condition:
            failures.append(what)

    if size < 2:
        failures.append("run on at least 2 processes, not %d" % size)

    output, messages = run(cloud(rank, size))
    check(len(messages.errors) == 1 and "point cloud" in messages.errors[0]
          and "neither solver" in messages.errors[0],
          "a distributed cloud: errors %s" % messages.errors)
    check(output.GetNumberOfPoints() == 0, "a distributed cloud: the output is not empty")

    output, messages = run(tetrahedra(rank))
    check(len(messages.errors) == 1 and "Choose Solver SLEPc" in messages.errors[0],
          "a distributed volume: errors %s" % messages.errors)
    check(output.GetNumberOfPoints() == 0, "a distributed volume: the output is not empty")

    output, messages = run(vtkPolyData())
    expected = ["in any process's piece" in text for text in messages.warnings]
    check(not messages.errors, "empty pieces: errors %s" % messages.errors)
    check(sum(expected) == (1 if rank == 0 else 0),
          "empty pieces: warnings on process %d: %s" % (rank, messages.warnings))

    for failure in failures:
        print("ERROR: process %d: %s" % (rank, failure))
    sys.stdout.flush()
    if failures:
        raise RuntimeError("%d check(s) failed on process %d" % (len(failures), rank))
    print("PASS (process %d)" % rank)


if __name__ == "__main__":
    # No sys.exit: under MPI it would end process 0 before pvbatch releases the others. A failed
    # check raises, which makes pvbatch fail.
    main()
