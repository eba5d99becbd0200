// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NearestNeighbors.h
 * @brief A kd-tree over 3-D points: the k nearest points of a query, and the points within a
 *        radius.
 *
 * The tree splits the longest side of each box at the median point until at most
 * NearestNeighbors::LeafSize points remain, so it is balanced whatever the distribution (clouds
 * of varying density, far outliers). Building costs O(n log n); a query about O(log n + k log k).
 * Queries only read the tree, so any number of threads may run them at once. Points at the same
 * distance come in the order of their rows, so the answers depend on the points alone.
 *
 * Used by Operators/PointCloud.cxx; tested by Testing/Core/TestPointCloud.cxx
 * (NearestNeighborsMatchBruteForce).
 */
#ifndef spectral_NearestNeighbors_h
#define spectral_NearestNeighbors_h

#include "Common/Mesh.h"

#include <utility>
#include <vector>

namespace spectral
{
/// A point found by a query: its squared distance to the query and its row in the points.
using Neighbor = std::pair<double, int>;

/// A kd-tree of points (a copy of them is kept, so the input may go away).
class NearestNeighbors
{
public:
  /// Points per leaf: below it, scanning a leaf costs less than descending further.
  static constexpr int LeafSize = 8;

  /// Build the tree of the rows of `points` (finite coordinates).
  explicit NearestNeighbors(const Points& points);

  /**
   * The k points nearest to q, nearest first.
   * \param q The query.
   * \param k How many (fewer are returned when the tree holds fewer points besides `exclude`).
   * \param exclude A row to leave out (the query point itself), or -1.
   * \param out Receives the (squared distance, row) pairs; its storage is reused.
   */
  void Nearest(const Eigen::Vector3d& q, int k, int exclude, std::vector<Neighbor>& out) const;

  /// The rows of the points at distance <= radius from q, in no particular order.
  void WithinRadius(const Eigen::Vector3d& q, double radius, std::vector<int>& out) const;

private:
  struct Node
  {
    /// The points of the node are Order[First, Last).
    int First = 0;
    int Last = 0;
    /// Children, or -1 for a leaf.
    int Left = -1;
    int Right = -1;
    /// Split axis and coordinate: Left holds the points with coordinate <= Split.
    int Axis = 0;
    double Split = 0.0;
  };

  int Build(const Points& points, int first, int last);
  void SearchNearest(int node,
    const Eigen::Vector3d& q,
    int k,
    int exclude,
    std::vector<Neighbor>& heap) const;
  void SearchRadius(int node, const Eigen::Vector3d& q, double r2, std::vector<int>& out) const;

  /// The points in tree order, and for each its row in the input.
  Points Sorted;
  std::vector<int> Order;
  std::vector<Node> Nodes;
};
} // namespace spectral

#endif
