// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FunctionalMap.h
 * @brief Correspondence between two shapes by functional maps: the map between their spectral
 *        domains, its refinement (ZoomOut), the point map, attribute transfer and mode alignment.
 *
 * Conventions (those of Ovsjanikov et al. and of pyFM): shape 1 is the SOURCE, shape 2 the
 * TARGET, each with a D-orthonormal basis Phi (n by m, Phi^T D Phi = I, D the lumped mass).
 * The functional map C (k2 by k1) takes the spectral coefficients of a function on the source
 * to those of the same function carried to the target: a_target = C a_source. The point map
 * goes the other way: for each target point j, the source point i it corresponds to
 * (CorrespondingPointIds), i.e. the n2 by n1 matrix Pi with Pi(j, i) = 1, and Pi Phi1 ~ Phi2 C.
 *
 * The method:
 * 1. Descriptors (Descriptors.h): the wave kernel signature (Aubry et al. 2011) at
 *    NumberOfDescriptors energies, the same energies on both shapes (taken from the spectrum
 *    both bases share), each column divided by its D-norm, projected on the first InitialSize
 *    harmonics: A = Phi1^T D1 F1, B = Phi2^T D2 F2.
 * 2. The initial map (Ovsjanikov et al., "Functional Maps: A Flexible Representation of Maps
 *    Between Shapes", SIGGRAPH 2012): C minimizing
 *      DescriptorWeight ||C A - B||^2 / q + CommutativityWeight ||C Lambda1 - Lambda2 C||^2 / s
 *    (q the number of descriptor columns, s the sum of the (lambda2_i - lambda1_j)^2 over the
 *    k by k entries, which makes both terms free of units). The commutativity term is the sum of
 *    (lambda2_i - lambda1_j)^2 C_ij^2, diagonal in the entries of C, so the problem splits into
 *    one k by k symmetric system per row of C.
 * 3. Landmarks (pairs of a source and a target point) add descriptors: for each pair (p1, p2),
 *    the heat kernels k_t(p, x) = sum_k e^{-lambda_k t} phi_k(p) phi_k(x) at 16 times log-spaced
 *    over [1 / lambda_K, 1 / lambda_1] (lambda_1 the first non-zero eigenvalue, K the tenth
 *    harmonic after it or the last of InitialSize), whose coefficients e^{-lambda_k t} phi_k(p)
 *    need no work on the points: O(16 L k) for L landmarks, nothing per point. They are smooth
 *    at the scale of the tenth harmonic's wavelength, so a landmark a few edges from the exact
 *    point costs little (the wave kernel at the landmark, as pyFM uses, resolves the highest
 *    frequencies and was measured to fail with landmarks one edge off). Their weight is
 *    LandmarkWeight relative to all the other descriptors together. The refinement keeps them as
 *    hard constraints: each target landmark corresponds to its source landmark in every point
 *    map (free). One landmark off every symmetry axis tells a shape from its mirror image; two
 *    or three are safer, and landmarks that are images of each other by a symmetry of the shape
 *    do not break it.
 * 4. Refinement (Melzi et al., "ZoomOut: Spectral Upsampling for Efficient Shape
 *    Correspondence", ACM TOG 38(6), 2019): from k = InitialSize to FinalSize by ZoomOutStep,
 *    the point map of C (each target point j to the source point whose row of Phi1_k is nearest
 *    to row j of Phi2_k C), then the map of the next size C = Phi2_k'^T D2 Pi Phi1_k'. The last
 *    point map is that of the final C. On shapes of more than ZoomOutSamples points the
 *    iterations run on that many farthest-point samples of each (landmarks included), with
 *    the least-squares map of the samples (their Gram matrix solved for), and only the final
 *    point map is on every point (pyFM's subsampling).
 * 5. The orientation term (OrientationTerm; Ren, Poulenard, Ovsjanikov and Guibas,
 *    "Continuous and Orientation-preserving Correspondences via Functional Maps", ACM TOG 37(6),
 *    2018): for every tenth descriptor g (5 of the default 50), the operator
 *    f -> <grad f x grad g, n> in the basis, Q = Phi^T D O_g Phi (per triangle for the linear f
 *    and g of the mesh, n from the order of the triangle's points), should commute with C:
 *      + OrientationWeight DescriptorWeight / (number of operators) sum_g ||C Q1_g - Q2_g C||^2
 *    with each pair divided by ||Q1_g||. Descriptors and Laplacians are blind to orientation,
 *    so without this term (or landmarks) a shape with a mirror symmetry may be mapped onto its
 *    reflection; with it the map keeps the orientation of the triangles (turn the target's
 *    triangles over to ask for a reflection). Cost: O(F k^2) per operator to build (F
 *    triangles), and the terms couple the rows of C, so the k^2 entries are solved for at once:
 *    a dense system of k^2 unknowns, O(k^6), about 0.1 s at k = 30 and a few seconds at the
 *    limit InitialSize <= 60. The refinement is unchanged (ZoomOut keeps the orientation of the
 *    map it starts from).
 *
 * Costs: the descriptors O(n m E) per shape; the initial map O(k^4) (k^6 with the orientation
 * term). The nearest neighbours of the point maps are a brute force by fixed blocks of matrix
 * products (||b||^2 - 2 a.b), deterministic whatever the threads: O(s1 s2 k) per ZoomOut
 * iteration, about (FinalSize - InitialSize) / ZoomOutStep of them, on s = min(n,
 * ZoomOutSamples) farthest-point samples of each shape, then one O(n1 n2 FinalSize) point map
 * on every point. Measured with the defaults on 13,536 and 19,942 points: 7.8 s on 2 shared
 * cores. Memory O((n1 + n2) m) plus fixed blocks.
 *
 * Used by vtkFunctionalMap; tested by Testing/Core/TestFunctionalMap.cxx.
 */
#ifndef spectral_FunctionalMap_h
#define spectral_FunctionalMap_h

#include "Common/Defaults.h"
#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Filtering/Transfer.h"

#include <utility>
#include <vector>

namespace spectral
{
/// One shape of a correspondence: (a copy of the first columns of) its basis and its mesh.
struct SpectralShape
{
  /// n by m, D-orthonormal (Harmonics^T diag(Mass) Harmonics = I).
  RowMatrix Harmonics;
  /// m eigenvalues, ascending (0 for the constant harmonic of each connected component).
  Vector Eigenvalues;
  /// n lumped masses, the weights of the integrals. A point of zero mass is a candidate of no
  /// target point; it is on the surface (OnSurface) when its row of harmonics is not zero: a
  /// copy of a welded seam point, whose mass counts once, on the copy that owns it, gets its
  /// own corresponding point. Points outside the surface (zero mass and harmonics) get -1.
  Vector Mass;
  /// n by 3 points (for the orientation term; may be empty otherwise).
  Points Vertices;
  /// Triangles (may be empty).
  Triangles Faces;
};

/// The settings of ComputeFunctionalMap; the defaults (Common/Defaults.h) work on two scans of
/// the same object with bases of DefaultNumberOfHarmonics harmonics each.
struct FunctionalMapOptions
{
  /// k of the descriptor-based estimate, >= 1; 0 takes min(DefaultFunctionalMapInitialSize,
  /// the final size).
  int InitialSize = 0;
  /// k after the refinement, InitialSize <= FinalSize <= both bases' m; 0 takes
  /// min(DefaultFunctionalMapFinalSize, m1, m2). FinalSize == InitialSize: no refinement.
  int FinalSize = 0;
  /// Growth of k per ZoomOut iteration, >= 1.
  int ZoomOutStep = DefaultZoomOutStep;
  /// The ZoomOut iterations run on this many points of each shape (farthest-point samples,
  /// landmarks included) when a shape has more; the final point map is on every point. 0: on
  /// every point.
  int ZoomOutSamples = DefaultZoomOutSamples;
  /// Wave kernel energies per shape, >= 1.
  int NumberOfDescriptors = DefaultNumberOfMapDescriptors;
  /// Weight of descriptor preservation, > 0.
  double DescriptorWeight = 1.0;
  /// Weight of the commutativity with the Laplacians, >= 0.
  double CommutativityWeight = DefaultCommutativityWeight;
  /// Weight of the landmark descriptors relative to the others, >= 0.
  double LandmarkWeight = DefaultLandmarkWeight;
  /// Weight of the orientation term relative to descriptor preservation, >= 0.
  double OrientationWeight = DefaultOrientationWeight;
  /// The orientation-preserving term of Ren et al. 2018 (needs Vertices and Faces on both
  /// shapes, InitialSize <= 60).
  bool OrientationTerm = false;
  /// (source point, target point) pairs known to correspond.
  std::vector<std::pair<int, int>> Landmarks;
  /// Threads of the nearest-neighbour searches (Common/Threads.h: 0 = automatic).
  int Threads = 0;
};

/// What ComputeFunctionalMap computes.
struct FunctionalMapResult
{
  /// FinalSize by FinalSize (target rows, source columns): the final C.
  DenseMatrix Map;
  /// InitialSize by InitialSize: the descriptor-based estimate, before the refinement.
  DenseMatrix InitialMap;
  /// n2 entries: the source point of each target point (-1 where the target's mass is 0).
  std::vector<int> CorrespondingPointIds;
  /// The resolved sizes.
  int InitialSize = 0;
  int FinalSize = 0;
  /// Number of ZoomOut point maps (refinement iterations; with samples, not counting the final
  /// point map on every point).
  int Iterations = 0;
  /// The points of the source and of the target the iterations ran on ({0, 0}: all).
  std::pair<int, int> Samples = { 0, 0 };
  /// ||C A - B|| / ||B|| of the initial map on the (non-landmark) descriptors.
  double DescriptorResidual = 0.0;
  /// Seconds for the descriptors and the initial map, and for the refinement.
  double EstimateSeconds = 0.0;
  double RefinementSeconds = 0.0;
};

/**
 * The functional map between two shapes, its ZoomOut refinement and the point map.
 * \param source Shape 1 (n1 points, m1 harmonics).
 * \param target Shape 2 (n2 points, m2 harmonics).
 * \param options Sizes, weights, landmarks, threads.
 * \param monitor Progress in [0, 1], stages ("Descriptors", "Refine") and cancellation.
 * \throws InvalidInput for sizes that disagree within a shape, fewer than 2 harmonics, sizes out
 *         of range (InitialSize > FinalSize, FinalSize above m1 or m2, ZoomOutSamples below twice
 *         FinalSize), a landmark out of range or outside the surface (OnSurface), non-finite values,
 *         negative weights, OrientationTerm without the points and triangles of both shapes or
 *         with InitialSize above 60.
 * \throws Cancelled if the monitor says so.
 */
FunctionalMapResult ComputeFunctionalMap(const SpectralShape& source,
  const SpectralShape& target,
  const FunctionalMapOptions& options,
  const Monitor& monitor = Monitor());

/**
 * `shape` scaled to unit area (A = the sum of its masses): harmonics times sqrt(A), eigenvalues
 * times A, masses and points divided by A and sqrt(A). Two scans of one object differ in size
 * (other units, or the area that noise adds: a 0.2% noise made a scan's area 16% larger and its
 * map 20% off), and their spectra and harmonics compare only at the same size, as pyFM and
 * ZoomOut scale them: ComputeFunctionalMap, PointMapFromFunctionalMap, FunctionalMapFromPointMap
 * and TransferThroughMap all work on the shapes at unit area, and the map C relates the
 * coefficients of functions in their unit-area bases (a constant has coefficient 1 on both).
 */
SpectralShape UnitArea(const SpectralShape& shape);

/// Whether point i of `shape` is on its surface: positive mass or a non-zero row of harmonics.
bool OnSurface(const SpectralShape& shape, Eigen::Index i);

/**
 * The point map of a functional map: for each target point j on the surface (OnSurface), the
 * source point i of non-zero mass whose row of Phi1_k1 is nearest to row j of Phi2_k2 C
 * (Pi Phi1 ~ Phi2 C); -1 for target points outside the surface.
 * \param map k2 by k1, k1 <= m1, k2 <= m2.
 * \throws InvalidInput for sizes out of range or a source without a point of non-zero mass.
 */
std::vector<int> PointMapFromFunctionalMap(const SpectralShape& source,
  const SpectralShape& target,
  const DenseMatrix& map,
  int threads = 0);

/**
 * The functional map of a point map: C = Phi2_k^T D2 Pi Phi1_k (k by k), the least-squares
 * solution of Pi Phi1_k = Phi2_k C. Target points with id -1 contribute nothing.
 * \throws InvalidInput for k above m1 or m2, ids of the wrong count or out of range.
 */
DenseMatrix FunctionalMapFromPointMap(const SpectralShape& source,
  const SpectralShape& target,
  const std::vector<int>& correspondingPointIds,
  int k);

/**
 * For each query row, the index of the nearest database row (Euclidean), ties to the smallest
 * index; rows of the database where `allowed` is false are skipped (an empty `allowed` allows
 * every row). A brute force by fixed blocks of matrix products: deterministic, independent of
 * the number of threads, memory bounded by the blocks.
 * \param queries nq by d. \param database nd by d.
 * \return nq indices (-1 if no database row is allowed).
 * \throws InvalidInput if the widths differ or `allowed` has neither 0 nor nd entries.
 */
std::vector<int> NearestRows(const RowMatrix& queries,
  const RowMatrix& database,
  const std::vector<bool>& allowed = {},
  int threads = 0);

/**
 * Smooth fields through the map: X_target = Phi2_k2 C Phi1_k1^T D1 X_source.
 * \param map k2 by k1. \param values n1 by c.
 * \return n2 by c.
 * \throws InvalidInput for sizes that disagree.
 */
RowMatrix TransferThroughMap(const SpectralShape& source,
  const SpectralShape& target,
  const DenseMatrix& map,
  const ConstRowView& values);

/**
 * Any array through the point map: X_target(j) = X_source(ids[j]); rows with id -1 are NaN.
 * \param values n1 by c.
 * \return ids.size() by c.
 * \throws InvalidInput for an id out of range.
 */
RowMatrix TransferThroughPoints(const std::vector<int>& correspondingPointIds,
  const ConstRowView& values);

/**
 * Mode alignment: harmonics of the target that match the source's one by one through C.
 * Column k of the result is the target function of coefficients C e_k restricted to the
 * target harmonics of the near-degenerate group (relative eigenvalue gap below
 * DegenerateEigenvalueGap) of the target harmonic j = order[k] with the largest |C_jk|
 * (each j used once, greedy over k ascending), scaled to unit D2-norm: for a simple eigenvalue
 * that is signs[k] * phi2_j, for a degenerate one the rotation of its eigenspace that matches
 * source harmonic k.
 * \param map k2 by k1 (k1 <= k2 columns are aligned).
 * \param order Out (optional): k1 target harmonic indices.
 * \param signs Out (optional): k1 signs (+1, -1) of C_{order[k], k}.
 * \return n2 by k1.
 * \throws InvalidInput for sizes that disagree or k1 > k2.
 */
RowMatrix AlignModes(const SpectralShape& source,
  const SpectralShape& target,
  const DenseMatrix& map,
  std::vector<int>* order = nullptr,
  Vector* signs = nullptr);

/// Eigenvalues within this relative gap of each other form a near-degenerate group
/// (AlignModes).
constexpr double DegenerateEigenvalueGap = 0.05;
} // namespace spectral

#endif
