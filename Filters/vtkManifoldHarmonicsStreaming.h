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
  /// The filter's design (the filter and its re-injection gain), given the highest eigenvalue
  /// before any harmonic.
  spectral::StreamedDesign Design;
  /// Set by SolveStreamed: the filtered coordinates of every input point (n by 3).
  spectral::RowMatrix Filtered;
  /// Set by SolveStreamed: the eigenvalues the stream knows (ascending, mesh units): those of
  /// the harmonics it solved, and the highest.
  spectral::Vector Eigenvalues;
};

#endif
