// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsArrays.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkTable.h"

#include "Spectral/Operators/Operators.h"
#include "Spectral/Operators/PointCloud.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

std::string Missing(vtkDataSet* input, const char* what, const char* name)
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
std::string FindBasis(vtkDataSet* input, Basis& basis)
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
// The number of edges that more than two distinct triangles of the core's mesh share: the
// triangles the core keeps, so duplicated ones count once and degenerate ones (zero area, which
// the core leaves out with its own warning) not at all. Triangles with an index out of range,
// which the core refuses, are skipped.
static vtkIdType NonManifoldEdges(const spectral::TriangleMesh& mesh)
{
  const spectral::Triangles& faces = mesh.Faces;
  const Eigen::Index points = mesh.Vertices.rows();
  std::vector<std::array<int, 3>> distinct;
  distinct.reserve(static_cast<std::size_t>(faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
  {
    std::array<int, 3> face = { faces(f, 0), faces(f, 1), faces(f, 2) };
    std::sort(face.begin(), face.end());
    if (face[0] >= 0 && face[2] < points && face[0] != face[1] && face[1] != face[2] &&
      !spectral::IsDegenerateTriangle(mesh, static_cast<int>(f)))
    {
      distinct.push_back(face);
    }
  }
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  std::vector<std::uint64_t> edges;
  edges.reserve(distinct.size() * 3);
  for (const auto& face : distinct)
  {
    for (const auto& edge : { std::make_pair(face[0], face[1]),
           std::make_pair(face[0], face[2]),
           std::make_pair(face[1], face[2]) })
    {
      edges.push_back((static_cast<std::uint64_t>(static_cast<std::uint32_t>(edge.first)) << 32) |
        static_cast<std::uint32_t>(edge.second));
    }
  }
  std::sort(edges.begin(), edges.end());
  vtkIdType count = 0;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
    {
      ++j;
    }
    count += j - i > 2 ? 1 : 0;
    i = j;
  }
  return count;
}

//------------------------------------------------------------------------------
bool IsSpectrumOnly(vtkDataSet* input)
{
  return !input->GetPointData()->GetArray(vtkManifoldHarmonicsNames::Harmonics) &&
    input->GetPointData()->GetArray(vtkManifoldHarmonicsNames::Mass) &&
    input->GetFieldData()->GetArray(vtkManifoldHarmonicsNames::Eigenvalues);
}

//------------------------------------------------------------------------------
std::string MissingBasisAdvice(vtkDataSet* input)
{
  if (IsSpectrumOnly(input))
  {
    return "the basis upstream was computed with EigenvaluesOnly, which gives the eigenvalues "
           "and the mass without the harmonics: turn EigenvaluesOnly off in "
           "ManifoldHarmonicBasis (vtkManifoldHarmonicBasis).";
  }
  vtkPointSet* points = vtkPointSet::SafeDownCast(input);
  if (points && points->GetNumberOfPoints() > 0 && !ToCoreMesh(points).HasCells())
  {
    return "the input has no polygons or volume cells, so ManifoldHarmonicBasis passed it "
           "through without a basis. Give it a surface (polygons or triangle strips) or a "
           "volume (tetrahedra, hexahedra, wedges, pyramids).";
  }
  return "compute the basis with ManifoldHarmonicBasis (vtkManifoldHarmonicBasis) upstream.";
}

//------------------------------------------------------------------------------
std::string NotFiniteOnSurface(const std::string& name, const char* what, const char* remedy)
{
  return "The point-data array '" + name +
    "' holds values that are not finite (NaN or infinity) at points of the surface: " + what +
    " is undefined. " + remedy + ", or replace those values first.";
}

//------------------------------------------------------------------------------
bool CoreMesh::IsPointCloud() const
{
  return this->Mesh.Vertices.rows() > 0 && !this->HasCells() && this->LineCells == 0 &&
    this->UnsupportedCells == 0;
}

//------------------------------------------------------------------------------
std::string CoreMesh::Problem() const
{
  std::ostringstream problem;
  if (this->UnsupportedCells > 0)
  {
    problem << this->UnsupportedCells << " cells are of a kind the harmonics do not take (the "
            << "first a " << this->UnsupportedType
            << "): give linear cells (Tessellate in ParaView, vtkTessellatorFilter, turns "
               "quadratic cells into linear ones).";
  }
  else if (this->SurfaceCells > 0 && this->VolumeCells > 0)
  {
    problem << "The input mixes " << this->SurfaceCells << " 2-D cells (triangles, polygons) and "
            << this->VolumeCells
            << " 3-D cells (tetrahedra, hexahedra, ...): the harmonics are those of a surface "
               "or of a volume, not both. Extract one kind first (Extract Cells By Type, "
               "vtkExtractCellsByType).";
  }
  return problem.str();
}

//------------------------------------------------------------------------------
std::vector<std::string> CoreMesh::Warnings() const
{
  std::vector<std::string> warnings;
  if (this->SplitPolygons > 0)
  {
    warnings.push_back(
      "Triangulating " + std::to_string(this->SplitPolygons) + " polygons and triangle strips.");
  }
  if (this->SplitVolumeCells > 0)
  {
    warnings.push_back("Split " + std::to_string(this->SplitVolumeCells) +
      " hexahedra, voxels, wedges and pyramids into tetrahedra (neighbours split their shared "
      "faces alike).");
  }
  if (this->HasCells() && this->VertexCells + this->LineCells > 0)
  {
    warnings.push_back("Left out " + std::to_string(this->VertexCells) + " vertex and " +
      std::to_string(this->LineCells) + " line cells: the harmonics are those of the " +
      std::to_string(this->SurfaceCells + this->VolumeCells) +
      " surface and volume cells, and points that only vertices or lines use stay where they "
      "are.");
  }
  const vtkIdType nonManifold = NonManifoldEdges(this->Mesh);
  if (nonManifold > 0)
  {
    warnings.push_back(std::to_string(nonManifold) +
      " edges are shared by more than two triangles (non-manifold): the harmonics are those of "
      "the sheets joined along these edges. If they are separate surfaces, split them first "
      "(Connectivity in ParaView, vtkPolyDataConnectivityFilter).");
  }
  return warnings;
}

//------------------------------------------------------------------------------
std::string CoreMesh::PointCloudWarning(int numberOfNeighbors) const
{
  if (!this->IsPointCloud())
  {
    return std::string();
  }
  std::ostringstream text;
  text << "The input has " << this->Mesh.Vertices.rows() << " points and no cells"
       << (this->VertexCells > 0 ? " but vertices" : "")
       << ": it is treated as a point cloud (NumberOfNeighbors = " << numberOfNeighbors
       << " neighbours per point). If it came from a surface reader that dropped its cells "
          "(e.g. a PLY of triangle strips), the harmonics are those of the cloud, not of the "
          "surface: read it with its faces, or rebuild them first (Delaunay 2D or a surface "
          "reconstruction).";
  return text.str();
}

namespace
{
/// What ToCoreMesh makes of a cell type: the one rule of which cells make a surface or a volume.
enum class CellKind
{
  Surface,    ///< triangles, and polygons, quadrilaterals, pixels and strips split into them
  Volume,     ///< tetrahedra, and hexahedra, voxels, wedges and pyramids split into them
  Vertex,     ///< vertices (and empty cells): left out; alone, a point cloud
  Line,       ///< lines and polylines: left out
  Unsupported ///< quadratic, polyhedral and other cells: refused
};

CellKind KindOfCell(int type)
{
  switch (type)
  {
    case VTK_TRIANGLE:
    case VTK_QUAD:
    case VTK_POLYGON:
    case VTK_PIXEL:
    case VTK_TRIANGLE_STRIP:
      return CellKind::Surface;
    case VTK_TETRA:
    case VTK_HEXAHEDRON:
    case VTK_WEDGE:
    case VTK_PYRAMID:
    case VTK_VOXEL:
      return CellKind::Volume;
    case VTK_EMPTY_CELL:
    case VTK_VERTEX:
    case VTK_POLY_VERTEX:
      return CellKind::Vertex;
    case VTK_LINE:
    case VTK_POLY_LINE:
      return CellKind::Line;
    default:
      return CellKind::Unsupported;
  }
}

/// The faces of the linear 3-D cells, as local point ids in cyclic order.
using Faces = std::vector<std::vector<int>>;
const Faces HexahedronFaces = { { 0, 3, 2, 1 },
  { 4, 5, 6, 7 },
  { 0, 1, 5, 4 },
  { 1, 2, 6, 5 },
  { 2, 3, 7, 6 },
  { 3, 0, 4, 7 } };
const Faces WedgeFaces = { { 0, 1, 2 },
  { 3, 5, 4 },
  { 0, 1, 4, 3 },
  { 1, 2, 5, 4 },
  { 2, 0, 3, 5 } };
const Faces PyramidFaces = { { 0, 1, 2, 3 }, { 0, 1, 4 }, { 1, 2, 4 }, { 2, 3, 4 }, { 3, 0, 4 } };

/// The cells being collected.
struct Collector
{
  explicit Collector(vtkPoints* points)
    : Points(points)
  {
  }

  vtkPoints* Points;
  std::vector<int> Triangles;
  std::vector<int> Tets;
  vtkNew<vtkPolygon> Polygon;
  vtkNew<vtkIdList> PolygonTriangles;

  void Triangle(vtkIdType a, vtkIdType b, vtkIdType c)
  {
    this->Triangles.insert(
      this->Triangles.end(), { static_cast<int>(a), static_cast<int>(b), static_cast<int>(c) });
  }

  /// A convex cell coned from its point of smallest id (see CoreMesh).
  void Split(const vtkIdType* pts, const Faces& faces)
  {
    int apex = 0;
    for (const auto& face : faces)
    {
      for (int local : face)
      {
        apex = pts[local] < pts[apex] ? local : apex;
      }
    }
    for (const auto& face : faces)
    {
      if (std::find(face.begin(), face.end(), apex) != face.end())
      {
        continue;
      }
      std::vector<vtkIdType> ids;
      for (int local : face)
      {
        ids.push_back(pts[local]);
      }
      const int low = static_cast<int>(std::min_element(ids.begin(), ids.end()) - ids.begin());
      const int first = ids.size() == 4 ? low % 2 : 0; // the diagonal through the smallest id
      for (std::size_t t = 1; t + 1 < ids.size(); ++t)
      {
        this->Tets.insert(this->Tets.end(),
          { static_cast<int>(pts[apex]),
            static_cast<int>(ids[first]),
            static_cast<int>(ids[(first + t) % ids.size()]),
            static_cast<int>(ids[(first + t + 1) % ids.size()]) });
      }
    }
  }

  /// Adds one input cell; counts it in `out`.
  void Add(int type, vtkIdType npts, const vtkIdType* pts, CoreMesh& out)
  {
    switch (KindOfCell(type))
    {
      case CellKind::Surface:
        ++out.SurfaceCells;
        out.SplitPolygons += type == VTK_TRIANGLE ? 0 : 1;
        this->AddSurfaceCell(type, npts, pts);
        break;
      case CellKind::Volume:
        ++out.VolumeCells;
        out.SplitVolumeCells += type == VTK_TETRA ? 0 : 1;
        this->AddVolumeCell(type, pts);
        break;
      case CellKind::Vertex:
        ++out.VertexCells;
        break;
      case CellKind::Line:
        ++out.LineCells;
        break;
      case CellKind::Unsupported:
        if (out.UnsupportedCells++ == 0)
        {
          out.UnsupportedType = vtkCellTypes::GetClassNameFromTypeId(type);
        }
    }
  }

  /// The triangles of a 2-D cell (KindOfCell Surface): the one polygon rule, for every kind of
  /// point set: a polygon or quadrilateral of more than 3 points by vtkPolygon::Triangulate (ear
  /// cutting: concave polygons too; as vtkTriangleFilter does), a strip as consecutive triples,
  /// a pixel along its diagonal from point 0 to point 3.
  void AddSurfaceCell(int type, vtkIdType npts, const vtkIdType* pts)
  {
    if ((type == VTK_POLYGON || type == VTK_QUAD) && npts > 3)
    {
      this->AddPolygon(npts, pts);
    }
    else if (type == VTK_PIXEL)
    {
      this->Triangle(pts[0], pts[1], pts[3]);
      this->Triangle(pts[0], pts[3], pts[2]);
    }
    else if (type == VTK_TRIANGLE_STRIP)
    {
      for (vtkIdType c = 0; c + 2 < npts; ++c)
      {
        this->Triangle(pts[c], pts[c + 1], pts[c + 2]);
      }
    }
    else if (npts == 3)
    {
      this->Triangle(pts[0], pts[1], pts[2]);
    }
  }

  /// The triangles vtkPolygon::Triangulate makes of a polygon (none when it finds none). A
  /// polygon naming a point that does not exist becomes a fan, for the core to refuse its ids.
  void AddPolygon(vtkIdType npts, const vtkIdType* pts)
  {
    const vtkIdType numPoints = this->Points ? this->Points->GetNumberOfPoints() : 0;
    if (std::any_of(
          pts, pts + npts, [numPoints](vtkIdType id) { return id < 0 || id >= numPoints; }))
    {
      for (vtkIdType c = 1; c + 1 < npts; ++c)
      {
        this->Triangle(pts[0], pts[c], pts[c + 1]);
      }
      return;
    }
    this->Polygon->PointIds->SetNumberOfIds(npts);
    this->Polygon->Points->SetNumberOfPoints(npts);
    for (vtkIdType i = 0; i < npts; ++i)
    {
      this->Polygon->PointIds->SetId(i, pts[i]);
      this->Polygon->Points->SetPoint(i, this->Points->GetPoint(pts[i]));
    }
    this->Polygon->Triangulate(this->PolygonTriangles);
    const vtkIdType* local = this->PolygonTriangles->GetPointer(0);
    for (vtkIdType t = 0; t + 2 < this->PolygonTriangles->GetNumberOfIds(); t += 3)
    {
      this->Triangle(pts[local[t]], pts[local[t + 1]], pts[local[t + 2]]);
    }
  }

  /// The tetrahedra of a 3-D cell (KindOfCell Volume).
  void AddVolumeCell(int type, const vtkIdType* pts)
  {
    if (type == VTK_TETRA)
    {
      this->Tets.insert(this->Tets.end(),
        { static_cast<int>(pts[0]),
          static_cast<int>(pts[1]),
          static_cast<int>(pts[2]),
          static_cast<int>(pts[3]) });
    }
    else if (type == VTK_VOXEL)
    {
      const vtkIdType hexahedron[8] = {
        pts[0], pts[1], pts[3], pts[2], pts[4], pts[5], pts[7], pts[6]
      };
      this->Split(hexahedron, HexahedronFaces);
    }
    else
    {
      this->Split(pts,
        type == VTK_HEXAHEDRON ? HexahedronFaces : (type == VTK_WEDGE ? WedgeFaces : PyramidFaces));
    }
  }
};
} // anonymous namespace

//------------------------------------------------------------------------------
CoreMesh ToCoreMesh(vtkPointSet* input)
{
  CoreMesh out;
  if (input->GetPoints())
  {
    out.Mesh.Vertices = Signal(input->GetPoints()->GetData()).View();
  }
  Collector cells(input->GetPoints());
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  // Ghost cells (copies of other processes' cells) are left out: vtkManifoldHarmonicsGhosts.h.
  vtkUnsignedCharArray* ghosts = vtkManifoldHarmonicsGhosts::CellGhosts(input);
  const auto counted = [ghosts](vtkIdType cell)
  { return !ghosts || !(ghosts->GetValue(cell) & vtkManifoldHarmonicsGhosts::IgnoredCellFlags); };
  if (vtkPolyData* poly = vtkPolyData::SafeDownCast(input))
  {
    // The cell arrays directly: no cell-type lookup (BuildCells) on a large surface. Cell ids
    // run over vertices, lines, polygons and strips, in this order.
    vtkIdType cell = 0;
    const auto each = [&](vtkCellArray* array, int type)
    {
      auto it = vtk::TakeSmartPointer(array->NewIterator());
      for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
      {
        if (!counted(cell))
        {
          continue;
        }
        it->GetCurrentCell(size, ids);
        const int kind = type != VTK_POLYGON ? type : (size == 3 ? VTK_TRIANGLE : VTK_POLYGON);
        cells.Add(kind, size, ids, out);
      }
    };
    each(poly->GetVerts(), VTK_POLY_VERTEX);
    each(poly->GetLines(), VTK_POLY_LINE);
    each(poly->GetPolys(), VTK_POLYGON);
    each(poly->GetStrips(), VTK_TRIANGLE_STRIP);
  }
  else
  {
    vtkNew<vtkIdList> points;
    for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
    {
      if (counted(c))
      {
        input->GetCellPoints(c, points);
        cells.Add(input->GetCellType(c), points->GetNumberOfIds(), points->GetPointer(0), out);
      }
    }
  }
  out.Mesh.Faces = Eigen::Map<const spectral::Triangles>(
    cells.Triangles.data(), static_cast<Eigen::Index>(cells.Triangles.size() / 3), 3);
  out.Mesh.Tets = Eigen::Map<const spectral::Tetrahedra>(
    cells.Tets.data(), static_cast<Eigen::Index>(cells.Tets.size() / 4), 4);
  return out;
}

//------------------------------------------------------------------------------
bool HasCellsOrIsPointCloud(vtkPointSet* input)
{
  if (input->GetNumberOfPoints() == 0)
  {
    return false;
  }
  if (vtkPolyData* polyData = vtkPolyData::SafeDownCast(input))
  {
    // Without building its cell map: polygons and strips are surface cells, the rest vertices
    // and lines.
    return polyData->GetNumberOfPolys() + polyData->GetNumberOfStrips() > 0 ||
      polyData->GetNumberOfLines() == 0;
  }
  bool others = false; // lines, or cells of a kind ToCoreMesh does not take
  for (vtkIdType c = 0; c < input->GetNumberOfCells(); ++c)
  {
    const CellKind kind = KindOfCell(input->GetCellType(c));
    if (kind == CellKind::Surface || kind == CellKind::Volume)
    {
      return true;
    }
    others = others || kind != CellKind::Vertex;
  }
  return !others;
}

//------------------------------------------------------------------------------
int OutputLikeInput(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkPointSet* input =
    inInfo ? vtkPointSet::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())) : nullptr;
  if (!input)
  {
    return 0;
  }
  vtkInformation* info = outputVector->GetInformationObject(0);
  vtkDataObject* output = info->Get(vtkDataObject::DATA_OBJECT());
  if (!output || !output->IsA(input->GetClassName()))
  {
    vtkSmartPointer<vtkDataObject> created = vtk::TakeSmartPointer(input->NewInstance());
    info->Set(vtkDataObject::DATA_OBJECT(), created);
  }
  return 1;
}

