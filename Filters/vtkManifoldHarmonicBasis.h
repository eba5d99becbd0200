// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkManifoldHarmonicBasis
 * @brief   compute the manifold harmonics (Laplace-Beltrami eigenfunctions) of a surface or a
 *          volume
 *
 * vtkManifoldHarmonicBasis computes the m smallest eigenpairs of the generalized eigenproblem
 * L h = lambda M h on a triangle mesh, where L is the cotangent stiffness matrix (symmetric,
 * positive semi-definite) and M the mass matrix (lumped barycentric areas by default, or the
 * consistent Galerkin mass). The eigenvectors h_0, h_1, ... are the manifold harmonics: the
 * discrete analogue of the Fourier basis on the surface, ordered by frequency. Their eigenvalues
 * lambda_k are the squared frequencies; lambda_0 = 0 with a constant h_0 on a connected surface.
 *
 * The input is any vtkPointSet (vtkPolyData, vtkUnstructuredGrid, vtkStructuredGrid, ...) and
 * the output has its type. Its 2-D cells make a surface: polygons, quadrilaterals, pixels and
 * triangle strips are triangulated (with a warning). Its 3-D cells make a volume, whose
 * harmonics are the eigenfunctions of the Laplacian of the solid: tetrahedra get the linear (P1)
 * finite-element stiffness (the cotangent weights of the volume) and a quarter of their volume
 * as lumped mass; hexahedra, voxels, wedges and pyramids are split into tetrahedra (with a
 * warning; neighbours split a shared face alike, see vtkManifoldHarmonicsArrays.h). An input
 * that mixes 2-D and 3-D cells, or has cells of another kind (quadratic, polyhedral), is an
 * error naming the counts. Vertices and lines are ignored; a point cloud (points and no cells
 * but vertices) gets the harmonics of Sharp and Crane's point-cloud Laplacian (see
 * NumberOfNeighbors; Built-in solver, serial runs). Cells of numerically zero
 * area or volume are left out, and points that no remaining cell uses get zero harmonics and
 * zero mass.
 *
 * The output is a shallow copy of the input with new arrays (names from the static accessors
 * below):
 * - point data HarmonicsArrayName() ("ManifoldHarmonics"): vtkDoubleArray (vtkFloatArray with
 *   BasisPrecision FLOAT) with m components named Phi_0, Phi_1, ...; tuple i holds the value of
 *   every harmonic at point i. With the default LUMPED mass the harmonics are M-orthonormal:
 *   sum_i mass_i h_k(i) h_l(i) = delta_kl with the lumped mass (to float round-off, about 1e-7,
 *   in single precision). With CONSISTENT they are orthonormal for the consistent mass, and
 *   for the lumped mass only to discretization error (0.02 for 20 harmonics of the bunny).
 * - point data MassArrayName() ("ManifoldHarmonicsMass"): the lumped mass (one third of the area
 *   of the triangles around each point), one component. Downstream filters use it as the inner
 *   product, so they never re-assemble the operators.
 * - field data EigenvaluesArrayName() ("ManifoldHarmonicsEigenvalues"): vtkDoubleArray with m
 *   tuples, the eigenvalues in ascending order.
 * - field data "ManifoldHarmonicsBackwardError" and "ManifoldHarmonicsResidual": one value each,
 *   the largest componentwise backward error and relative residual of the pairs. A pair is
 *   accepted when either is at most 1e-8: it is then an exact eigenpair of operators within
 *   1e-8 of the assembled ones, entry by entry (spectral::BackwardErrors), or its residual is.
 *
 * Parameters: NumberOfHarmonics (default DEFAULT_NUMBER_OF_HARMONICS), BoundaryCondition
 * (default NEUMANN; DIRICHLET: the harmonics vanish on the boundary), MassMatrix (default LUMPED),
 * Laplacian (default COTANGENT; INTRINSIC_DELAUNAY for meshes with badly shaped triangles),
 * BasisPrecision (default DOUBLE; FLOAT halves the harmonics array), the solver settings BandSize
 * (default 0, automatic), Tolerance (default 1e-11) and MaxIterations (default 1000), and
 * MemoryLimit (default 0: the memory the system reports available).
 *
 * Seams: points that coincide within SeamTolerance (default 1e-12 of the bounding box diagonal)
 * are one point (WeldSeams, default on), in serial and distributed runs alike: a mesh whose faces
 * hold their own copies of shared points (an OBJ with texture or normal indices as ParaView's
 * reader gives it, an unmerged STL) has the harmonics of the welded surface. Every copy of a
 * welded point gets the same harmonics and mass, so filtering keeps the seams closed, and the
 * output keeps the input's points, cells and arrays; all copies but one (the first that the
 * input does not flag as another process's) are flagged vtkDataSetAttributes::DUPLICATEPOINT in
 * the point ghost array (vtkGhostType), so that vtkManifoldHarmonicTransform counts the point
 * once. WeldSeams off keeps every point apart (each piece its own connected component) in a
 * serial run; a distributed run merges coincident points whatever WeldSeams says (it cannot tell
 * a seam inside a piece from one between pieces) and warns.
 *
 * Memory: before it assembles anything, the filter estimates the memory the computation needs
 * (the output basis, the solver's eigenvectors, its Lanczos workspace and the sparse factor;
 * formula in Filters/Spectral/Solver/Memory.h); when it does not fit, Storage AUTOMATIC keeps the
 * basis in a file that the harmonics array maps (see Storage, BasisFileName), and when that does
 * not fit either it fails with an error saying how much is needed, how much is available and
 * what to change, instead of being killed by the system during a long solve.
 *
 * The output can be written with the mesh (vtkXMLPolyDataWriter, binary or ASCII data mode) and
 * read back: vtkManifoldHarmonicTransform and vtkSpectralFilter use the arrays read from the
 * file as they are, without recomputing the basis (Filters/Testing/Cxx/TestBasisReuse.cxx).
 *
 * The eigenproblem is solved band by band with shift-invert block Lanczos iterations on sparse
 * LDL^T factorizations of L - sigma M (CHOLMOD); the inertia of each factorization proves that
 * no eigenpair was missed (see Filters/Spectral/Solver/EigenSolver.h). The filter reports progress
 * during the solve and honours AbortExecute: an aborted execution leaves the output empty.
 *
 * Distributed runs (MPI: pvbatch, pvserver): when the global controller has several processes
 * and more than one holds triangles, the pieces are gathered on process 0 (surfaces in
 * vtkPolyData only: a distributed volume or unstructured grid is an error for now), the points they
 * share along their seams are merged (the seam rule above), the basis of the
 * whole surface is computed there and every process receives the rows of its own points and
 * all eigenvalues. Ghost cells (the vtkGhostType cell array, as D3 gives them) are left out of
 * the surface: another process owns them. A shared point is owned by the lowest rank holding it
 * as its own (not as a ghost point); on the other processes it is flagged
 * vtkDataSetAttributes::DUPLICATEPOINT in the point ghost array (vtkGhostType), which
 * vtkManifoldHarmonicTransform uses to count it once; it still gets its rows of the basis, so
 * that each piece is complete. Never a per-piece basis. Tests:
 * Testing/ParaView/TestParallelManifoldHarmonics.py.in, TestParallelGhostCells.py.in.
 *
 * @warning The harmonics array holds n x m doubles (100 harmonics on a million points take
 * 800 MB), or n x m floats with BasisPrecision FLOAT (400 MB), and the eigensolver needs about
 * as much again in double while it runs. Several connected components give several zero
 * eigenvalues (one constant per component) and are reported with a warning. NumberOfHarmonics
 * is clamped to the number of points that triangles use. NaN or infinite coordinates on used
 * points are an error. Needle triangles so thin that the eigenvalues span more than about 10^8
 * get eigenpairs verified to the accuracy double precision allows (with a warning), or an error
 * beyond 1e-4; INTRINSIC_DELAUNAY removes the needles that lie inside a manifold part of the
 * surface.
 *
 * Reference: B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics",
 * Computer Graphics Forum 27(2), 2008.
 *
 * Tested by Filters/Testing/Cxx/TestManifoldHarmonicBasis.cxx,
 * Filters/Testing/Cxx/TestRobustness.cxx, Filters/Testing/Cxx/TestBasisReuse.cxx,
 * Filters/Testing/Cxx/TestBasisFile.cxx and
 * Filters/Testing/Python/TestManifoldHarmonicBasis.py.
 *
 * @sa
 * vtkManifoldHarmonicTransform vtkSpectralFilter vtkWindowedSincPolyDataFilter
 */

