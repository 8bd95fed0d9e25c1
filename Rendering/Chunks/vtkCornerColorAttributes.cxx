#include "vtkCornerColorAttributes.h"

#include "LVDIFVolumeBridge.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationInformationVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkCornerColorAttributes);

vtkCornerColorAttributes::vtkCornerColorAttributes() = default;

const char* vtkCornerColorAttributes::PackedCornerArrayName(int i)
{
  static const char* names[3] = { "lvdif_corners_packed0", "lvdif_corners_packed1", "lvdif_corners_packed2" };
  return (i >= 0 && i < 3) ? names[i] : nullptr;
}

void vtkCornerColorAttributes::PackCorners(const unsigned char rgba[32], float packed[12])
{
  // byte i goes to float i/3, digit i%3 in base 256: below 2^24, so exact in a float
  for (int j = 0; j < 12; ++j)
  {
    unsigned int v = 0;
    for (int d = 0; d < 3 && 3 * j + d < 32; ++d)
    {
      v |= static_cast<unsigned int>(rgba[3 * j + d]) << (8 * d);
    }
    packed[j] = static_cast<float>(v);
  }
}

void vtkCornerColorAttributes::UnpackCorners(const float packed[12], unsigned char rgba[32])
{
  for (int i = 0; i < 32; ++i)
  {
    const auto v = static_cast<unsigned long>(packed[i / 3]);
    rgba[i] = static_cast<unsigned char>((v >> (8 * (i % 3))) & 0xff);
  }
}

unsigned long long vtkCornerColorAttributes::MortonCode(int i, int j, int k)
{
  auto spread = [](unsigned long long v) {
    v &= 0x1fffffull; // 21 bits
    v = (v | (v << 32)) & 0x1f00000000ffffull;
    v = (v | (v << 16)) & 0x1f0000ff0000ffull;
    v = (v | (v << 8)) & 0x100f00f00f00f00full;
    v = (v | (v << 4)) & 0x10c30c30c30c30c3ull;
    v = (v | (v << 2)) & 0x1249249249249249ull;
    return v;
  };
  return spread(static_cast<unsigned int>(i)) | (spread(static_cast<unsigned int>(j)) << 1) |
    (spread(static_cast<unsigned int>(k)) << 2);
}

bool vtkCornerColorAttributes::HasCornerColors(vtkPolyData* pd)
{
  if (!pd)
  {
    return false;
  }
  auto* corners = vtkUnsignedCharArray::SafeDownCast(pd->GetCellData()->GetArray("corner_rgba"));
  vtkDataArray* ijk = pd->GetCellData()->GetArray("cell_ijk");
  return corners && corners->GetNumberOfComponents() == 32 && ijk && ijk->GetNumberOfComponents() == 3;
}

