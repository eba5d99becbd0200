// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Operators/NearestNeighbors.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace spectral
{
//------------------------------------------------------------------------------
NearestNeighbors::NearestNeighbors(const Points& points)
  : Order(static_cast<std::size_t>(points.rows()))
{
  std::iota(this->Order.begin(), this->Order.end(), 0);
  const int n = static_cast<int>(points.rows());
  this->Nodes.reserve(static_cast<std::size_t>(2 * (n / LeafSize + 1)));
  if (n > 0)
  {
    this->Build(points, 0, n);
  }
  this->Sorted.resize(points.rows(), 3);
  for (int i = 0; i < n; ++i)
  {
    this->Sorted.row(i) = points.row(this->Order[static_cast<std::size_t>(i)]);
  }
}

//------------------------------------------------------------------------------
int NearestNeighbors::Build(const Points& points, int first, int last)
{
  const int id = static_cast<int>(this->Nodes.size());
  this->Nodes.emplace_back();
  this->Nodes.back().First = first;
  this->Nodes.back().Last = last;
  if (last - first <= LeafSize)
  {
    return id;
  }
  Eigen::RowVector3d low = points.row(this->Order[static_cast<std::size_t>(first)]);
  Eigen::RowVector3d high = low;
  for (int i = first + 1; i < last; ++i)
  {
    low = low.cwiseMin(points.row(this->Order[static_cast<std::size_t>(i)]));
    high = high.cwiseMax(points.row(this->Order[static_cast<std::size_t>(i)]));
  }
  int axis = 0;
  (high - low).maxCoeff(&axis);
  const int middle = first + (last - first) / 2;
  std::nth_element(this->Order.begin() + first,
    this->Order.begin() + middle,
    this->Order.begin() + last,
    [&points, axis](int a, int b) { return points(a, axis) < points(b, axis); });
  const double split = points(this->Order[static_cast<std::size_t>(middle)], axis);
  // Left holds [first, middle), all <= split; right [middle, last), all >= split.
  const int left = this->Build(points, first, middle);
  const int right = this->Build(points, middle, last);
  Node& node = this->Nodes[static_cast<std::size_t>(id)];
  node.Left = left;
  node.Right = right;
  node.Axis = axis;
  node.Split = split;
  return id;
}

//------------------------------------------------------------------------------
void NearestNeighbors::Nearest(const Eigen::Vector3d& q,
  int k,
  int exclude,
  std::vector<Neighbor>& out) const
{
  out.clear();
  if (k <= 0 || this->Nodes.empty())
  {
    return;
  }
  this->SearchNearest(0, q, k, exclude, out); // a max-heap on the squared distance
  std::sort_heap(out.begin(), out.end());
}

//------------------------------------------------------------------------------
void NearestNeighbors::SearchNearest(int id,
  const Eigen::Vector3d& q,
  int k,
  int exclude,
  std::vector<Neighbor>& heap) const
{
  const Node& node = this->Nodes[static_cast<std::size_t>(id)];
  if (node.Left < 0)
  {
    for (int i = node.First; i < node.Last; ++i)
    {
      const int row = this->Order[static_cast<std::size_t>(i)];
      if (row == exclude)
      {
        continue;
      }
      const double d2 = (this->Sorted.row(i).transpose() - q).squaredNorm();
      if (static_cast<int>(heap.size()) < k)
      {
        heap.emplace_back(d2, row);
        std::push_heap(heap.begin(), heap.end());
      }
      else if (Neighbor(d2, row) < heap.front())
      {
        std::pop_heap(heap.begin(), heap.end());
        heap.back() = Neighbor(d2, row);
        std::push_heap(heap.begin(), heap.end());
      }
    }
    return;
  }
  const double gap = q[node.Axis] - node.Split;
  const int near = gap <= 0.0 ? node.Left : node.Right;
  const int far = gap <= 0.0 ? node.Right : node.Left;
  this->SearchNearest(near, q, k, exclude, heap);
  if (static_cast<int>(heap.size()) < k || gap * gap <= heap.front().first)
  {
    this->SearchNearest(far, q, k, exclude, heap);
  }
}

//------------------------------------------------------------------------------
void NearestNeighbors::WithinRadius(const Eigen::Vector3d& q,
  double radius,
  std::vector<int>& out) const
{
  out.clear();
  if (!this->Nodes.empty() && radius >= 0.0)
  {
    this->SearchRadius(0, q, radius * radius, out);
  }
}

//------------------------------------------------------------------------------
void NearestNeighbors::SearchRadius(int id,
  const Eigen::Vector3d& q,
  double r2,
  std::vector<int>& out) const
{
  const Node& node = this->Nodes[static_cast<std::size_t>(id)];
  if (node.Left < 0)
  {
    for (int i = node.First; i < node.Last; ++i)
    {
      if ((this->Sorted.row(i).transpose() - q).squaredNorm() <= r2)
      {
        out.push_back(this->Order[static_cast<std::size_t>(i)]);
      }
    }
    return;
  }
  const double gap = q[node.Axis] - node.Split;
  if (gap <= 0.0 || gap * gap <= r2)
  {
    this->SearchRadius(node.Left, q, r2, out);
  }
  if (gap >= 0.0 || gap * gap <= r2)
  {
    this->SearchRadius(node.Right, q, r2, out);
  }
}
} // namespace spectral
