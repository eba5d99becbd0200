// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsArrays.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "Spectral/Operators/Operators.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace
{
/// Copies the values of any array into an n by c row-major matrix of doubles.
struct ReadValues
{
  template<typename ArrayT>
  void operator()(ArrayT* array, spectral::RowMatrix& out) const
  {
    const auto values = vtk::DataArrayValueRange(array);
    out.resize(array->GetNumberOfTuples(), array->GetNumberOfComponents());
    std::copy(values.begin(), values.end(), out.data());
  }
};

/// Writes a row-major matrix into an array sized to match, rounding and clamping when asked.
struct WriteValues
{
  template<typename ArrayT>
  void operator()(ArrayT* array,
    const spectral::RowMatrix& values,
    bool integral,
    double low,
    double high) const
  {
    using ValueT = vtk::GetAPIType<ArrayT>;
    auto range = vtk::DataArrayValueRange(array);
    const double* source = values.data();
    for (auto&& value : range)
    {
      double v = *source++;
      if (integral)
      {
        v = std::isnan(v) ? 0.0 : std::round(std::min(std::max(v, low), high));
      }
      value = static_cast<ValueT>(v);
    }
  }
};

/// f(view) with a row-major view of the basis memory in its own precision (no copy).
template<typename Function>
spectral::RowMatrix InPlace(const vtkManifoldHarmonicsArrays::Basis& basis, const Function& f)
{
  if (basis.Floats)
  {
    return f(spectral::FloatBasisView(basis.Floats, basis.NumberOfPoints, basis.NumberOfHarmonics));
  }
  return f(spectral::BasisView(basis.Doubles, basis.NumberOfPoints, basis.NumberOfHarmonics));
}

std::string Missing(vtkPolyData* input, const char* what, const char* name)
{
  std::ostringstream message;
  message << "Missing " << what << " '" << name
          << "': " << vtkManifoldHarmonicsArrays::MissingBasisAdvice(input);
  return message.str();
}

std::string Mismatch(const char* name, vtkIdType found, const char* what, vtkIdType expected)
{
  std::ostringstream message;
  message << "Array '" << name << "' has " << found << " " << what << " where " << expected
          << " are expected: recompute the basis with ManifoldHarmonicBasis "
             "(vtkManifoldHarmonicBasis) on this mesh.";
  return message.str();
}
} // anonymous namespace

