// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Streaming.h"

#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace spectral
{
//------------------------------------------------------------------------------
StreamedFilter::StreamedFilter(const ConstRowView& X, StreamedDesign design)
  : Signals(X)
  , Design(std::move(design))
{
}

//------------------------------------------------------------------------------
BasisSink StreamedFilter::Sink()
{
  BasisSink sink;
  sink.HighestFirst = true;
  sink.Begin = [this](const BasisResult& basis) { this->Begin(basis); };
  sink.Harmonics = [this](int, const Vector& values, const DenseMatrix& harmonics)
  { this->Add(values, harmonics); };
  sink.Restart = [this]() { this->Sum.setZero(); };
  sink.WantedUpTo = [this]() { return this->WantedUpTo; };
  return sink;
}

//------------------------------------------------------------------------------
void StreamedFilter::Begin(const BasisResult& basis)
{
  this->Rows = basis.InputPointIds;
  this->Mass = basis.LumpedMass;
  const Vector& lambda = basis.Pairs.Eigenvalues;
  if (lambda.size() == 0 || !std::isfinite(lambda[lambda.size() - 1]))
  {
    throw InvalidInput("a streamed filter needs the highest eigenvalue before the harmonics");
  }
  this->Parameters = this->Design(lambda[lambda.size() - 1], this->HighFrequencyGain);
  // A harmonic whose gain is the re-injection gain adds nothing (Add): those above the frequency
  // where F becomes constant, if that constant is hfGain (a low pass: 0 and 0), are not solved.
  const double constant = ConstantAbove(this->Parameters);
  const bool flat = std::isfinite(constant) &&
    Gain(this->Parameters, std::nextafter(constant, std::numeric_limits<double>::infinity())) ==
      this->HighFrequencyGain;
  this->WantedUpTo = flat ? constant * constant : std::numeric_limits<double>::infinity();
  const Eigen::Index used = static_cast<Eigen::Index>(this->Rows.size());
  this->Weighted.resize(used, this->Signals.cols());
  for (Eigen::Index r = 0; r < used; ++r)
  {
    const Eigen::Index row = this->Rows[static_cast<std::size_t>(r)];
    if (row < 0 || row >= this->Signals.rows())
    {
      throw InvalidInput("the streamed basis names point " + std::to_string(row) + " of " +
        std::to_string(this->Signals.rows()) + " signals");
    }
    // A point of zero mass adds nothing, even where its signal is not finite (ForwardTransform).
    this->Weighted.row(r) = this->Mass[r] > 0.0 ? (this->Mass[r] * this->Signals.row(row)).eval()
                                                : Eigen::RowVectorXd::Zero(this->Signals.cols());
  }
  this->Sum = DenseMatrix::Zero(used, this->Signals.cols());
  this->Begun = true;
}

//------------------------------------------------------------------------------
void StreamedFilter::Add(const Vector& values, const DenseMatrix& harmonics)
{
  const DenseMatrix coefficients = harmonics.transpose() * this->Weighted;
  const Vector gains = Gains(this->Parameters, values).array() - this->HighFrequencyGain;
  this->Sum.noalias() += harmonics * (gains.asDiagonal() * coefficients);
}

//------------------------------------------------------------------------------
RowMatrix StreamedFilter::Result() const
{
  std::vector<long long> identity(static_cast<std::size_t>(this->Signals.rows()));
  std::iota(identity.begin(), identity.end(), 0LL);
  return this->ResultOn(
    ConstRowView(this->Signals.data(), this->Signals.rows(), this->Signals.cols()), identity);
}

//------------------------------------------------------------------------------
RowMatrix StreamedFilter::ResultOn(const ConstRowView& X, const std::vector<long long>& rowOf) const
{
  if (!this->Begun)
  {
    throw InvalidInput("no basis was streamed into the filter");
  }
  if (static_cast<std::size_t>(X.rows()) != rowOf.size() || X.cols() != this->Signals.cols())
  {
    throw InvalidInput("the signals of a streamed filter's result do not match its points");
  }
  // The position of each row of the streamed mesh among the basis rows (-1: none).
  std::vector<Eigen::Index> position(static_cast<std::size_t>(this->Signals.rows()), -1);
  for (std::size_t r = 0; r < this->Rows.size(); ++r)
  {
    position[static_cast<std::size_t>(this->Rows[r])] = static_cast<Eigen::Index>(r);
  }
  RowMatrix Y = X;
  for (std::size_t i = 0; i < rowOf.size(); ++i)
  {
    const long long row = rowOf[i];
    const Eigen::Index r =
      row >= 0 && row < this->Signals.rows() ? position[static_cast<std::size_t>(row)] : -1;
    if (r >= 0 && this->Mass[r] > 0.0)
    {
      const Eigen::Index point = static_cast<Eigen::Index>(i);
      Y.row(point) = this->HighFrequencyGain * X.row(point) + this->Sum.row(r);
    }
  }
  return Y;
}
} // namespace spectral