//------------------------------------------------------------------------------
std::vector<double> EdgeSums(vtkPointSet* input)
{
  return input->GetNumberOfPoints() > 0 ? EdgeSums(ToCoreMesh(input))
                                        : std::vector<double>{ 0.0, 0.0 };
}

//------------------------------------------------------------------------------
const MeshFigures& MeshFiguresCache::Of(vtkPointSet* input)
{
  if (input != this->Input.GetPointer() || input->GetMTime() != this->Time)
  {
    this->Figures = MeshFigures();
    if (input->GetNumberOfPoints() > 0)
    {
      const CoreMesh cells = ToCoreMesh(input);
      this->Figures.EdgeSums = EdgeSums(cells);
      this->Figures.IsVolume = cells.Mesh.IsVolume();
    }
    this->Input = input;
    this->Time = input->GetMTime();
  }
  return this->Figures;
}

//------------------------------------------------------------------------------
std::vector<double> EdgeSums(const CoreMesh& cells)
{
  if (cells.IsPointCloud())
  {
    return spectral::CloudEdgeSums(cells.Mesh.Vertices);
  }
  const double count = spectral::EdgeCount(cells.Mesh);
  return { spectral::MeanEdgeLength(cells.Mesh) * count, count };
}
} // namespace vtkManifoldHarmonicsArrays
