// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Mesh.h
 * @brief Types shared by the spectral core: the triangle mesh and the matrix aliases.
 *
 * The core (namespace spectral) is plain C++17 on Eigen, Spectra and CHOLMOD. It never includes a
 * VTK header; vtkManifoldHarmonicBasis converts a vtkPolyData into a TriangleMesh.
 */
#ifndef spectral_Mesh_h
#define spectral_Mesh_h

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <stdexcept>
#include <string>

namespace spectral
{
/// Sparse column-major matrix of doubles with int indices (the CHOLMOD "int" interface).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
/// Dense column-major matrix of doubles.
using DenseMatrix = Eigen::MatrixXd;
/// Dense column vector of doubles.
using Vector = Eigen::VectorXd;
/// #V by 3 point coordinates, one point a row.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 point indices, one triangle a row.
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A triangle soup: points and triangles indexing them. No connectivity is assumed.
struct TriangleMesh
{
  Points Vertices;
  Triangles Faces;
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