namespace vtkManifoldHarmonicsArrays
{
//------------------------------------------------------------------------------
spectral::RowMatrix Basis::ForwardTransform(const spectral::Vector& mass,
  const spectral::ConstRowView& X,
  int threads) const
{
  return InPlace(*this,
    [&mass, &X, threads](const auto& H)
    { return spectral::ForwardTransform(H, mass, X, threads); });
}

//------------------------------------------------------------------------------
spectral::RowMatrix Basis::FilterSignal(const spectral::Vector& mass,
  const spectral::Vector& gains,
  const spectral::ConstRowView& coefficients,
  const spectral::ConstRowView& X,
  double hfGain,
  int threads) const
{
  return InPlace(*this,
    [&mass, &gains, &coefficients, &X, hfGain, threads](const auto& H)
    { return spectral::FilterSignal(H, mass, gains, coefficients, X, hfGain, threads); });
}

//------------------------------------------------------------------------------
spectral::Vector Basis::MassVector() const
{
  return Signal(this->Mass).View().col(0);
}

//------------------------------------------------------------------------------
spectral::Vector Basis::EigenvalueVector() const
{
  return Signal(this->Eigenvalues).View().col(0);
}

//------------------------------------------------------------------------------
std::string FindBasis(vtkPolyData* input, Basis& basis)
{
  const char* harmonicsName = vtkManifoldHarmonicsNames::Harmonics;
  const char* massName = vtkManifoldHarmonicsNames::Mass;
  const char* eigenvaluesName = vtkManifoldHarmonicsNames::Eigenvalues;
  vtkDataArray* harmonics = input->GetPointData()->GetArray(harmonicsName);
  basis.Mass = input->GetPointData()->GetArray(massName);
  basis.Eigenvalues = input->GetFieldData()->GetArray(eigenvaluesName);
  if (!harmonics)
  {
    return Missing(input, "point data array", harmonicsName);
  }
  if (!basis.Mass)
  {
    return Missing(input, "point data array", massName);
  }
  if (!basis.Eigenvalues)
  {
    return Missing(input, "field data array", eigenvaluesName);
  }
  basis.Harmonics = harmonics;
  if (auto* doubles = vtkArrayDownCast<vtkAOSDataArrayTemplate<double>>(harmonics))
  {
    basis.Doubles = doubles->GetPointer(0);
  }
  else if (auto* floats = vtkArrayDownCast<vtkAOSDataArrayTemplate<float>>(harmonics))
  {
    basis.Floats = floats->GetPointer(0);
  }
  else
  {
    return std::string("Array '") + harmonicsName + "' is a " + harmonics->GetClassName() +
      ", not the vtkDoubleArray or vtkFloatArray that ManifoldHarmonicBasis "
      "(vtkManifoldHarmonicBasis) writes.";
  }
  basis.NumberOfPoints = input->GetNumberOfPoints();
  basis.NumberOfHarmonics = basis.Harmonics->GetNumberOfComponents();
  if (basis.Harmonics->GetNumberOfTuples() != basis.NumberOfPoints)
  {
    return Mismatch(
      harmonicsName, basis.Harmonics->GetNumberOfTuples(), "tuples (points)", basis.NumberOfPoints);
  }
  if (basis.Mass->GetNumberOfTuples() != basis.NumberOfPoints)
  {
    return Mismatch(
      massName, basis.Mass->GetNumberOfTuples(), "tuples (points)", basis.NumberOfPoints);
  }
  if (basis.Mass->GetNumberOfComponents() != 1)
  {
    return Mismatch(massName, basis.Mass->GetNumberOfComponents(), "components", 1);
  }
  if (basis.Eigenvalues->GetNumberOfValues() != basis.NumberOfHarmonics)
  {
    return Mismatch(eigenvaluesName,
      basis.Eigenvalues->GetNumberOfValues(),
      "values (harmonics)",
      basis.NumberOfHarmonics);
  }
  return std::string();
}

//------------------------------------------------------------------------------
Signal::Signal(vtkDataArray* array)
  : Rows(array->GetNumberOfTuples())
  , Cols(array->GetNumberOfComponents())
{
  if (auto* doubles = vtkArrayDownCast<vtkAOSDataArrayTemplate<double>>(array))
  {
    this->Data = doubles->GetPointer(0);
    return;
  }
  ReadValues worker;
  if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::AllTypes>::Execute(
        array, worker, this->Converted))
  {
    worker(array, this->Converted);
  }
  this->Data = this->Converted.data();
}

//------------------------------------------------------------------------------
spectral::ConstRowView Signal::View() const
{
  return spectral::ConstRowView(this->Data, this->Rows, this->Cols);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDoubleArray> NewDoubleArray(const spectral::RowMatrix& values, const char* name)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(static_cast<int>(values.cols()));
  array->SetNumberOfTuples(values.rows());
  std::copy(values.data(), values.data() + values.size(), array->GetPointer(0));
  return array;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataArray> NewArrayLike(vtkDataArray* prototype,
  const spectral::RowMatrix& values,
  const char* name)
{
  vtkSmartPointer<vtkDataArray> array;
  array.TakeReference(prototype->NewInstance());
  array->SetName(name);
  array->SetNumberOfComponents(static_cast<int>(values.cols()));
  array->SetNumberOfTuples(values.rows());
  for (int c = 0; c < prototype->GetNumberOfComponents() && c < values.cols(); ++c)
  {
    if (const char* componentName = prototype->GetComponentName(c))
    {
      array->SetComponentName(c, componentName);
    }
  }
  const int type = array->GetDataType();
  const bool integral = type != VTK_FLOAT && type != VTK_DOUBLE;
  const double low = array->GetDataTypeMin();
  // Just below the top of the range, so that 64-bit maxima (not representable) stay in range.
  const double high = std::nextafter(array->GetDataTypeMax(), 0.0);
  WriteValues worker;
  if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::AllTypes>::Execute(
        array.Get(), worker, values, integral, low, high))
  {
    worker(array.Get(), values, integral, low, high);
  }
  return array;
}

