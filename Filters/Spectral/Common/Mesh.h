// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Mesh.h
 * @brief Types shared by the spectral core: the mesh (triangles or tetrahedra) and the matrix
 *        aliases.
 *
 * The core (namespace spectral) is plain C++17 on Eigen, Spectra and CHOLMOD. It never includes a
 * VTK header; vtkManifoldHarmonicBasis converts any vtkPointSet into a TriangleMesh (the
 * surface's triangles, or the volume's tetrahedra).
 */
#ifndef spectral_Mesh_h
#define spectral_Mesh_h

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <stdexcept>
#include <string>
#include <vector>

namespace spectral
{
/// Sparse column-major matrix of doubles with int indices (the CHOLMOD "int" interface).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
/// Dense column-major matrix of doubles.
using DenseMatrix = Eigen::MatrixXd;
/// Dense column vector of doubles.
using Vector = Eigen::VectorXd;
/**
 * A buffer of doubles aligned as Eigen aligns its own matrices (EIGEN_MAX_ALIGN_BYTES: 64 with
 * AVX-512). Some of Eigen's vectorized kernels choose where their vector instructions start
 * from the runtime address of a Map: a reduction (sum, mean, prod) called on the Map itself,
 * an assignment into a Map whose packet and scalar paths add in different orders (small
 * coefficient-based products, rowwise sums), self-adjoint products. With malloc's 16-byte
 * alignment their rounding would follow where the heap happened to place the buffer; memory
 * given to them must be allocated so. (Dot products, norms, GEMV and GEMM do not depend on it.)
 */
using AlignedBuffer = std::vector<double, Eigen::aligned_allocator<double>>;

/**
 * The sum of the stored entries of `A`, added one after the other in storage order. Eigen's
 * SparseMatrix::sum() adds them with vector instructions from the first 64-byte boundary of
 * its value array, which `new` places anywhere on 16 bytes: its rounding changed with the
 * allocations the process made before (the area of a mesh, hence a whole solve: one small
 * allocation changed the worst residual of 400 pairs from 3.8e-11 to 5.3e-10).
 */
inline double SumOfEntries(const SparseMatrix& A)
{
  double sum = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
  {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
    {
      sum += it.value();
    }
  }
  return sum;
}

/// #V by 3 point coordinates, one point a row.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 point indices, one triangle a row.
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// #T by 4 point indices, one tetrahedron a row (either orientation).
using Tetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

/**
 * A triangle soup (a surface) or a tetrahedron soup (a volume): points, and triangles or
 * tetrahedra indexing them. No connectivity is assumed. A mesh holds triangles or tetrahedra,
 * not both (PrepareMesh refuses a mix): a surface has the operators of the Laplace-Beltrami
 * operator, a volume those of the Laplacian of the solid (Operators/Operators.h).
 */
struct TriangleMesh
{
  Points Vertices;
  Triangles Faces;
  Tetrahedra Tets;
  /// Whether this is a volume (it has tetrahedra).
  bool IsVolume() const { return this->Tets.rows() > 0; }
  /// A point cloud: points and no cells (ComputeBasis then uses PointCloudLaplacian).
  bool IsPointCloud() const
  {
    return this->Vertices.rows() > 0 && this->Faces.rows() == 0 && this->Tets.rows() == 0;
  }
};

/// Thrown when the input cannot be processed (bad indices, NaN coordinates, too many eigenpairs).
class InvalidInput : public std::invalid_argument
{
public:
  using std::invalid_argument::invalid_argument;
};

/// Thrown when a solver does not deliver what it promised. Carries the number of pairs it had.
class SolverFailure : public std::runtime_error
{
public:
  SolverFailure(const std::string& what, int converged = 0)
    : std::runtime_error(what)
    , Converged(converged)
  {
  }
  /// Number of eigenpairs that had converged when the solver gave up.
  int Converged;
};

/// Thrown when a Monitor reports that the user cancelled the computation.
class Cancelled : public std::runtime_error
{
public:
  Cancelled()
    : std::runtime_error("computation cancelled")
  {
  }
};
} // namespace spectral

#endif
