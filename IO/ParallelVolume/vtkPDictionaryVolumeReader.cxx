#include "vtkPDictionaryVolumeReader.h"

#include "LVDIFVolumeIndex.h"
#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "lvdif/VolumeFile.h"

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
#include <cmath>
#include <iomanip>
#include <locale>
#include <sstream>
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
  // the project's file check: a FIFO blocked std::ifstream (ParaView's file
  // dialog asks every reader); the first line that is no comment, as the reader reads it
  try
  {
    lvdif::FileSource f(fileName ? fileName : "");
    std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(f.size(), 4096)), '\0');
    if (!head.empty())
      f.read(0, &head[0], head.size());
    std::istringstream in(head);
    std::string line;
    while (std::getline(in, line))
    {
      std::istringstream ls(line);
      std::string word;
      if (!(ls >> word) || word[0] == '#')
        continue;
      return word == "LVDIF-PVOLUME";
    }
    return false;
  }
  catch (const lvdif::Error&)
  {
    return false;
  }
}

int vtkPDictionaryVolumeReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkPDictionaryVolumeReader::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  LVDIFVolumeBridge::EnsureSparseOutput(out);
  return 1;
}

namespace
{
/// f(), its errors naming the piece file: a piece that was no .lvdv (or was
/// damaged) said "cannot read 'x.lvdvp': header: bad magic", naming the index only.
template <typename F>
auto inPiece(const std::string& file, F&& f) -> decltype(f())
{
  try
  {
    return f();
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() == lvdif::ErrorCode::Cancelled || std::string(e.what()).find("'" + file + "'") != std::string::npos)
      throw;
    throw lvdif::Error(e.code(), "piece file '" + file + "': " + e.what());
  }
}

/// The volume the index describes: its geometry, with the first piece's chunk
/// edge, band and SDF dictionary (the writer gives every piece the same).
lvdif::VolumeOptions indexOptions(const lvdifvtk::VolumeIndex& index, const std::string& dir)
{
  if (index.pieces.empty())
  {
    throw lvdif::Error(lvdif::ErrorCode::CorruptData, "the index lists no piece");
  }
  lvdif::VolumeOptions o = inPiece(index.pieces.front().file, [&] {
    return lvdif::readVolumeInfo(dir + index.pieces.front().file).options;
  });
  for (int a = 0; a < 3; ++a)
  {
    o.dims[a] = static_cast<std::int64_t>(index.wholeExtent[2 * a + 1]) - index.wholeExtent[2 * a] + 1;
    // the sparse volume's indices start at 0: its origin is the whole extent's first point
    o.origin[a] = index.origin[a] + index.spacing[a] * index.wholeExtent[2 * a];
    o.spacing[a] = index.spacing[a];
  }
  o.memoryLimit = 0;
  return o;
}

/// A piece's voxels in the volume's indices (from 0).
lvdif::VoxelBox pieceBox(const lvdifvtk::VolumeIndex& index, const lvdifvtk::VolumeIndexPiece& piece)
{
  lvdif::VoxelBox box;
  for (int a = 0; a < 3; ++a)
  {
    box.lo[a] = static_cast<std::int64_t>(piece.extent[2 * a]) - index.wholeExtent[2 * a];
    box.hi[a] = static_cast<std::int64_t>(piece.extent[2 * a + 1]) - index.wholeExtent[2 * a];
  }
  return box;
}

