#include "vtkPDictionaryVolumeReader.h"

#include "LVDIFVolumeIndex.h"
#include "vtkDictionaryVolumeReader.h"
#include "vtkSparseVolumeToImage.h"

#include "lvdif/Error.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <fstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkPDictionaryVolumeReader);

vtkPDictionaryVolumeReader::vtkPDictionaryVolumeReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPDictionaryVolumeReader::~vtkPDictionaryVolumeReader() = default;

bool vtkPDictionaryVolumeReader::CanReadFile(const char* fileName)
{
  std::ifstream f(fileName ? fileName : "");
  std::string word;
  return static_cast<bool>(f >> word) && word == "LVDIF-PVOLUME";
}

int vtkPDictionaryVolumeReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return 0;
  }
  lvdifvtk::VolumeIndex index;
  try
  {
    index = lvdifvtk::readVolumeIndex(this->FileName);
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), index.wholeExtent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), index.origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), index.spacing, 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

int vtkPDictionaryVolumeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  this->PiecesRead = 0;
  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  lvdifvtk::VolumeIndex index;
  try
  {
    index = lvdifvtk::readVolumeIndex(this->FileName);
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  output->SetExtent(ext);
  output->SetOrigin(index.origin);
  output->SetSpacing(index.spacing);
  const vtkIdType n = output->GetNumberOfPoints();
  std::vector<char> filled(static_cast<size_t>(n), 0);
  vtkIdType missing = n;
  const std::string dir = lvdifvtk::directoryOf(this->FileName);
  for (size_t p = 0; p < index.pieces.size() && missing > 0; ++p)
  {
    const auto& piece = index.pieces[p];
    int sub[6], local[6];
    bool overlaps = true;
    for (int a = 0; a < 3; ++a)
    {
      sub[2 * a] = std::max(ext[2 * a], piece.extent[2 * a]);
      sub[2 * a + 1] = std::min(ext[2 * a + 1], piece.extent[2 * a + 1]);
      overlaps = overlaps && sub[2 * a] <= sub[2 * a + 1];
      local[2 * a] = sub[2 * a] - piece.extent[2 * a]; // the piece file's own indices start at 0
      local[2 * a + 1] = sub[2 * a + 1] - piece.extent[2 * a];
    }
    if (!overlaps)
    {
      continue;
    }
    vtkNew<vtkDictionaryVolumeReader> r;
    r->SetFileName((dir + piece.file).c_str());
    r->SetWithColor(this->WithColor);
    r->UpdateInformation();
    int pieceWhole[6];
    r->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), pieceWhole);
    for (int a = 0; a < 3; ++a)
    {
      if (pieceWhole[2 * a + 1] - pieceWhole[2 * a] != piece.extent[2 * a + 1] - piece.extent[2 * a])
      {
        vtkErrorMacro("piece file '" << piece.file << "' does not have the size the index gives it");
        output->Initialize();
        return 0;
      }
    }
    vtkNew<vtkSparseVolumeToImage> decode; // the piece's part of the request only
    decode->SetInputConnection(r->GetOutputPort());
    decode->SetWithColor(this->WithColor);
    decode->UpdateInformation();
    if (!decode->UpdateExtent(local))
    {
      vtkErrorMacro("cannot read piece file '" << piece.file << "'");
      output->Initialize();
      return 0;
    }
    ++this->PiecesRead;
    vtkImageData* img = decode->GetOutput();
    vtkPointData* src = img->GetPointData();
    vtkPointData* dst = output->GetPointData();
    for (int q = 0; q < src->GetNumberOfArrays(); ++q)
    {
      vtkDataArray* s = src->GetArray(q);
      if (!s || !s->GetName() || dst->GetArray(s->GetName()))
        continue;
      vtkSmartPointer<vtkDataArray> d = vtkSmartPointer<vtkDataArray>::Take(s->NewInstance());
      d->SetName(s->GetName());
      d->SetNumberOfComponents(s->GetNumberOfComponents());
      d->SetNumberOfTuples(n);
      d->Fill(0);
      if (src->GetScalars() == s)
        dst->SetScalars(d);
      else
        dst->AddArray(d);
    }
    // (destination, source) arrays, matched by name once per piece, not per voxel
    std::vector<std::pair<vtkDataArray*, vtkDataArray*>> pairs;
    for (int q = 0; q < dst->GetNumberOfArrays(); ++q)
    {
      if (vtkDataArray* sa = src->GetArray(dst->GetArray(q)->GetName()))
        pairs.emplace_back(dst->GetArray(q), sa);
    }
    for (int k = sub[4]; k <= sub[5]; ++k)
      for (int j = sub[2]; j <= sub[3]; ++j)
        for (int i = sub[0]; i <= sub[1]; ++i)
        {
          int gi[3] = { i, j, k };
          int li[3] = { i - piece.extent[0], j - piece.extent[2], k - piece.extent[4] };
          const vtkIdType o = output->ComputePointId(gi);
          if (filled[static_cast<size_t>(o)])
            continue;
          const vtkIdType s = img->ComputePointId(li);
          for (const auto& pr : pairs)
            pr.first->SetTuple(o, s, pr.second);
          filled[static_cast<size_t>(o)] = 1;
          --missing;
        }
    this->UpdateProgress(0.05 + 0.95 * static_cast<double>(n - missing) / static_cast<double>(n > 0 ? n : 1));
    if (this->AbortExecute)
    {
      output->Initialize();
      return 0;
    }
  }
  if (missing > 0)
  {
    vtkErrorMacro("the pieces of '" << this->FileName << "' do not cover the requested extent (" << missing
                                    << " points missing)");
    output->Initialize();
    return 0;
  }
  return 1;
}

void vtkPDictionaryVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
}
