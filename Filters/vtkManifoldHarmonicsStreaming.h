// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsStreaming.h
 * @brief Private: what vtkManifoldHarmonicSmoothing's STREAMED storage hands its internal
 *        vtkManifoldHarmonicBasis (SolveStreamed): the basis streams into a
 *        spectral::StreamedFilter (Spectral/Streaming.h) of the input's point coordinates, with
 *        the basis filter's mesh, seams, settings and errors, and is never written.
 */
#ifndef vtkManifoldHarmonicsStreaming_h
#define vtkManifoldHarmonicsStreaming_h

#include "vtkManifoldHarmonicBasis.h"

#include "Spectral/Streaming.h"

/// A streamed low pass of the input's point coordinates.
struct vtkManifoldHarmonicBasis::StreamRequest
{
  /// The filter's design (gains and re-injection gain), given the spectrum before any harmonic.
  spectral::StreamedDesign Design;
  /// Set by SolveStreamed: the filtered coordinates of every input point (n by 3).
  spectral::RowMatrix Filtered;
};

#endif
