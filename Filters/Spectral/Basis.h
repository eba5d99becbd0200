// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Basis.h
 * @brief The one entry point of the spectral core: a mesh and options in, a verified basis out.
 *
 * ComputeBasis is the whole algorithm of vtkManifoldHarmonicBasis, without VTK: it keeps the
 * usable part of the mesh (Operators.h, PrepareMesh), checks the request against the mesh and
 * the memory (Solver/Memory.h), assembles the chosen operators (Operators/Laplacian.h) and
 * solves for the smallest eigenpairs one connected component at a time (Solver/Components.h,
 * Solver/EigenSolver.h), in units of the mesh's size (so that the result does not depend on
 * them: lambda s^2 and the harmonics times s are the same at every scale s), with the two
 * fallbacks that the
 * solver alone does not take: a single harmonic is computed as the first of two (alone, the zero
 * eigenvalue gives the residual test no frequency scale), and operators too badly conditioned
 * for the residual tolerance are solved again with the tolerance double precision allows, with
 * a warning. The filter, the benchmark, the fuzzer and the tests all call it, so they all run
 * the same computation; the VTK layer only converts and reports.
 *
 * Tested by Testing/Core/TestBasis.cxx.
 */
#ifndef spectral_Basis_h
#define spectral_Basis_h

#include "Common/Defaults.h"
#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Operators/Laplacian.h"
#include "Operators/PointCloud.h"
#include "Solver/Components.h"
#include "Solver/EigenSolver.h"
#include "Solver/Memory.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace spectral
{
struct BasisResult;

/**
 * Where a streamed basis goes (BasisOptions::Sink): ComputeBasis hands each verified harmonic to
 * the caller as soon as the solver lets it go, instead of returning the n by m basis. Memory is
 * then the mesh, the operators, the factor and a few bands' vectors (EstimateStreamedMemory,
 * Solver/Memory.h), whatever m; the eigensolver runs as for a spectrum alone
 * (EigenOptions::KeepEigenvectors false, EigenOptions::Deliver).
 *
 * What the caller receives equals the in-memory basis of the same options: the same eigenvalues,
 * each harmonic (rows as BasisResult::InputPointIds, in the mesh's units, signs by
 * NormalizeSigns, the constant harmonic exact) the same column up to the round-off of the
 * solver's seams. In memory, a band may merge again pairs that the streamed solve has already
 * let go (Bands.h, Retire): the two differ by round-off, and within a cluster of eigenvalues by
 * a rotation of its eigenspace (compare subspaces there); Testing/Core/TestStreaming.cxx
 * measures it.
 *
 * Cost. Which pair of a component gets which index of the basis is known only once every
 * component is solved (the m smallest of the union, Solver/Components.h). With one connected
 * component and neither SpectrumFirst nor HighestFirst the pairs stream at once, in one solve.
 * With one component and HighestFirst, ComputeBasis first finds lambda_{m-1} alone
 * (HighestOfSmallest: a few inertia counts and a solve of the pairs just below it), then
 * streams the pairs up to the sink's WantedUpTo, whose number an inertia count gives. Otherwise
 * (SpectrumFirst, or several components) ComputeBasis first solves for the spectrum alone
 * (memory independent of m), which fixes each component's request, each pair's final index and
 * the points left out (components none of the m harmonics represents), then solves each
 * component again with the same request, streaming: twice the eigensolve time (the assembly is
 * done once), less where the sink wants the lower pairs alone (WantedUpTo): the second solve of
 * each component then stops at its last wanted pair.
 *
 * Not streamed: a frequency window (IsFrequencyWindow; InvalidInput).
 */
struct BasisSink
{
  /// Whether Begin must receive all m eigenvalues: costs a second solve with one component
  /// (see above).
  bool SpectrumFirst = false;
  /// Whether Begin must receive the highest eigenvalue lambda_{m-1} (e.g. gains relative to the
  /// highest frequency): with one component it costs a fraction of a solve (see above).
  bool HighestFirst = false;
  /**
   * Called once, before any harmonic, with the basis but its harmonics: InputPointIds and
   * LumpedMass as returned (the rows of every harmonic to come), Components, ConstantHarmonics,
   * BoundaryPoints and the warnings so far; Pairs.Eigenvalues holds all m eigenvalues (mesh
   * units) when they are known (SpectrumFirst, or several components), m entries of which only
   * the last, lambda_{m-1}, is known (the others NaN) with HighestFirst and one component, else
   * it is empty. May be empty.
   */
  std::function<void(const BasisResult& basis)> Begin;
  /**
   * Optional, asked after Begin where the eigenvalues or the highest are known before the
   * harmonics (SpectrumFirst, HighestFirst, or several components): the largest eigenvalue
   * (mesh units) whose harmonic can change what the sink computes. A streamed low pass
   * multiplies every harmonic above its transition by exactly zero (StreamedFilter): each
   * component is then solved only up to its last pair at or below it (with the pairs of the
   * same eigenvalue as that one, StreamedClusterGap), and Harmonics receives those pairs alone,
   * not necessarily all m. Empty, or infinity: all are wanted.
   */
  std::function<double()> WantedUpTo;
  /**
   * Receives verified harmonics: `harmonics` (#InputPointIds by values.size(), at most
   * StreamedBlockColumns, Solver/Memory.h) holds the harmonics of indices first, first + 1, ...
   * of the basis, `values` their eigenvalues (mesh
   * units). Each index in [0, m) comes exactly once (unless Restart is called; with WantedUpTo,
   * each index up to its component's last wanted pair), in no particular order across
   * components, ascending within one.
   */
  std::function<void(int first, const Vector& values, const DenseMatrix& harmonics)> Harmonics;
  /**
   * Called when every harmonic delivered so far is void and all will be delivered again: a
   * component whose solve failed its residual test after some of its pairs were delivered is
   * solved again with the relaxed tolerance (Acceptance.h; rare: badly conditioned meshes).
   * Empty: such a failure is thrown (SolverFailure) instead.
   */
  std::function<void()> Restart;
};

/**
 * Where a streamed pass stops early (BasisSink::WantedUpTo): after its component's last wanted pair
 * it still solves the pairs whose eigenvalue exceeds that pair's by at most this fraction, so
 * that a cluster of (nearly) equal eigenvalues is delivered whole, as the in-memory basis holds
 * it, and not cut where the solver's choice within the cluster is arbitrary.
 */
constexpr double StreamedClusterGap = 1e-6;

/**
 * Whether the ends [lower, upper) of BasisOptions (or DistributedOptions) ask for a frequency
 * window: every setting but the default [0, 0), which is off. A window that is not one (upper not
 * above lower, NaN, infinite) is thus refused (WindowEigenvalues, Problem.h), never taken for
 * "off". The one rule of every path.
 */
inline bool IsFrequencyWindow(double lower, double upper)
{
  return !(lower == 0.0 && upper == 0.0);
}

/// What ComputeBasis computes and how.
struct BasisOptions
{
  /// m, the number of harmonics; clamped, with a warning, to the number of usable points.
  int NumberOfHarmonics = DefaultNumberOfHarmonics;
  /// The operators.
  LaplacianOptions Operators;
  /// The neighbours of each point of a point cloud (PointCloudLaplacian; its Mass is
  /// Operators.Mass).
  int NumberOfNeighbors = DefaultNumberOfNeighbors;
  /// Connected components of fewer points are left out (zero harmonics and mass, a warning);
  /// 0 keeps every component.
  int MinimumComponentSize = 0;
  /// The eigensolver's settings; its NumberOfEigenpairs is set from NumberOfHarmonics.
  EigenOptions Solver;
  /// Bytes of one value of the caller's output basis (8 double, 4 float): the memory estimate.
  int BytesPerValue = 8;
  /// Compute and verify the eigenpairs but return no harmonics (BasisResult::Pairs has no
  /// eigenvectors): the spectrum alone, without the output basis in the memory estimate, and
  /// with a solver that keeps only the vectors of its last bands (EigenOptions::KeepEigenvectors).
  bool EigenvaluesOnly = false;
  /**
   * The frequency window [LowerFrequency, UpperFrequency): when IsFrequencyWindow, the
   * harmonics whose frequency omega = sqrt(lambda) lies in it are computed instead of the
   * NumberOfHarmonics smallest. Their number is proven by two inertia counts (Sylvester's law:
   * the negative pivots of L - omega^2 M are the eigenvalues below omega^2), per connected
   * component too, and each component's bands start at the lower end (EigenpairsInWindowBy-
   * Component, EigenOptions::StartIndex): the harmonics below it are not computed. Frequencies
   * are in the units of the mesh.
   */
  double LowerFrequency = 0.0;
  double UpperFrequency = 0.0;
  /// Whether to compare the memory estimate with what is available before assembling.
  bool CheckMemory = true;
  /// The memory available in bytes; 0 asks the system (AvailableMemory in Solver/Memory.h).
  std::uint64_t MemoryLimit = 0;
  /// Stream the basis to a sink instead of returning it (BasisSink): when Sink.Harmonics is
  /// set. The memory check then takes EstimateStreamedMemory, and BasisResult::Pairs holds the
  /// eigenvalues but no harmonics.
  BasisSink Sink;
};

/// A basis: the eigenpairs of a mesh's operators and the map back to its points.
struct BasisResult
{
  /// m eigenvalues ascending and the #used by m harmonics (M-orthonormal), with the solver's
  /// statistics (residual, bands, factorizations, timings).
  EigenResult Pairs;
  /// The lumped mass of each used point (the transform's weights).
  Vector LumpedMass;
  /// For each row of Pairs.Eigenvectors and LumpedMass, the input point it belongs to; the
  /// input points not listed have zero harmonics and mass.
  std::vector<int> InputPointIds;
  /// Number of connected components (one zero eigenvalue each with ConstantHarmonics; with
  /// Dirichlet conditions, the components of the interior points).
  int Components = 0;
  /// Whether each component has a constant harmonic of eigenvalue 0 (Neumann conditions, or
  /// Dirichlet conditions on a closed surface, which has no boundary).
  bool ConstantHarmonics = true;
  /// Boundary points eliminated by Dirichlet conditions: their harmonics and mass are 0.
  int BoundaryPoints = 0;
  /// With a frequency window: the number of eigenvalues below its lower end (the index of the
  /// first returned pair among all); otherwise 0.
  int FirstIndex = 0;
  /// Every warning that Monitor::Warning received, in order.
  std::vector<std::string> Warnings;
  /// Seconds spent preparing the mesh and assembling the operators.
  double AssemblySeconds = 0.0;
};

/// Thrown by ComputeBasis when the memory estimate exceeds what is available.
class InsufficientMemory : public std::runtime_error
{
public:
  InsufficientMemory(const MemoryEstimate& needed,
    std::uint64_t available,
    int harmonics,
    bool streamed);
  /// The number of harmonics the estimate is for (after clamping).
  int Harmonics;
  /// Whether the estimate is of a streamed basis (BasisSink): its Basis term is then the blocks
  /// in delivery, always doubles (EstimateStreamedMemory, Solver/Memory.h), not an output basis.
  bool Streamed;
  /// The estimate of the computation.
  MemoryEstimate Needed;
  /// The memory that was available, in bytes.
  std::uint64_t Available;
};

/**
 * The unit of length the operators are assembled in: the power of two nearest below `diameter`
 * (the bounding box diagonal of the used points; 1 for 0 or a non-finite value). Dividing the
 * coordinates by it is exact and makes the solve independent of the mesh's units: lambda scales
 * as 1 / s^2, the mass (an area or a volume) as s^d, M-normalized harmonics as s^(-d/2).
 * ComputeBasis (Problem.h) and the distributed
 * engine (Distributed/Solve.h) both use it.
 */
double UnitScale(double diameter);

/**
 * The m smallest eigenpairs of the Laplacian of a triangle or tetrahedral mesh.
 * \param mesh Points and triangles, or points and tetrahedra (any; what cannot be used is left
 *        out with a warning).
 * \param options m, operators, solver settings, memory check.
 * \param monitor Progress in [0, 1] (0.1 at the end of the assembly), cancellation, the names
 *        of the steps ("Assemble", "Eigensolve") and warnings as soon as they are known.
 * \throws InvalidInput for an index out of range, a non-finite coordinate on a used point (on
 *         any point of a point cloud, or one beyond MaxCoordinate), a
 *         mesh whose cells are all degenerate, a mesh with both triangles and tetrahedra, a
 *         Dirichlet condition with no interior point, NumberOfHarmonics below 1, or a frequency
 *         window that is empty or holds no eigenvalue.
 * \throws InsufficientMemory if the estimate exceeds the available memory.
 * \throws InvalidInput for a streamed basis (options.Sink) with a frequency window.
 * \throws SolverFailure if no verified basis can be had (see SmallestEigenpairs).
 * \throws Cancelled if the monitor says so.
 */
BasisResult ComputeBasis(const TriangleMesh& mesh,
  const BasisOptions& options,
  const Monitor& monitor = Monitor());
} // namespace spectral

#endif