/// The piece file's header against the index: its size, and its grid where
/// the index puts it (spacing, and origin = the index's origin + spacing x the
/// piece's first point, as the writer makes it; to a millionth of a voxel). A
/// piece of another size was refused only after the whole volume was made, and
/// one of another grid (a file of another set copied in) was read without a word.
void checkPiece(const lvdifvtk::VolumeIndex& index, const lvdifvtk::VolumeIndexPiece& piece, const std::string& dir)
{
  const lvdif::VolumeOptions o = inPiece(piece.file, [&] { return lvdif::readVolumeInfo(dir + piece.file).options; });
  const lvdif::VoxelBox box = pieceBox(index, piece);
  auto text = [](double x, double y, double z) {
    std::ostringstream s;
    s.imbue(std::locale::classic());
    s << std::setprecision(10) << x << " " << y << " " << z;
    return s.str();
  };
  for (int a = 0; a < 3; ++a)
    if (o.dims[a] != box.hi[a] - box.lo[a] + 1)
      throw lvdif::Error(lvdif::ErrorCode::CorruptData,
        "piece file '" + piece.file + "' has " + std::to_string(o.dims[0]) + " x " + std::to_string(o.dims[1]) + " x " +
          std::to_string(o.dims[2]) + " voxels, the index gives it " + std::to_string(box.hi[0] - box.lo[0] + 1) + " x " +
          std::to_string(box.hi[1] - box.lo[1] + 1) + " x " + std::to_string(box.hi[2] - box.lo[2] + 1));
  double origin[3];
  bool same = true;
  for (int a = 0; a < 3; ++a)
  {
    const double s = index.spacing[a];
    origin[a] = index.origin[a] + s * piece.extent[2 * a];
    same = same && std::fabs(o.spacing[a] - s) <= 1e-9 * s &&
      std::fabs(o.origin[a] - origin[a]) <= 1e-6 * s + 1e-12 * std::fabs(origin[a]);
  }
  if (!same)
    throw lvdif::Error(lvdif::ErrorCode::CorruptData,
      "piece file '" + piece.file + "' has origin " + text(o.origin[0], o.origin[1], o.origin[2]) + " and spacing " +
        text(o.spacing[0], o.spacing[1], o.spacing[2]) + ", the index puts it at " + text(origin[0], origin[1], origin[2]) +
        " with spacing " + text(index.spacing[0], index.spacing[1], index.spacing[2]) + " (a piece of another volume?)");
}

}

int vtkPDictionaryVolumeReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  try
  {
    const lvdifvtk::VolumeIndex index = lvdifvtk::readVolumeIndex(this->FileName);
    LVDIFVolumeBridge::SetSparseInformation(
      outputVector->GetInformationObject(0), indexOptions(index, lvdifvtk::directoryOf(this->FileName)));
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< LVDIFVolumeBridge::FileError("read", this->FileName, e.what()));
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  return 1;
}

int vtkPDictionaryVolumeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outInfo);
  this->PiecesRead = 0;
  const std::string dir = lvdifvtk::directoryOf(this->FileName);
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  output->SetPartitionColors(this->WithColor);
  const bool ok = LVDIFVolumeBridge::CallCore(
    this,
    [&] {
      const lvdifvtk::VolumeIndex index = lvdifvtk::readVolumeIndex(this->FileName);
      const lvdif::VolumeOptions options = indexOptions(index, dir);
      // the voxels this request needs, in the volume's indices (from 0)
      lvdif::VoxelBox want;
      int owned[6] = { 0, -1, 0, -1, 0, -1 };
      const int kind = LVDIFVolumeBridge::RequestedVoxels(outInfo, options, owned, want);
      if (kind < 0)
      {
        output->Initialize(); // a piece without chunks: empty
        return;
      }
      if (kind == 1)
      {
        // the next chunks whole, as the .lvdv reader loads them (their shared
        // layer alone gave partitions the serial read has not: ParaView's
        // Integrate Variables over 2 ranks gave 52,832 for the serial 43,264)
        LVDIFVolumeBridge::GrowToWholeChunks(want, options);
      }
      // (readVolumeIndex checked that the pieces tile the whole extent, so they hold `want`)
      auto volume = std::make_shared<lvdif::DictionaryVolume>(options);
      lvdif::DictionaryVolume& out = *volume;
      // progress over the pieces' parts, each half loading (the piece file's
      // own progress) and half copying: the loads reported 0..1 each, so the
      // progress went to 1 and back at every piece (and an observer cancelling
      // at "done" cancelled the read)
      std::int64_t total = 0, done = 0;
      for (const lvdifvtk::VolumeIndexPiece& piece : index.pieces)
      {
        total += pieceBox(index, piece).intersect(want).voxelCount();
      }
      total = std::max<std::int64_t>(total, 1);
      // the pieces this request reads, each header against the index, before the volume is made
      for (const lvdifvtk::VolumeIndexPiece& piece : index.pieces)
      {
        if (!pieceBox(index, piece).intersect(want).empty())
          checkPiece(index, piece, dir);
      }
      // in reverse, so that on a shared plane the first piece listed writes last
      for (auto it = index.pieces.rbegin(); it != index.pieces.rend(); ++it)
      {
        const lvdif::VoxelBox box = pieceBox(index, *it); // the piece in the volume's indices
        const lvdif::VoxelBox part = box.intersect(want);
        if (part.empty())
        {
          continue;
        }
        const std::int64_t partCount = part.voxelCount();
        interrupter.setStage(static_cast<double>(done) / static_cast<double>(total),
          0.5 * static_cast<double>(partCount) / static_cast<double>(total));
        std::int64_t copied = 0;
        lvdif::VolumeFileReadOptions read;
        read.wholeVolume = false;
        for (int a = 0; a < 3; ++a)
        {
          read.region.lo[a] = part.lo[a] - box.lo[a]; // the piece file's own indices start at 0
          read.region.hi[a] = part.hi[a] - box.lo[a];
        }
        const std::unique_ptr<lvdif::DictionaryVolume> pv =
          inPiece(it->file, [&] { return lvdif::loadVolume(dir + it->file, read, interrupter); });
        for (int a = 0; a < 3; ++a)
        {
          if (pv->dims()[a] != box.hi[a] - box.lo[a] + 1) // (checkPiece read its header; the file changed since)
          {
            throw lvdif::Error(lvdif::ErrorCode::CorruptData,
              "piece file '" + it->file + "' does not have the size the index gives it");
          }
        }
        ++this->PiecesRead;
        // keys copied as they are; colours by value; distances re-encoded only
        // when the piece's dictionary differs from the output's
        const bool sameSdf = pv->options().dictionary == out.options().dictionary;
        std::vector<lvdif::ColorKey> colorKey(pv->colors().size());
        for (std::size_t k = 0; k < colorKey.size(); ++k)
        {
          colorKey[k] = out.colors().add(pv->colors()[static_cast<lvdif::ColorKey>(k)]);
        }
        for (std::int64_t z = part.lo[2]; z <= part.hi[2]; ++z)
        {
          for (std::int64_t y = part.lo[1]; y <= part.hi[1]; ++y)
          {
            for (std::int64_t x = part.lo[0]; x <= part.hi[0]; ++x)
            {
              lvdif::Voxel v = pv->get(x - box.lo[0], y - box.lo[1], z - box.lo[2]);
              v.color = colorKey[v.color];
              if (!sameSdf)
              {
                v.sdf = out.encode(pv->decode(v.sdf));
              }
              out.set(x, y, z, v); // a no-op where a uniform chunk already holds v
            }
          }
          copied += (part.hi[1] - part.lo[1] + 1) * (part.hi[0] - part.lo[0] + 1);
          this->UpdateProgress(std::min(1.0, (static_cast<double>(done) + 0.5 * static_cast<double>(partCount + copied)) /
                                                 static_cast<double>(total)));
          interrupter.checkInterrupt();
        }
        done += partCount;
      }
      out.collapseUniformChunks();
      out.takeDirtyChunks(); // a volume as read: nothing to re-mesh
      output->SetVolume(std::move(volume));
      if (kind == 1)
      {
        output->SetOwnedChunks(owned);
      }
    },
    "cannot read '" + this->FileName + "': ");
  if (!ok)
  {
    output->Initialize();
    return LVDIFVolumeBridge::FailReported(outInfo); // (a cancel: no error, no dump)
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPDictionaryVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
}