#ifndef vtkManifoldHarmonicBasis_h
#define vtkManifoldHarmonicBasis_h

#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkManifoldHarmonicsModule.h" // For export macro

#include <string> // For SlepcOptions, BasisFileName

class vtkMultiProcessController;
class vtkPointSet;
class vtkPolyData;

class VTKMANIFOLDHARMONICS_EXPORT vtkManifoldHarmonicBasis : public vtkManifoldHarmonicsAlgorithm
{
public:
  /**
   * Construct with DEFAULT_NUMBER_OF_HARMONICS harmonics, the lumped mass matrix, the cotangent
   * Laplacian, a double basis, automatic band size, tolerance 1e-11, 1000 iterations at most and
   * the memory the system reports available as the limit.
   */
  static vtkManifoldHarmonicBasis* New();

  ///@{
  /**
   * Standard methods for type information and printing.
   */
  vtkTypeMacro(vtkManifoldHarmonicBasis, vtkManifoldHarmonicsAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  ///@}

  /**
   * The mass matrix of the eigenproblem L h = lambda M h.
   * LUMPED: diagonal, one third of the area of the triangles around each point (Vallet & Levy
   * use it; fastest). CONSISTENT: the Galerkin mass of linear elements; more accurate
   * eigenvalues on coarse meshes, at a higher cost.
   */
  enum MassMatrixType
  {
    LUMPED = 0,
    CONSISTENT = 1
  };

  /**
   * The default NumberOfHarmonics, here and in vtkManifoldHarmonicSmoothing: the wrapped copy of
   * spectral::DefaultNumberOfHarmonics (Filters/Spectral/Common/Defaults.h, the one home of that
   * value; a static_assert keeps them equal), against which the ParaView XML is checked by
   * Testing/ParaView/TestManifoldHarmonicsXMLDefaults.py.in.
   */
  enum DefaultNumberOfHarmonics
  {
    DEFAULT_NUMBER_OF_HARMONICS = 100
  };

  /**
   * The default NumberOfNeighbors, here and in vtkManifoldHarmonicSmoothing: the wrapped copy
   * of spectral::DefaultNumberOfNeighbors (Filters/Spectral/Common/Defaults.h; a static_assert
   * keeps them equal).
   */
  enum DefaultNumberOfNeighbors
  {
    DEFAULT_NUMBER_OF_NEIGHBORS = 30
  };

  ///@{
  /**
   * Number m of harmonics (eigenpairs) to compute, lowest frequencies first: at least 1 (a
   * smaller value is refused with an error and the previous value kept), clamped at execution
   * to the number of points that triangles use (with a warning). The cost grows with m: memory
   * n x m, time roughly n x m^2. Default is DEFAULT_NUMBER_OF_HARMONICS.
   */
  virtual void SetNumberOfHarmonics(int m);
  vtkGetMacro(NumberOfHarmonics, int);
  ///@}

  ///@{
  /**
   * Choose the mass matrix M of the eigenproblem: LUMPED (0) or CONSISTENT (1). The output mass
   * array always holds the lumped mass, and the harmonics are M-orthonormal for the chosen M.
   * vtkManifoldHarmonicTransform weighs by the lumped mass, so a round trip through the
   * transform and the filter is exact (to round-off) with LUMPED only; with CONSISTENT it is
   * exact to discretization error (0.4% for a signal in the span of 20 harmonics of the
   * bunny). Use CONSISTENT to study eigenvalues on coarse meshes, LUMPED to filter.
   * Default is LUMPED.
   */
  vtkSetClampMacro(MassMatrix, int, LUMPED, CONSISTENT);
  vtkGetMacro(MassMatrix, int);
  void SetMassMatrixToLumped() { this->SetMassMatrix(LUMPED); }
  void SetMassMatrixToConsistent() { this->SetMassMatrix(CONSISTENT); }
  ///@}

  /**
   * The discrete Laplace-Beltrami operator (stiffness and mass) of the eigenproblem.
   * COTANGENT: the cotan Laplacian of the input triangles (Vallet & Levy; Pinkall & Polthier).
   * INTRINSIC_DELAUNAY: the cotan Laplacian of the intrinsic Delaunay triangulation of the same
   * surface (Bobenko & Springborn 2007; Sharp & Crane 2020), robust to obtuse and needle
   * triangles.
   */
  enum LaplacianType
  {
    COTANGENT = 0,
    INTRINSIC_DELAUNAY = 1
  };

  ///@{
  /**
   * Choose the Laplacian: COTANGENT (0) or INTRINSIC_DELAUNAY (1). INTRINSIC_DELAUNAY is the
   * robust Laplacian of Sharp & Crane (2020): it takes every triangle twice (the tufted cover,
   * a closed oriented surface even where the input has boundaries, non-manifold edges or an
   * inconsistent orientation), lengthens every edge by the smallest amount that gives each
   * triangle a margin of 1e-5 mean edge lengths in the triangle inequality (mollification), and
   * flips edges, on edge lengths alone, until every edge is locally Delaunay (its opposite angles
   * sum to at most pi). The surface and its points stay the same, but the cotan weights become
   * non-negative and the eigenpairs stop degrading on badly shaped, near-degenerate or
   * non-manifold triangles; no cleaning is needed first. Its mass (the output mass array, and
   * the consistent mass if chosen) comes from the intrinsic triangles: the total area is the
   * same up to the mollification, its distribution over the points differs slightly from the
   * cotangent option's. Default is COTANGENT.
   */
  vtkSetClampMacro(Laplacian, int, COTANGENT, INTRINSIC_DELAUNAY);
  vtkGetMacro(Laplacian, int);
  void SetLaplacianToCotangent() { this->SetLaplacian(COTANGENT); }
  void SetLaplacianToIntrinsicDelaunay() { this->SetLaplacian(INTRINSIC_DELAUNAY); }
  ///@}

  /**
   * The condition the harmonics satisfy on the boundary of the surface (its boundary edges) or
   * volume (the faces of one tetrahedron only), the values of spectral::BoundaryCondition.
   * NEUMANN: the natural condition, zero normal derivative; each connected component has a
   * constant harmonic of eigenvalue 0. DIRICHLET: the harmonics vanish on the boundary; the
   * boundary points get zero harmonics and zero mass (so vtkSpectralFilter and
   * vtkManifoldHarmonicSmoothing pass them through unchanged) and no eigenvalue is 0. A closed
   * surface has no boundary: DIRICHLET is then ignored with a warning.
   */
  enum BoundaryConditionType
  {
    NEUMANN = 0,
    DIRICHLET = 1
  };

  ///@{
  /**
   * Choose the boundary condition: NEUMANN (0) or DIRICHLET (1). Default is NEUMANN.
   */
  vtkSetClampMacro(BoundaryCondition, int, NEUMANN, DIRICHLET);
  vtkGetMacro(BoundaryCondition, int);
  void SetBoundaryConditionToNeumann() { this->SetBoundaryCondition(NEUMANN); }
  void SetBoundaryConditionToDirichlet() { this->SetBoundaryCondition(DIRICHLET); }
  ///@}

  ///@{
  /**
   * Number of eigenpairs the solver computes per band (per shift-invert Lanczos run). Small
   * bands keep each Lanczos basis small; large bands need fewer factorizations. 0 chooses
   * automatically: a single band for up to 120 harmonics, else bands of 100; smaller ones, down
   * to 20 eigenpairs, where those do not fit the memory (MemoryLimit; a warning says so). Range
   * [0, VTK_INT_MAX]. Default is 0.
   */
  vtkSetClampMacro(BandSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(BandSize, int);
  ///@}

  ///@{
  /**
   * Relative convergence tolerance of the Lanczos iteration within a band. Smaller values give
   * more accurate eigenpairs at the cost of more iterations. Range [1e-16, 1]. Default is 1e-11.
   */
  vtkSetClampMacro(Tolerance, double, 1e-16, 1.0);
  vtkGetMacro(Tolerance, double);
  ///@}

  ///@{
  /**
   * Maximum number of Lanczos restarts within a band. When a band does not converge within
   * this limit, the filter reports an error and produces no output. Range [1, VTK_INT_MAX].
   * Default is 1000.
   */
  vtkSetClampMacro(MaxIterations, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaxIterations, int);
  ///@}

  /**
   * The value type of the harmonics array. FLOAT: vtkFloatArray, half the memory of DOUBLE;
   * the eigensolver still works in double and the values are rounded once when written (relative
   * error about 6e-8), which is far below what filtering a shape needs. DOUBLE: vtkDoubleArray.
   * The one declaration of these values: vtkManifoldHarmonicSmoothing uses them too.
   */
  enum BasisPrecisionType
  {
    FLOAT = 0,
    DOUBLE = 1
  };

  ///@{
  /**
   * Choose the value type of the harmonics array: FLOAT (0, vtkFloatArray) or DOUBLE (1,
   * vtkDoubleArray). FLOAT halves the memory of the basis (a million points and 1000 harmonics:
   * 4 GB instead of 8 GB), in the output and in every file it is saved to;
   * vtkManifoldHarmonicTransform and vtkSpectralFilter read either type in place and accumulate
   * in double, so their results differ from DOUBLE's by float round-off (below 1e-7 relative in
   * the tests). The mass and eigenvalue arrays stay double. Default is DOUBLE.
   */
  vtkSetClampMacro(BasisPrecision, int, FLOAT, DOUBLE);
  vtkGetMacro(BasisPrecision, int);
  void SetBasisPrecisionToFloat() { this->SetBasisPrecision(FLOAT); }
  void SetBasisPrecisionToDouble() { this->SetBasisPrecision(DOUBLE); }
  ///@}

  ///@{
  /**
   * The memory, in MiB (2^20 bytes), that the computation may use; 0 uses what the system
   * reports available when the filter runs (MemAvailable in /proc/meminfo on Linux, free
   * physical pages elsewhere). When the estimate of Filters/Spectral/Solver/Memory.h exceeds it,
   * Storage AUTOMATIC keeps the basis in a file (whose mapped pages are page cache, not counted);
   * where the automatic bands (BandSize 0) do not fit, the solve runs in smaller ones, down to
   * 20 eigenpairs (spectral::SmallestPlannedBand), and warns; and when the solve alone still
   * exceeds it the filter reports an error (how much is needed and available; fewer harmonics,
   * BasisPrecision FLOAT, BandSize 0) and produces an empty output. Set a limit to keep room for
   * other work, or to test the check. Range [0, VTK_DOUBLE_MAX]. Default is 0.
   */
  vtkSetClampMacro(MemoryLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  /**
   * Where the harmonics array is kept. IN_MEMORY: a vtkDoubleArray (vtkFloatArray) in the
   * process's memory, as always. FILE: a file (BasisFileName, or a temporary file) whose payload
   * the output's harmonics array maps read-only (PROT_READ, MAP_SHARED): its pages are the
   * system's page cache, not the process's memory, so a basis larger than the memory can be
   * computed, transformed, filtered and saved; the array must never be written (a write is a
   * segmentation fault; DeepCopy it first). AUTOMATIC: in memory when the estimate of
   * Filters/Spectral/Solver/Memory.h fits in MemoryLimit (or the available memory), else a file
   * when the solve alone fits and the file's disk has room (statvfs; twice the basis while it
   * is written, spectral::BasisFileDiskBytes), else an error naming what would make it run;
   * a named BasisFileName means a file with AUTOMATIC (with IN_MEMORY or EigenvaluesOnly it is
   * not used, and a warning says so). GetStorageUsed() and
   * GetStorageReason() say what was chosen and why (a warning too when AUTOMATIC chose a file).
   * Serial runs of the Built-in solver only: FILE or a BasisFileName in a distributed run or
   * with the SLEPc solver is an error. The one declaration of these values.
   */
  enum StorageType
  {
    AUTOMATIC = 0,
    IN_MEMORY = 1,
    FILE = 2
  };

  ///@{
  /**
   * Choose where the harmonics are kept: AUTOMATIC (0), IN_MEMORY (1) or FILE (2). Default is
   * AUTOMATIC.
   */
  vtkSetClampMacro(Storage, int, AUTOMATIC, FILE);
  vtkGetMacro(Storage, int);
  void SetStorageToAutomatic() { this->SetStorage(AUTOMATIC); }
  void SetStorageToInMemory() { this->SetStorage(IN_MEMORY); }
  void SetStorageToFile() { this->SetStorage(FILE); }
  ///@}

  ///@{
  /**
   * The file of a file-backed basis. Empty (the default): a temporary file
   * ManifoldHarmonics-<pid>-<n>.mhb in $TMPDIR (or /tmp), unlinked as soon as it is mapped: its
   * name is gone at once, and its disk space is freed when the last array mapping it is
   * released (the filter recomputes or is destroyed, and no downstream output holds it). Named:
   * kept, and reused without solving when its header records the same mesh (a digest of the
   * points and cells) and the same options that change the basis (NumberOfHarmonics, MassMatrix,
   * Laplacian, BoundaryCondition, BandSize, Tolerance, MinimumComponentSize, NumberOfNeighbors,
   * FrequencyWindow, WeldSeams, SeamTolerance, BasisPrecision); otherwise it is recomputed and
   * overwritten, with a warning naming what differed. A file that is not a basis file is never
   * overwritten (an error). The file is written as `<name>.partial` and renamed when complete,
   * so an abort or an error leaves no file that would be reused. Format:
   * Filters/Spectral/Common/BasisFile.h.
   */
  vtkSetStdStringFromCharMacro(BasisFileName);
  vtkGetCharFromStdStringMacro(BasisFileName);
  ///@}

  ///@{
  /**
   * After an execution: where the harmonics were kept (IN_MEMORY or FILE; AUTOMATIC when no
   * harmonics were computed), why (a sentence), and whether a named BasisFileName was reused
   * without solving.
   */
  vtkGetMacro(StorageUsed, int);
  const char* GetStorageReason() { return this->StorageReason.c_str(); }
  vtkGetMacro(BasisReused, bool);
  ///@}

  ///@{
  /**
   * Connected components of fewer points than this are left out: their points get zero
   * harmonics and mass (as points no triangle uses), a warning says how many, and the filters
   * downstream pass them through unchanged. For scans whose debris (islands of a few points)
   * should not take a zero eigenvalue each. Every component is solved on its own, so however
   * many are kept each has exactly one zero eigenvalue. Range [0, VTK_INT_MAX]; 0 keeps every
   * component. Default is 0.
   */
  vtkSetClampMacro(MinimumComponentSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(MinimumComponentSize, int);
  ///@}

  ///@{
  /**
   * Point clouds (a point set without cells, or with vertex cells only): the neighbours of each
   * point whose local Delaunay triangulation builds the point-cloud Laplacian of Sharp and
   * Crane ("A Laplacian for Nonmanifold Triangle Meshes", SGP 2020); clamped, with a warning, to
   * the other points of the cloud. Not used for meshes. Range [2, VTK_INT_MAX]. Default is
   * DEFAULT_NUMBER_OF_NEIGHBORS.
   */
  vtkSetClampMacro(NumberOfNeighbors, int, 2, VTK_INT_MAX);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * Compute and verify the eigenvalues but do not store the n x m harmonics: the output has the
   * eigenvalues and the mass only (for ShapeDNA with vtkSpectralDescriptors), and the memory
   * check leaves the output basis out. The eigensolver keeps only the vectors of its last bands
   * (it verifies the older pairs before it lets their vectors go), so its memory does not grow
   * with the number of harmonics. Not available in distributed runs yet (an error says so).
   * Default is false.
   */
  vtkSetMacro(EigenvaluesOnly, bool);
  vtkGetMacro(EigenvaluesOnly, bool);
  vtkBooleanMacro(EigenvaluesOnly, bool);
  ///@}

  ///@{
  /**
   * A frequency window [lower, upper) in the units of the mesh: unless both are 0, the harmonics
   * whose frequency omega = sqrt(lambda) lies in it are computed instead of the
   * NumberOfHarmonics smallest. Two inertia counts prove how many there are (none missing); the
   * solver's bands start at the lower end, so the harmonics below it are not computed. A window
   * that is not 0 <= lower < upper < infinity (NaN included), or one without an eigenvalue, is an
   * error.
   * Default is (0, 0): off.
   */
  vtkSetVector2Macro(FrequencyWindow, double);
  vtkGetVector2Macro(FrequencyWindow, double);
  ///@}

  /**
   * The eigensolver. BUILT_IN: the module's own (band-by-band shift-invert block Lanczos on
   * CHOLMOD, every option of this filter); in a distributed run, process 0 gathers the surface
   * and solves alone. SLEPC: SLEPc's Krylov-Schur spectrum slicing on PETSc matrices with MUMPS
   * factorizations, distributed over the MPI processes of the run: each assembles the operators
   * of its own piece, nothing is gathered, and each keeps the rows of its own points (also
   * used in a serial run, on one process). Available when the module is built with SLEPc
   * (HasSlepc()). The one declaration of these values: vtkManifoldHarmonicSmoothing uses them.
   */
  enum SolverType
  {
    BUILT_IN = 0,
    SLEPC = 1
  };

  ///@{
  /**
   * Choose the eigensolver: BUILT_IN (0) or SLEPC (1). SLEPC needs a build with SLEPc
   * (HasSlepc(); an error otherwise) and takes surfaces and volumes (triangles or tetrahedra,
   * any vtkPointSet; point clouds are refused). It supports the COTANGENT Laplacian, both mass
   * matrices, NumberOfHarmonics, Tolerance and MaxIterations (Krylov-Schur's);
   * MinimumComponentSize, EigenvaluesOnly, FrequencyWindow and the DIRICHLET
   * BoundaryCondition are refused with an error, and BandSize, MemoryLimit (a warning says so)
   * and NumberOfThreads (the built-in solver's) do not apply; StorageUsed is IN_MEMORY. Its results
   * equal the built-in solver's to round-off: the eigenvalues, the spanned subspaces, the filtered
   * points (Testing/ParaView/TestSlepcManifoldHarmonics.py.in, at 1, 2 and 3 processes). The output
   * has the same arrays, and in field data also ManifoldHarmonicsInertiaCount (eigenvalues
   * SLEPc's interval holds, counted by the inertia of a MUMPS factorization) and
   * ManifoldHarmonicsOrthonormalityError. Default is BUILT_IN.
   */
  vtkSetClampMacro(Solver, int, BUILT_IN, SLEPC);
  vtkGetMacro(Solver, int);
  void SetSolverToBuiltIn() { this->SetSolver(BUILT_IN); }
  void SetSolverToSlepc() { this->SetSolver(SLEPC); }
  ///@}

  /**
   * Whether this build of the module has the SLEPC solver (CMake found SLEPc through
   * pkg-config).
   */
  static bool HasSlepc();

  ///@{
  /**
   * SLEPc's npart (EPSKrylovSchurSetPartitions): the spectrum slicing interval is cut into this
   * many sub-intervals, each solved at once by a group of processes. More partitions run more
   * factorizations at once, each on fewer processes (more memory per process). Clamped to the
   * number of processes (with a warning). SLEPC only. Range [1, VTK_INT_MAX]. Default is 1.
   */
  vtkSetClampMacro(SlepcPartitions, int, 1, VTK_INT_MAX);
  vtkGetMacro(SlepcPartitions, int);
  ///@}

  ///@{
  /**
   * Options for SLEPc, PETSc and MUMPS, for experts, in the syntax of PETSc's options database
   * (PetscOptionsInsertString), applied after the solver's own settings and for this filter's
   * solve only; e.g. "-st_mat_mumps_icntl_14 50" (more MUMPS workspace) or
   * "-eps_krylovschur_nev 60" (pairs per shift). The solver's factorization has the prefix
   * st_. SLEPC only. Default is "" (none).
   */
  vtkSetStdStringFromCharMacro(SlepcOptions);
  vtkGetCharFromStdStringMacro(SlepcOptions);
  ///@}

  ///@{
  /**
   * Merge the points that coincide within SeamTolerance before solving (see Seams above), so
   * that a surface whose faces hold their own copies of shared points is solved as one surface,
   * and write each harmonic onto every copy. Default is on. Off keeps such pieces apart (one
   * connected component each) in a serial run; a distributed run merges whatever this says.
   */
  vtkSetMacro(WeldSeams, bool);
  vtkGetMacro(WeldSeams, bool);
  vtkBooleanMacro(WeldSeams, bool);
  ///@}

  ///@{
  /**
   * Points closer than this fraction of the bounding box diagonal are one point (WeldSeams, and
   * the seams between the pieces of a distributed run). Default is 1e-12 (round-off: a sphere's
   * 0 and 360 degree meridians differ by 1e-16 in sin(2 pi)); raise it for seams whose copies
   * were rounded apart (a file written with few digits). Valid range [0, 0.1].
   */
  vtkSetClampMacro(SeamTolerance, double, 0.0, 0.1);
  vtkGetMacro(SeamTolerance, double);
  ///@}

  ///@{
  /**
   * Names of the output arrays: the point data harmonics ("ManifoldHarmonics"), the point data
   * lumped mass ("ManifoldHarmonicsMass") and the field data eigenvalues
   * ("ManifoldHarmonicsEigenvalues"). Downstream filters look the arrays up by these names,
   * whose home is the module's private vtkManifoldHarmonicsNames.h.
   */
  static const char* HarmonicsArrayName();
  static const char* MassArrayName();
  static const char* EigenvaluesArrayName();
  ///@}

protected:
  vtkManifoldHarmonicBasis();
  ~vtkManifoldHarmonicBasis() override = default;

  /// The stages of a request (see vtkManifoldHarmonicsAlgorithm for errors and aborts).
  int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* table) override;
  const char* GetWorkName() override { return "Manifold harmonics"; }
  /// The core's exceptions of the eigensolve: memory, solver, input.
  std::string DescribeFailure(const std::exception& e) override;

  /**
   * The basis of the whole `input` into `output` (a serial run, or process 0 of a distributed
   * one, on the merged pieces), welding its coincident points first when `weld` is true.
   */
  int ComputeBasis(vtkPointSet* input, vtkPointSet* output, bool weld);

  /// Execute but for the storage report, which Execute resets where no harmonics were computed.
  int ChooseAndRun(vtkPointSet* input, vtkPointSet* output);
  /**
   * The SLEPC solver: every process solves with the others on its own piece (collective; a
   * serial run is one process). Errors and cancels alike on every process.
   */
  int ComputeSlepcBasis(vtkPointSet* input, vtkPointSet* output);

  /**
   * Distributed run (MPI, several processes hold triangles): gather and merge the pieces on
   * process 0, solve there, give every process the rows of its points. Collective.
   */
  int ComputeDistributedBasis(vtkMultiProcessController* controller,
    vtkPolyData* input,
    vtkPolyData* output);

  int NumberOfHarmonics;
  int MassMatrix;
  int Laplacian;
  int BoundaryCondition;
  int BandSize;
  double Tolerance;
  int MaxIterations;
  int BasisPrecision;
  double MemoryLimit;
  int MinimumComponentSize;
  int NumberOfNeighbors;
  bool EigenvaluesOnly;
  double FrequencyWindow[2];
  int Solver;
  int SlepcPartitions;
  std::string SlepcOptions;
  bool WeldSeams;
  double SeamTolerance;
  int Storage;
  std::string BasisFileName;
  int StorageUsed = AUTOMATIC;
  std::string StorageReason;
  bool BasisReused = false;

private:
  /// The core's basis of a mesh and the welding of its points before the solve.
  struct Solution;
  /// vtkManifoldHarmonicSmoothing's STREAMED storage (vtkManifoldHarmonicsStreaming.h).
  friend class vtkManifoldHarmonicSmoothing;
  struct StreamRequest;
  /// The basis of `input` with this filter's settings streamed into `request`'s filter
  /// instead of written (serial, built-in solver). \return 0 after an error or an abort.
  int SolveStreamed(vtkPointSet* input, StreamRequest& request);
  /**
   * Converts and checks the cells of `input`, welds them when `weld` is true and solves:
   * 0 after an error (reported), 1 otherwise; `solution` holds a basis unless the input has no
   * cells to solve on (warned). `allowFile`: whether the basis may be kept in a file
   * (Storage; not on process 0 of a distributed run, which scatters it from memory).
   * `stream`: the basis streams into the smoothing's filter instead (SolveStreamed; no storage).
   */
  int Solve(vtkPointSet* input,
    bool weld,
    Solution& solution,
    bool allowFile,
    StreamRequest* stream = nullptr);

  /// The points of the mesh being solved, for the message of InsufficientMemory.
  vtkIdType SolvedPoints = 0;
  /// Storage AUTOMATIC when nothing fits: why a file would not do, for the same message.
  std::string FileRefusal;

  vtkManifoldHarmonicBasis(const vtkManifoldHarmonicBasis&) = delete;
  void operator=(const vtkManifoldHarmonicBasis&) = delete;
};

#endif
