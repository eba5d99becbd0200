// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Operators.h
 * @brief Discrete Laplace operators of a triangle or tetrahedral mesh: cotan stiffness and mass.
 *
 * The generalized eigenproblem L h = lambda M h of these matrices defines the manifold harmonics
 * (B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics", Computer Graphics
 * Forum 27(2), 2008). On a surface they are the linear finite elements of the Laplace-Beltrami
 * operator (cotangent weights); on a volume those of the Laplacian of the solid: the P1
 * stiffness of each tetrahedron, |T| grad(phi_i) . grad(phi_j) with phi the hat functions
 * (equivalently an edge weight l_kl cot(theta_kl) / 6 from the dihedral angle theta_kl at the
 * opposite edge kl), and a quarter of its volume to each corner as lumped mass. Natural
 * (Neumann) boundary conditions hold on open boundaries; Laplacian.h eliminates the boundary
 * points for Dirichlet conditions.
 *
 * Used by vtkManifoldHarmonicBasis; tested by Testing/Core/TestOperators.cxx.
 */
#ifndef spectral_Operators_h
#define spectral_Operators_h

#include "Common/Mesh.h"

#include <vector>

namespace spectral
{
/// The part of a mesh that the operators are built on, and how it maps to the input.
struct PreparedMesh
{
  /// Triangles of non-zero area (or tetrahedra of non-zero volume), on the points they use,
  /// renumbered 0..#used-1.
  TriangleMesh Mesh;
  /// Whether the input was a volume (tetrahedra), even if none of them remains.
  bool Volume = false;
  /// For each point of Mesh, its index in the input mesh.
  std::vector<int> InputPointIds;
  /// Input triangles (tetrahedra) left out because their area (volume) is numerically zero.
  int DegenerateTriangles = 0;
  /// Input triangles (tetrahedra) left out because an earlier one has the same points (either
  /// orientation): counted twice they would double the local stiffness and mass.
  int DuplicateTriangles = 0;
  /// Input points that no remaining triangle (tetrahedron) uses (their harmonics are zero).
  int UnusedPoints = 0;
  /// Connected components left out by LeaveOutSmallComponents, and their points (which have
  /// zero harmonics, as unused points have).
  int SmallComponents = 0;
  int SmallComponentPoints = 0;
};

/// Largest coordinate magnitude the operators accept: squared areas (edge lengths to the fourth
/// power) stay finite below it.
constexpr double MaxCoordinate = 1e75;

/**
 * The one check of a point's coordinates, for every kind of input.
 * \throws InvalidInput if point `id` has a non-finite coordinate or one of magnitude above
 *         MaxCoordinate.
 */
void CheckCoordinates(const Points& points, Eigen::Index id);

/**
 * Relative size below which a cell is degenerate: twice a triangle's area below it times its
 * longest edge squared, six times a tetrahedron's volume below it times its longest edge cubed
 * (zero-area or zero-volume cells, repeated points, collinear or coplanar corners).
 */
constexpr double DegenerateCellSize = 1e-12;

/**
 * Whether triangle f of `mesh` is degenerate by DegenerateCellSize: the rule PrepareMesh leaves
 * triangles out by, for callers that count something on the triangles it keeps.
 * \param f A row of mesh.Faces whose indices lie in [0, #V).
 */
bool IsDegenerateTriangle(const TriangleMesh& mesh, int f);

/**
 * Keep the triangles (tetrahedra) of non-zero area (volume), once each, and the points they use.
 *
 * Degenerate cells (DegenerateCellSize) carry no stiffness and no mass, so they are left out
 * rather than turned into infinite cotangents.
 *
 * \param input Points and triangles, or points and tetrahedra; indices must lie in [0, #V).
 * \return The compact mesh with the map back to input point ids.
 * \throws InvalidInput for an index out of range, a coordinate that CheckCoordinates refuses
 *         on a used point, or a mesh with both triangles and tetrahedra.
 */
PreparedMesh PrepareMesh(const TriangleMesh& input);

/**
 * Leave out the connected components of fewer than `minimumPoints` points: their triangles are
 * dropped and their points get zero harmonics and mass, like unused points (SmallComponents and
 * SmallComponentPoints count them).
 * \param prepared The output of PrepareMesh.
 * \param minimumPoints Components of at least this many points stay; 0 or 1 keeps all.
 */
PreparedMesh LeaveOutSmallComponents(const PreparedMesh& prepared, int minimumPoints);

/**
 * Cotangent stiffness matrix Q (#V by #V, sparse, symmetric, positive semi-definite).
 *
 * Surface: Q_ij = -(cot a_ij + cot b_ij) / 2 for an edge ij with opposite angles a_ij and b_ij
 * (one angle on a boundary edge), Q_ii = -sum_j Q_ij, so Q 1 = 0. Cotangents come from edge
 * vectors (cot = u.v / |u x v|). Volume: Q_ij = sum over the tetrahedra T with edge ij of
 * |T| grad(phi_i) . grad(phi_j), the gradients from the inverse of the edge matrix and |T| the
 * unsigned volume, so that either orientation gives the same Q. Degenerate cells contribute
 * nothing. The diagonal is stored even where it is zero, so every Q has the pattern of the mesh
 * graph plus the diagonal.
 */
SparseMatrix CotanStiffness(const TriangleMesh& mesh);

/// Lumped (barycentric) mass: D_ii = sum of |t|/3 over the triangles t around point i (of |T|/4
/// over the tetrahedra T around it). Length #V.
Vector LumpedMass(const TriangleMesh& mesh);

/**
 * Consistent (Galerkin) mass matrix B (#V by #V, sparse, symmetric positive definite on used
 * points): B_ij = sum |t|/12 over triangles t with edge ij, B_ii = sum |t|/6 over t around i
 * (|T|/20 and |T|/10 for tetrahedra). Its row sums equal LumpedMass.
 */
SparseMatrix ConsistentMass(const TriangleMesh& mesh);

/**
 * A sparse symmetric operator assembled from per-triangle contributions, shared by the extrinsic
 * operators here and the intrinsic ones of IntrinsicDelaunay.h. Every diagonal entry is stored,
 * also where it stays zero, so all operators of a mesh have the pattern of its graph plus the
 * diagonal.
 */
class TriangleAssembly
{
public:
  /// n unknowns; room for `perTriangle` entries of each of `triangles` triangles.
  TriangleAssembly(Eigen::Index n, Eigen::Index triangles, int perTriangle);
  /// Edge weight w between points i and j: -w at (i, j) and (j, i), +w at (i, i) and (j, j).
  void AddEdgeWeight(int i, int j, double w);
  /// Galerkin mass of a triangle of the given area: area/6 on its diagonal, area/12 off it.
  void AddMassBlock(int a, int b, int c, double area);
  /// Galerkin mass of a tetrahedron of the given volume: volume/10 on its diagonal, volume/20
  /// off it.
  void AddMassBlock(const int (&corners)[4], double volume);
  /// The assembled matrix (duplicates summed), compressed.
  SparseMatrix Matrix() const;

private:
  Eigen::Index Size;
  std::vector<Eigen::Triplet<double>> Triplets;
};

/// The diagonal matrix diag(d) in sparse form.
SparseMatrix Diagonal(const Vector& d);

/// The diagonal of the bounding box of the points; 0 for none.
double BoundingBoxDiagonal(const Points& points);

/// Total area of the triangles.
double SurfaceArea(const TriangleMesh& mesh);

/// The measure of the mesh: the total volume of its tetrahedra (unsigned) for a volume, the area
/// of its triangles otherwise.
double Measure(const TriangleMesh& mesh);

/**
 * The points on the boundary of the mesh: those of the edges that one triangle alone uses, for
 * a surface, or of the faces that one tetrahedron alone uses, for a volume (1 on the boundary,
 * 0 elsewhere; length #V). A closed surface has none.
 */
std::vector<char> BoundaryPoints(const TriangleMesh& mesh);

/**
 * The points of a piece of a mesh that another piece may hold: those of a facet (an edge of a
 * triangle, a face of a tetrahedron) that not exactly two cells of the piece share (a seam
 * between pieces, a boundary of the mesh, a non-manifold facet). 1 or 0 per point, as
 * BoundaryPoints, which marks the facets of one cell only: both count facets in FacetPoints.
 */
std::vector<char> BorderPoints(const TriangleMesh& mesh);

/// The points of the facets whose number of cells `marked` accepts (1 or 0 per point).
std::vector<char> FacetPoints(const TriangleMesh& mesh, bool (*marked)(std::size_t cells));

/// The connected component of each point (points joined by triangle edges).
struct ComponentLabels
{
  /// For each point, its component in [0, Count), numbered in the order of their first points.
  std::vector<int> Label;
  /// Number of components; isolated points count as components of their own.
  int Count = 0;
};

/// Label the connected components of a mesh (points joined by the edges of its cells).
ComponentLabels LabelComponents(const TriangleMesh& mesh);

/// Label the connected components of the graph of a sparse symmetric matrix (rows joined by
/// their stored entries, explicit zeros included).
ComponentLabels LabelComponents(const SparseMatrix& pattern);

/// Number of connected components (points joined by cell edges; isolated points count too).
int ConnectedComponents(const TriangleMesh& mesh);

/// The number of cell edges, each counted once per cell: 3 per triangle, 6 per tetrahedron.
double EdgeCount(const TriangleMesh& mesh);

/// Mean edge length over all cell edges (each edge counted once per cell). 0 for no cells.
double MeanEdgeLength(const TriangleMesh& mesh);

/**
 * Two boundary points of a surface closer than this fraction of its mean edge length
 * (MeanEdgeLength), and not joined by an edge, look like the two copies of one seam point that
 * welding (Common/Seams.h) left apart, their gap above SeamTolerance: FindOpenSeams.
 */
constexpr double OpenSeamGap = 0.01;

/// What FindOpenSeams found.
struct OpenSeams
{
  /// Pairs of such points (a point with several such partners counts once).
  long long Pairs = 0;
  /// The largest gap of those pairs, as a fraction of the bounding box diagonal of the finite
  /// points: a SeamTolerance above it welds them.
  double LargestGap = 0.0;
};

/**
 * The boundary points of the surface `mesh` (on an edge of a single triangle) that lie within
 * OpenSeamGap times its mean edge length of another boundary point they share no edge with: a
 * seam left open, which makes the harmonics those of a surface cut there. A mesh without
 * triangles, with a point id out of range (which PrepareMesh refuses) or with a non-finite point
 * on a triangle has none.
 */
OpenSeams FindOpenSeams(const TriangleMesh& mesh);

/**
 * The number of edges that two triangles of `faces` traverse in the same direction (a, b): none
 * on a consistently oriented surface; at least one on a non-orientable one (a Moebius strip)
 * and where triangles were flipped. Edges of a single triangle, repeated corners and negative
 * ids are ignored.
 */
long long OrientationConflicts(const Triangles& faces);
} // namespace spectral

#endif
