// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Defaults.h
 * @brief The defaults that the core, the filters and the examples share, each written once.
 *
 * The filters' constructors and the core's option structures take their defaults from here; the
 * ParaView XML repeats them for the GUI and Testing/ParaView checks that it agrees.
 */
#ifndef spectral_Defaults_h
#define spectral_Defaults_h

namespace spectral
{
/// The number of harmonics computed when none is asked for.
constexpr int DefaultNumberOfHarmonics = 100;
/// The neighbours of each point that the point-cloud Laplacian triangulates (Sharp and Crane's
/// choice; Operators/PointCloud.h).
constexpr int DefaultNumberOfNeighbors = 30;
/// The low-pass cutoff as a fraction of the highest computed frequency sqrt(lambda_{m-1})
/// (FrequencyUnits::FractionOfHighest in Filtering/Transfer.h): the default of
/// vtkManifoldHarmonicSmoothing's CutoffFraction and of vtkSpectralFilter's Cutoff. On a surface
/// the number of harmonics below omega grows like omega^2 (Weyl), so 0.5 keeps about the lowest
/// quarter of the computed harmonics: a visible smoothing that keeps the shape, on any model at
/// any scale and for any number of harmonics (an absolute cutoff collapses a small model to its
/// centroid and leaves a large one unchanged).
constexpr double DefaultCutoffFraction = 0.5;
/// The upper band edge (band filters) in the same units: the highest computed frequency.
constexpr double DefaultUpperCutoffFraction = 1.0;
/// The functional map's first size k (FunctionalMapOptions::InitialSize, Filtering/FunctionalMap.h):
/// the descriptor-based estimate. Low frequencies are what descriptors and the commutativity
/// with the Laplacians determine well (Ovsjanikov et al. 2012 and ZoomOut start at 20 to 30).
constexpr int DefaultFunctionalMapInitialSize = 30;
/// Its final size after the ZoomOut refinement (clamped to the harmonics both bases have):
/// the default number of harmonics of a basis.
constexpr int DefaultFunctionalMapFinalSize = DefaultNumberOfHarmonics;
/// The growth of k per ZoomOut iteration (Melzi et al. 2019 use 1).
constexpr int DefaultZoomOutStep = 1;
/// The points of each shape the ZoomOut iterations run on (farthest-point samples) when a
/// shape has more: each iteration's nearest-neighbour search costs O(samples^2 k) instead of
/// O(n1 n2 k), and the final point map is on every point. pyFM subsamples likewise. Measured
/// on 13,536 and 19,942 points (TestFunctionalMap LargeScansWithDefaults): 2000 samples 7.8 s
/// and 0.32% of the diameter, 3000 samples 14.2 s and 0.28%.
constexpr int DefaultZoomOutSamples = 2000;
/// The wave kernel energies of the functional map's descriptors.
constexpr int DefaultNumberOfMapDescriptors = 50;
/// The weight of the commutativity with the Laplacians relative to descriptor preservation
/// (each term divided by its own scale, FunctionalMap.h).
constexpr double DefaultCommutativityWeight = 0.1;
/// The weight of the orientation term (FunctionalMapOptions::OrientationTerm) relative to
/// descriptor preservation: 0.1 kept the right map of a bunny against its 50% decimation (0.83%
/// of the diagonal, as without the term) and gave the mirror one with the target turned over;
/// at 1 the term outweighed the descriptors (13%).
constexpr double DefaultOrientationWeight = 0.1;
/// The weight of the landmark descriptors relative to the other descriptors.
constexpr double DefaultLandmarkWeight = 1.0;
} // namespace spectral

#endif
