# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""The SLEPc solver in a serial run: what it does with the built-in solver's memory settings.

MemoryLimit does not apply to it (no memory estimate is checked): a warning says so, and the
basis is computed; the storage report is IN_MEMORY (each process keeps its own rows), not
AUTOMATIC as if nothing had been computed. Without SLEPc in the build, it checks the error.
"""

import sys

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkFiltersCore import vtkCleanPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource

from manifoldharmonics import vtkManifoldHarmonicBasis


def main():
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(30)
    sphere.SetPhiResolution(30)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(sphere.GetOutputPort())
    basis = vtkManifoldHarmonicBasis()
    basis.SetInputConnection(clean.GetOutputPort())
    basis.SetNumberOfHarmonics(20)
    basis.SetSolverToSlepc()
    basis.SetMemoryLimit(1.0)  # MiB: far below the basis alone
    messages = {"warnings": [], "errors": []}

    @calldata_type(VTK_STRING)
    def on_warning(caller, event, text):
        messages["warnings"].append(text)

    @calldata_type(VTK_STRING)
    def on_error(caller, event, text):
        messages["errors"].append(text)

    basis.AddObserver(vtkCommand.WarningEvent, on_warning)
    basis.AddObserver(vtkCommand.ErrorEvent, on_error)
    basis.GetExecutive().AddObserver(vtkCommand.ErrorEvent, on_error)
    basis.Update()
    if not vtkManifoldHarmonicBasis.HasSlepc():
        assert any("has no SLEPc solver" in text for text in messages["errors"]), messages
        print("no SLEPc in this build: refused as expected")
        return 0
    assert not messages["errors"], messages["errors"]
    assert basis.GetOutput().GetNumberOfPoints() > 0
    assert any("does not apply to the SLEPc solver" in text for text in messages["warnings"]), (
        messages["warnings"])
    assert basis.GetStorageUsed() == vtkManifoldHarmonicBasis.IN_MEMORY, basis.GetStorageUsed()
    print("SLEPc: MemoryLimit warned, storage", basis.GetStorageReason())
    return 0


if __name__ == "__main__":
    sys.exit(main())
