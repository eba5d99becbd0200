// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkManifoldHarmonicBasis
 * @brief   compute the manifold harmonics (Laplace-Beltrami eigenfunctions) of a surface
 *
 * vtkManifoldHarmonicBasis computes the m smallest eigenpairs of the generalized eigenproblem
 * L h = lambda M h on a triangle mesh, where L is the cotangent stiffness matrix (symmetric,
 * positive semi-definite) and M the mass matrix (lumped barycentric areas by default, or the
 * consistent Galerkin mass). The eigenvectors h_0, h_1, ... are the manifold harmonics: the
 * discrete analogue of the Fourier basis on the surface, ordered by frequency. Their eigenvalues
 * lambda_k are the squared frequencies; lambda_0 = 0 with a constant h_0 on a connected surface.
 *
 * The input is a vtkPolyData. Polygons and triangle strips are triangulated (with a warning);
 * vertices and lines are ignored. Triangles of numerically zero area are left out, and points
 * that no remaining triangle uses get zero harmonics and zero mass.
 *
 * The output is a shallow copy of the input with three new arrays (names from the static
 * accessors below):
 * - point data HarmonicsArrayName() ("ManifoldHarmonics"): vtkDoubleArray with m components
 *   named Phi_0, Phi_1, ...; tuple i holds the value of every harmonic at point i. The harmonics
 *   are M-orthonormal: sum_i mass_i h_k(i) h_l(i) = delta_kl with the lumped mass.
 * - point data MassArrayName() ("ManifoldHarmonicsMass"): the lumped mass (one third of the area
 *   of the triangles around each point), one component. Downstream filters use it as the inner
 *   product, so they never re-assemble the operators.
 * - field data EigenvaluesArrayName() ("ManifoldHarmonicsEigenvalues"): vtkDoubleArray with m
 *   tuples, the eigenvalues in ascending order.
 *
 * Parameters: NumberOfHarmonics (default 100), MassMatrix (default LUMPED), and the solver
 * settings BandSize (default 0, automatic), Tolerance (default 1e-11) and MaxIterations
 * (default 1000).
 *
 * The eigenproblem is solved band by band with shift-invert Lanczos iterations on a sparse
 * LDL^T factorization (Spectra and CHOLMOD). The filter reports progress during the solve and
 * honours AbortExecute: an aborted execution leaves the output empty.
 *
 * @warning The harmonics array holds n x m doubles (100 harmonics on a million points take
 * 800 MB). Several connected components give several zero eigenvalues (one constant per
 * component) and are reported with a warning. NumberOfHarmonics is clamped to the number of
 * points that triangles use.
 *
 * Reference: B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics",
 * Computer Graphics Forum 27(2), 2008.
 *
 * Tested by Filters/Testing/Cxx/TestManifoldHarmonicBasis.cxx and
 * Filters/Testing/Python/TestManifoldHarmonicBasis.py.
 *
 * @sa
 * vtkManifoldHarmonicTransform vtkSpectralFilter vtkWindowedSincPolyDataFilter
 */

#ifndef vtkManifoldHarmonicBasis_h
#define vtkManifoldHarmonicBasis_h

#include "vtkManifoldHarmonicsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

class VTKMANIFOLDHARMONICS_EXPORT vtkManifoldHarmonicBasis : public vtkPolyDataAlgorithm
{
public:
  /**
   * Construct with 100 harmonics, the lumped mass matrix, automatic band size, tolerance 1e-11
   * and 1000 iterations at most.
   */
  static vtkManifoldHarmonicBasis* New();

  ///@{
  /**
   * Standard methods for type information and printing.
   */
  vtkTypeMacro(vtkManifoldHarmonicBasis, vtkPolyDataAlgorithm);
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

  ///@{
  /**
   * Number m of harmonics (eigenpairs) to compute, lowest frequencies first. The value is
   * clamped to [1, VTK_INT_MAX] here, and at execution to the number of points that triangles
   * use (with a warning). The cost grows with m: memory n x m, time roughly n x m^2.
   * Default is 100.
   */
  vtkSetClampMacro(NumberOfHarmonics, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfHarmonics, int);
  ///@}

  ///@{
  /**
   * Choose the mass matrix M of the eigenproblem: LUMPED (0) or CONSISTENT (1). The output mass
   * array always holds the lumped mass, and the harmonics are M-orthonormal for the chosen M.
   * Default is LUMPED.
   */
  vtkSetClampMacro(MassMatrix, int, LUMPED, CONSISTENT);
  vtkGetMacro(MassMatrix, int);
  void SetMassMatrixToLumped() { this->SetMassMatrix(LUMPED); }
  void SetMassMatrixToConsistent() { this->SetMassMatrix(CONSISTENT); }
  ///@}

  ///@{
  /**
   * Number of eigenpairs the solver computes per band (per shift-invert Lanczos run). Small
   * bands keep each Lanczos basis small; large bands need fewer factorizations. 0 chooses
   * automatically (about 100). Range [0, VTK_INT_MAX]. Default is 0.
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

  ///@{
  /**
   * Names of the output arrays: the point data harmonics ("ManifoldHarmonics"), the point data
   * lumped mass ("ManifoldHarmonicsMass") and the field data eigenvalues
   * ("ManifoldHarmonicsEigenvalues"). Downstream filters look the arrays up by these names.
   */
  static const char* HarmonicsArrayName() { return "ManifoldHarmonics"; }
  static const char* MassArrayName() { return "ManifoldHarmonicsMass"; }
  static const char* EigenvaluesArrayName() { return "ManifoldHarmonicsEigenvalues"; }
  ///@}

protected:
  vtkManifoldHarmonicBasis();
  ~vtkManifoldHarmonicBasis() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfHarmonics;
  int MassMatrix;
  int BandSize;
  double Tolerance;
  int MaxIterations;

private:
  vtkManifoldHarmonicBasis(const vtkManifoldHarmonicBasis&) = delete;
  void operator=(const vtkManifoldHarmonicBasis&) = delete;
};

#endif