//------------------------------------------------------------------------------
void FillSpectrum(vtkTable* table,
  const spectral::Vector& lambda,
  bool eigenvalueColumn,
  const spectral::Vector* gains,
  const std::vector<SpectrumSignal>& signals)
{
  namespace Names = vtkManifoldHarmonicsNames;
  const vtkIdType m = lambda.size();
  vtkNew<vtkIdTypeArray> index;
  index->SetName(Names::IndexColumn);
  index->SetNumberOfTuples(m);
  spectral::RowMatrix frequency(m, 1);
  for (vtkIdType k = 0; k < m; ++k)
  {
    index->SetValue(k, k);
    frequency(k, 0) = std::sqrt(std::max(lambda[k], 0.0));
  }
  table->AddColumn(index);
  if (eigenvalueColumn)
  {
    table->AddColumn(NewDoubleArray(lambda, Names::EigenvalueColumn));
  }
  table->AddColumn(NewDoubleArray(frequency, Names::FrequencyColumn));
  if (gains)
  {
    table->AddColumn(NewDoubleArray(*gains, Names::GainColumn));
  }
  for (const SpectrumSignal& signal : signals)
  {
    const spectral::RowMatrix magnitude = signal.Coefficients.rowwise().norm();
    table->AddColumn(NewDoubleArray(
      magnitude, Names::Concatenate(signal.Name.c_str(), Names::MagnitudeSuffix).c_str()));
    if (gains)
    {
      const spectral::RowMatrix filtered = gains->cwiseAbs().cwiseProduct(magnitude.col(0));
      const std::string name = signal.Name + Names::FilteredSuffix + Names::MagnitudeSuffix;
      table->AddColumn(NewDoubleArray(filtered, name.c_str()));
    }
  }
}

//------------------------------------------------------------------------------
std::string MissingBasisAdvice(vtkPolyData* input)
{
  if (input->GetNumberOfPoints() > 0 && input->GetNumberOfPolys() == 0 &&
    input->GetNumberOfStrips() == 0)
  {
    return "the input has no polygons, so ManifoldHarmonicBasis passed it through without a "
           "basis. Give it a surface (polygons or triangle strips).";
  }
  return "compute the basis with ManifoldHarmonicBasis (vtkManifoldHarmonicBasis) upstream.";
}
//------------------------------------------------------------------------------
spectral::TriangleMesh SurfaceTriangles(vtkPolyData* surface)
{
  vtkSmartPointer<vtkPolyData> input = vtkManifoldHarmonicsGhosts::CountedCells(surface);
  spectral::TriangleMesh mesh;
  mesh.Vertices = Signal(input->GetPoints()->GetData()).View();
  std::vector<int> corners;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  auto polygons = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
  for (polygons->GoToFirstCell(); !polygons->IsDoneWithTraversal(); polygons->GoToNextCell())
  {
    polygons->GetCurrentCell(size, ids);
    for (vtkIdType c = 1; c + 1 < size; ++c)
    {
      corners.insert(corners.end(),
        { static_cast<int>(ids[0]), static_cast<int>(ids[c]), static_cast<int>(ids[c + 1]) });
    }
  }
  auto strips = vtk::TakeSmartPointer(input->GetStrips()->NewIterator());
  for (strips->GoToFirstCell(); !strips->IsDoneWithTraversal(); strips->GoToNextCell())
  {
    strips->GetCurrentCell(size, ids);
    for (vtkIdType c = 0; c + 2 < size; ++c)
    {
      corners.insert(corners.end(),
        { static_cast<int>(ids[c]), static_cast<int>(ids[c + 1]), static_cast<int>(ids[c + 2]) });
    }
  }
  mesh.Faces = Eigen::Map<const spectral::Triangles>(
    corners.data(), static_cast<Eigen::Index>(corners.size() / 3), 3);
  return mesh;
}

//------------------------------------------------------------------------------
std::vector<double> EdgeSums(vtkPolyData* input)
{
  std::vector<double> sums = { 0.0, 0.0 };
  if (input->GetNumberOfPoints() > 0)
  {
    const spectral::TriangleMesh mesh = SurfaceTriangles(input);
    sums[1] = 3.0 * static_cast<double>(mesh.Faces.rows());
    sums[0] = spectral::MeanEdgeLength(mesh) * sums[1];
  }
  return sums;
}
} // namespace vtkManifoldHarmonicsArrays