int vtkCornerColorAttributes::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  if (!input || !output)
  {
    return 0;
  }
  // a refusal is this filter's one error (FailReported drops the executive's
  // "returned failure for request" dump that followed it)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (this->Spacing[0] <= 0 || this->Spacing[1] <= 0 || this->Spacing[2] <= 0)
  {
    vtkErrorMacro("Spacing must be positive, got " << this->Spacing[0] << " " << this->Spacing[1] << " "
                                                   << this->Spacing[2]);
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  if (!HasCornerColors(input))
  {
    vtkErrorMacro("Input lacks the cell arrays corner_rgba (unsigned char, 32 components) and "
                  "cell_ijk (3 components)");
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  auto* corners = vtkUnsignedCharArray::SafeDownCast(input->GetCellData()->GetArray("corner_rgba"));
  vtkDataArray* ijk = input->GetCellData()->GetArray("cell_ijk");

  vtkCellArray* polys = input->GetPolys();
  // Cell ids of polygons start after the vertices and lines (vtkPolyData's cell order).
  const vtkIdType firstPoly = input->GetNumberOfVerts() + input->GetNumberOfLines();
  const vtkIdType nPolys = polys->GetNumberOfCells();
  auto allTriangles = [nPolys](auto* offsets) {
    const auto* off = offsets->GetPointer(0);
    for (vtkIdType p = 0; p < nPolys; ++p)
    {
      if (off[p + 1] - off[p] != 3)
      {
        return false;
      }
    }
    return true;
  };
  const bool triangleOnly =
    polys->IsStorage64Bit() ? allTriangles(polys->GetOffsetsArray64()) : allTriangles(polys->GetOffsetsArray32());
  vtkIdType triangles = triangleOnly ? nPolys : 0;
  if (!triangleOnly)
  {
    auto it = vtk::TakeSmartPointer(polys->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      const vtkIdType n = it->GetCurrentCell()->GetNumberOfIds();
      triangles += n >= 3 ? n - 2 : 0;
    }
  }

  vtkPoints* inPts = input->GetPoints();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(3 * triangles);
  vtkPointData* outPd = output->GetPointData();
  outPd->CopyAllocate(input->GetPointData(), 3 * triangles);
  // Point data is copied in one batch at the end (typed, much faster than per point).
  vtkNew<vtkIdList> fromIds, toIds;
  fromIds->SetNumberOfIds(3 * triangles);
  toIds->SetNumberOfIds(3 * triangles);
  vtkNew<vtkFloatArray> local;
  local->SetName(LocalArrayName());
  local->SetNumberOfComponents(3);
  local->SetNumberOfTuples(3 * triangles);
  vtkNew<vtkFloatArray> cornerArrays[3];
  for (int c = 0; c < 3; ++c)
  {
    cornerArrays[c]->SetName(PackedCornerArrayName(c));
    cornerArrays[c]->SetNumberOfComponents(4);
    cornerArrays[c]->SetNumberOfTuples(3 * triangles);
  }
  vtkCellData* outCd = output->GetCellData();
  outCd->CopyFieldOff("corner_rgba");
  outCd->CopyFieldOff("cell_ijk");
  outCd->CopyAllocate(input->GetCellData(), triangles);
  vtkNew<vtkCellArray> outPolys;
  outPolys->AllocateExact(triangles, 3 * triangles);

  // the polygons in output order: as given, or by their cells' Morton codes
  std::vector<vtkIdType> order(static_cast<std::size_t>(nPolys));
  // The marching cubes' meshes (float points, int cell_ijk, triangles only, no
  // other cell arrays) take typed loops below: the same values, written
  // without a virtual call per component, point and cell (the editor prepares
  // every re-meshed chunk in the frame that shows it).
  auto* floatPts = vtkFloatArray::SafeDownCast(inPts ? inPts->GetData() : nullptr);
  auto* intIjk = vtkIntArray::SafeDownCast(ijk);
  const bool typed = triangleOnly && floatPts && intIjk && outCd->GetNumberOfArrays() == 0;
  const int* ijkData = intIjk ? intIjk->GetPointer(0) : nullptr;
  if (this->SpatialOrder)
  {
    std::vector<std::pair<unsigned long long, vtkIdType>> keyed(static_cast<std::size_t>(nPolys));
    for (vtkIdType p = 0; p < nPolys; ++p)
    {
      const vtkIdType c = firstPoly + p;
      keyed[static_cast<std::size_t>(p)] = { typed
          ? MortonCode(ijkData[3 * c], ijkData[3 * c + 1], ijkData[3 * c + 2])
          : MortonCode(static_cast<int>(ijk->GetComponent(c, 0)), static_cast<int>(ijk->GetComponent(c, 1)),
              static_cast<int>(ijk->GetComponent(c, 2))),
        p };
    }
    std::sort(keyed.begin(), keyed.end()); // ties by input index: stable
    for (vtkIdType p = 0; p < nPolys; ++p)
    {
      order[static_cast<std::size_t>(p)] = keyed[static_cast<std::size_t>(p)].second;
    }
  }
  else
  {
    for (vtkIdType p = 0; p < nPolys; ++p)
    {
      order[static_cast<std::size_t>(p)] = p;
    }
  }

  vtkIdType next = 0, tri = 0;
  const vtkIdType reportEvery = triangles / 50 + 1;
  vtkNew<vtkIdList> ids;
  // the output arrays written directly (per vertex: position, ids, local
  // coordinates, 3 packed corner tuples)
  float* outXyz = vtkFloatArray::SafeDownCast(pts->GetData())->GetPointer(0);
  vtkIdType* from = fromIds->GetPointer(0);
  vtkIdType* to = toIds->GetPointer(0);
  float* outLocal = local->GetPointer(0);
  float* outCorners[3] = { cornerArrays[0]->GetPointer(0), cornerArrays[1]->GetPointer(0),
    cornerArrays[2]->GetPointer(0) };
  const bool copyCells = outCd->GetNumberOfArrays() > 0;
  if (typed)
  {
    // every polygon a triangle: output triangle i is polygon order[i]
    const float* inXyz = floatPts->GetPointer(0);
    auto fill = [&](auto* offsets, auto* connectivity) {
      const auto* off = offsets->GetPointer(0);
      const auto* conn = connectivity->GetPointer(0);
      for (vtkIdType p : order)
      {
        const vtkIdType cellId = firstPoly + p;
        double cellOrigin[3];
        for (int a = 0; a < 3; ++a)
        {
          cellOrigin[a] = this->Origin[a] + ijkData[3 * cellId + a] * this->Spacing[a];
        }
        float packed[12];
        PackCorners(corners->GetPointer(32 * cellId), packed);
        const auto* fan = conn + off[p];
        for (int v = 0; v < 3; ++v, ++next)
        {
          const vtkIdType id = static_cast<vtkIdType>(fan[v]);
          for (int a = 0; a < 3; ++a)
          {
            const double x = inXyz[3 * id + a]; // as vtkPoints::GetPoint gives it
            outXyz[3 * next + a] = static_cast<float>(x);
            outLocal[3 * next + a] = static_cast<float>((x - cellOrigin[a]) / this->Spacing[a]);
          }
          from[next] = id;
          to[next] = next;
          for (int c = 0; c < 3; ++c)
          {
            std::copy(packed + 4 * c, packed + 4 * c + 4, outCorners[c] + 4 * next);
          }
        }
      }
    };
    if (polys->IsStorage64Bit())
    {
      fill(polys->GetOffsetsArray64(), polys->GetConnectivityArray64());
    }
    else
    {
      fill(polys->GetOffsetsArray32(), polys->GetConnectivityArray32());
    }
    // triangle t is output points 3t..3t+2, as InsertNextCell below makes
    // them, in the storage AllocateExact chose
    auto iota = [&](auto* offsets, auto* connectivity) {
      offsets->SetNumberOfValues(triangles + 1);
      connectivity->SetNumberOfValues(3 * triangles);
      for (vtkIdType t = 0; t <= triangles; ++t)
      {
        offsets->SetValue(t, 3 * t);
      }
      for (vtkIdType i = 0; i < 3 * triangles; ++i)
      {
        connectivity->SetValue(i, i);
      }
    };
    if (outPolys->IsStorage64Bit())
    {
      iota(outPolys->GetOffsetsArray64(), outPolys->GetConnectivityArray64());
    }
    else
    {
      iota(outPolys->GetOffsetsArray32(), outPolys->GetConnectivityArray32());
    }
    tri = triangles;
  }
  else for (vtkIdType p : order)
  {
    const vtkIdType cellId = firstPoly + p;
    polys->GetCellAtId(p, ids);
    const vtkIdType n = ids->GetNumberOfIds();
    double cellOrigin[3];
    for (int a = 0; a < 3; ++a)
    {
      cellOrigin[a] = this->Origin[a] + ijk->GetComponent(cellId, a) * this->Spacing[a];
    }
    float packed[12];
    PackCorners(corners->GetPointer(32 * cellId), packed);
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      const vtkIdType fan[3] = { ids->GetId(0), ids->GetId(k), ids->GetId(k + 1) };
      vtkIdType outIds[3];
      for (int v = 0; v < 3; ++v, ++next)
      {
        double pt[3];
        inPts->GetPoint(fan[v], pt);
        for (int a = 0; a < 3; ++a)
        {
          outXyz[3 * next + a] = static_cast<float>(pt[a]);
          outLocal[3 * next + a] = static_cast<float>((pt[a] - cellOrigin[a]) / this->Spacing[a]);
        }
        from[next] = fan[v];
        to[next] = next;
        for (int c = 0; c < 3; ++c)
        {
          std::copy(packed + 4 * c, packed + 4 * c + 4, outCorners[c] + 4 * next);
        }
        outIds[v] = next;
      }
      outPolys->InsertNextCell(3, outIds);
      if (copyCells)
      {
        outCd->CopyData(input->GetCellData(), cellId, tri);
      }
      if (++tri % reportEvery == 0)
      {
        this->UpdateProgress(static_cast<double>(tri) / triangles);
        if (this->GetAbortExecute())
        {
          return 1;
        }
      }
    }
  }
  outPd->CopyData(input->GetPointData(), fromIds, toIds);
  output->SetPoints(pts);
  output->SetPolys(outPolys);
  outPd->AddArray(local);
  for (int c = 0; c < 3; ++c)
  {
    outPd->AddArray(cornerArrays[c]);
  }
  if (typed && triangles > 0)
  {
    // The coordinates' ranges, cached in the array as vtkDataArray::GetRange
    // caches them (PER_COMPONENT, COMPONENT_RANGE; set after the array's last
    // modification, so they count as current): one tight pass here instead of
    // VTK's generic one when the vertex buffer upload (its automatic shift and
    // scale) or vtkChunkActorManager asks. The typed path's points are finite
    // marching cubes vertices.
    float lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = hi[a] = outXyz[a];
    }
    for (vtkIdType i = 0; i < 3 * triangles; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], outXyz[3 * i + a]);
        hi[a] = std::max(hi[a], outXyz[3 * i + a]);
      }
    }
    vtkNew<vtkInformationVector> perComponent;
    perComponent->SetNumberOfInformationObjects(3);
    for (int a = 0; a < 3; ++a)
    {
      const double range[2] = { lo[a], hi[a] };
      perComponent->GetInformationObject(a)->Set(vtkDataArray::COMPONENT_RANGE(), range, 2);
    }
    pts->GetData()->GetInformation()->Set(vtkAbstractArray::PER_COMPONENT(), perComponent);
  }
  return 1;
}

void vtkCornerColorAttributes::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " " << this->Origin[2] << "\n";
  os << indent << "SpatialOrder: " << this->SpatialOrder << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " " << this->Spacing[2] << "\n";
}
