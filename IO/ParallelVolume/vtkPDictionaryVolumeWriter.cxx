#include "vtkPDictionaryVolumeWriter.h"

#include "LVDIFVolumeIndex.h"
#include "vtkDictionaryVolumeWriter.h"
#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "lvdif/VolumeFile.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCommunicator.h"
#include "vtkDataObject.h"
#include "vtkErrorCode.h"
#include "vtkExtentTranslator.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <unistd.h>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkPDictionaryVolumeWriter);
vtkCxxSetObjectMacro(vtkPDictionaryVolumeWriter, Controller, vtkMultiProcessController);

vtkPDictionaryVolumeWriter::vtkPDictionaryVolumeWriter()
  : CompressionLevel(lvdif::VolumeFileWriteOptions().compressionLevel)
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPDictionaryVolumeWriter::~vtkPDictionaryVolumeWriter()
{
  this->SetController(nullptr);
}

vtkImageData* vtkPDictionaryVolumeWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkPDictionaryVolumeWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

void vtkPDictionaryVolumeWriter::PieceExtent(const int whole[6], int piece, int numberOfPieces, int extent[6])
{
  vtkNew<vtkExtentTranslator> t;
  int w[6] = { whole[0], whole[1], whole[2], whole[3], whole[4], whole[5] };
  if (!t->PieceToExtentThreadSafe(piece, numberOfPieces, 0, w, extent, vtkExtentTranslator::BLOCK_MODE, 0))
  {
    extent[0] = extent[2] = extent[4] = 0; // no points for this piece
    extent[1] = extent[3] = extent[5] = -1;
  }
}

namespace
{
/// Piece p of n of a sparse volume: the block of storage chunks a sparse
/// producer computes for that piece (the readers' ownership rule,
/// LVDIFVolumeBridge::PieceChunks) plus the layer of points it shares with the
/// next chunks. A split of the points instead (PieceExtent) took voxels the
/// producer had not computed for this piece whenever the two splits differ
/// (90 points in chunks of 8: points 0..44 | 44..89, chunks 0..47 | 48..89).
void SparsePieceExtent(const lvdif::VolumeOptions& o, int piece, int numberOfPieces, int extent[6])
{
  int owned[6];
  lvdif::VoxelBox region;
  if (!LVDIFVolumeBridge::PieceChunks(piece, numberOfPieces, o, owned, region))
  {
    extent[0] = extent[2] = extent[4] = 0; // no chunks for this piece
    extent[1] = extent[3] = extent[5] = -1;
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a] = static_cast<int>(region.lo[a]);
    extent[2 * a + 1] = static_cast<int>(region.hi[a]);
  }
}

/// Whether piece p of n of the sparse volume announced in `inInfo` has no chunks
/// (more pieces than chunk blocks): its producer then gives it no volume, and
/// the piece has nothing to write (it failed with "no input image or sparse
/// volume", and no index was written: any volume of one chunk under 2 ranks).
bool EmptySparsePiece(vtkInformation* inInfo, int piece, int numberOfPieces)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!inInfo || !inInfo->Has(SDDP::WHOLE_EXTENT()) || !inInfo->Has(LVDIFVolumeBridge::CHUNK_EDGE()))
    return false;
  int whole[6], ext[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  lvdif::VolumeOptions o;
  for (int a = 0; a < 3; ++a) o.dims[a] = whole[2 * a + 1] - whole[2 * a] + 1;
  o.chunkEdge = inInfo->Get(LVDIFVolumeBridge::CHUNK_EDGE());
  SparsePieceExtent(o, piece, numberOfPieces, ext);
  return !lvdifvtk::extentIsValid(ext);
}
} // namespace

int vtkPDictionaryVolumeWriter::Write()
{
  this->Agreed = false;
  int written = 0;
  if (this->GetNumberOfInputConnections(0) < 1)
    written = this->Superclass::Write(); // VTK's "No input provided!"
  else
  {
    this->SetErrorCode(vtkErrorCode::NoError);
    // the pieces, the file name, the folder and the settings before the input
    // is brought up to date, as vtkLVDIFVolumeWriter::Write: a write into a
    // missing folder ran the whole pipeline above it (Mesh To SDF: minutes)
    // and only then refused. The ranks agree first: a rank that stopped here
    // while the others ran a collective filter upstream would hang them.
    int generation = 0;
    int ok = this->CheckTarget(this->InputIsImage(), generation) ? 1 : 0;
    if (this->IsCollective())
    {
      int all = ok;
      this->Controller->AllReduce(&ok, &all, 1, vtkCommunicator::MIN_OP);
      if (!all && ok)
      {
        vtkErrorMacro("another piece refused its file or settings; nothing is written");
        this->SetErrorCode(vtkErrorCode::UnknownError);
      }
      ok = all;
    }
    if (!ok)
      return 0; // every rank alike: nothing ran, nothing to agree on
    if (!vtkLVDIFVolumeWriter::UpdateWholeInput(this) && this->GetErrorCode() == vtkErrorCode::NoError)
      this->SetErrorCode(vtkErrorCode::UnknownError);
    written = this->GetErrorCode() == vtkErrorCode::NoError ? 1 : 0;
  }
  if (!this->Agreed && this->IsCollective())
  {
    // this rank's input failed upstream (WriteData never ran) or WriteData
    // refused before the agreement: join it as a failed piece, and the
    // barrier after it, or the other ranks wait for this one forever
    this->AgreeOnPieces(0);
    this->AgreeOnIndex(0);
    written = 0;
  }
  return written;
}

bool vtkPDictionaryVolumeWriter::PieceExists() const
{
  return this->NumberOfPieces >= 1 && this->Piece >= 0 && this->Piece < this->NumberOfPieces;
}

bool vtkPDictionaryVolumeWriter::IsSerial() const
{
  return !this->Controller || this->Controller->GetNumberOfProcesses() <= 1;
}

bool vtkPDictionaryVolumeWriter::IsCollective() const
{
  return this->Controller && this->Controller->GetNumberOfProcesses() == this->NumberOfPieces &&
    this->NumberOfPieces > 1;
}

int vtkPDictionaryVolumeWriter::AgreeOnPieces(int ok)
{
  this->Agreed = true;
  return this->AgreeOnIndex(ok);
}

int vtkPDictionaryVolumeWriter::AgreeOnIndex(int ok)
{
  int all = ok;
  if (this->IsCollective())
    this->Controller->AllReduce(&ok, &all, 1, vtkCommunicator::MIN_OP);
  return all;
}

// Ask the input for exactly this piece's extent (the one piece 0 lists in the index).
vtkTypeBool vtkPDictionaryVolumeWriter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    // (a piece that does not exist asks for nothing: WriteData refuses it)
    if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()) && this->PieceExists())
    {
      int whole[6], ext[6];
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
      // a serial run writes every piece: it asks for the whole input
      const bool serial = this->IsSerial();
      if (serial)
        std::copy(whole, whole + 6, ext);
      else
        PieceExtent(whole, this->Piece, this->NumberOfPieces, ext);
      if (!lvdifvtk::extentIsValid(ext))
      {
        // an empty piece still needs a (small) valid request; nothing is written for it
        for (int a = 0; a < 3; ++a)
          ext[2 * a + 1] = ext[2 * a] = whole[2 * a];
      }
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), serial ? 0 : this->Piece);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), serial ? 1 : this->NumberOfPieces);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext, 6);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
    }
    return 1;
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

std::string vtkPDictionaryVolumeWriter::PieceFilePath(const std::string& indexPath, int piece, int generation)
{
  return lvdifvtk::directoryOf(indexPath) + lvdifvtk::pieceFileName(indexPath, piece, generation);
}

int vtkPDictionaryVolumeWriter::NextGeneration(const std::string& indexPath)
{
  // the generation the current index does not list (none, or one that cannot be read: 0)
  try
  {
    for (const lvdifvtk::VolumeIndexPiece& p : lvdifvtk::readVolumeIndex(indexPath).pieces)
    {
      int n = 0;
      if (lvdifvtk::isPieceFileName(indexPath, p.file, &n) && p.file == lvdifvtk::pieceFileName(indexPath, n, 0))
        return 1;
    }
  }
  catch (const lvdif::Error&)
  {
  }
  return 0;
}

namespace
{
/// The names in the index's folder that are piece files of its set (either generation).
std::vector<std::string> setFiles(const std::string& indexPath, bool temporaries)
{
  std::vector<std::string> names;
  const std::string dir = lvdifvtk::directoryOf(indexPath);
  DIR* d = ::opendir(dir.empty() ? "." : dir.c_str());
  if (!d)
    return names;
  while (const dirent* e = ::readdir(d))
  {
    std::string name = e->d_name;
    const auto tmp = name.find(".tmp-");
    if (temporaries && tmp != std::string::npos)
      name.resize(tmp); // "<piece file>.tmp-<pid>-XXXXXX...": the piece file's name
    else if (temporaries || tmp != std::string::npos)
      continue;
    if (lvdifvtk::isPieceFileName(indexPath, name) && std::find(names.begin(), names.end(), name) == names.end())
      names.push_back(name);
  }
  ::closedir(d);
  return names;
}
} // namespace

void vtkPDictionaryVolumeWriter::RequireNoUnlistedPieces(const std::string& indexPath)
{
  // a set that has an index owns the files named as its pieces (leftovers of killed writes are
  // removed); before its first index they were overwritten or removed without a word, a user's
  // scan_1.lvdv and scan_2.lvdv deleted by writing scan.lvdvp
  if (::access(indexPath.c_str(), F_OK) == 0)
    return;
  std::vector<std::string> names = setFiles(indexPath, false);
  if (names.empty())
    return;
  std::sort(names.begin(), names.end());
  std::string list = "'" + names[0] + "'";
  for (std::size_t i = 1; i < names.size() && i < 3; ++i)
    list += ", '" + names[i] + "'";
  if (names.size() > 3)
    list += " and " + std::to_string(names.size() - 3) + " more";
  throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
    "cannot write '" + indexPath + "': " + list + (names.size() == 1 ? " lies" : " lie") +
      " beside it, named as " + (names.size() == 1 ? "a piece" : "pieces") +
      " of its set, but no index lists them (another volume's files?), and writing the set would overwrite or "
      "remove them: move them, or choose another name");
}

bool vtkPDictionaryVolumeWriter::WritePiece(
  vtkSparseDictionaryVolume* sparse, int pieceNumber, const int ext[6], const std::string& path)
{
  // the piece's voxels as they are stored (keys copied, nothing re-encoded)
  lvdif::VolumeFileWriteOptions options;
  options.compressionLevel = this->CompressionLevel;
  if (!this->VolumeName.empty()) options.metadata["name"] = this->VolumeName;
  LVDIFInterrupter interrupter(this);
  return LVDIFVolumeBridge::CallCore(
    this,
    [&] {
      lvdif::saveVolume(*LVDIFVolumeBridge::CropVolume(*sparse->GetVolume(), ext), path, options, interrupter);
    },
    "piece " + std::to_string(pieceNumber) + ": ");
}

bool vtkPDictionaryVolumeWriter::WritePiece(
  vtkImageData* image, int pieceNumber, const int ext[6], const std::string& path)
{
  // crop: a producer may give more than the requested extent
  vtkNew<vtkImageData> piece;
  piece->ShallowCopy(image);
  piece->Crop(ext);
  int got[6];
  piece->GetExtent(got);
  for (int q = 0; q < 6; ++q)
  {
    if (got[q] != ext[q])
    {
      vtkErrorMacro("piece " << pieceNumber << ": the input does not cover the piece's extent");
      return false;
    }
  }
  vtkNew<vtkDictionaryVolumeWriter> w;
  w->SetInputData(piece);
  w->SetFileName(path.c_str());
  w->SetBandWidth(this->BandWidth);
  w->SetChunkEdge(this->ChunkEdge);
  w->SetCompressionLevel(this->CompressionLevel);
  w->SetVolumeName(this->VolumeName.c_str());
  // the piece's progress is this writer's (a serial run: piece p of n is the
  // p-th n-th of it), and this writer's cancel the piece's: the pieces of an
  // image reported no progress and could not be cancelled
  struct Forward
  {
    vtkPDictionaryVolumeWriter* outer;
    double shift, scale;
  } forward{ this, this->IsSerial() ? double(pieceNumber) / this->NumberOfPieces : 0.0,
    this->IsSerial() ? 1.0 / this->NumberOfPieces : 1.0 };
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&forward);
  onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
    auto* f = static_cast<Forward*>(client);
    f->outer->UpdateProgress(f->shift + f->scale * *static_cast<double*>(call));
    if (f->outer->GetAbortExecute())
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  w->AddObserver(vtkCommand::ProgressEvent, onProgress);
  if (this->GetAbortExecute())
    return false; // cancelled before this piece
  // Write() answers 0 for a cancel too (nothing written; no error)
  return w->Write() == 1;
}

bool vtkPDictionaryVolumeWriter::InputIsImage()
{
  // the input's type, known once its data object exists (nothing computed)
  auto* exec = vtkStreamingDemandDrivenPipeline::SafeDownCast(this->GetExecutive());
  if (exec)
    exec->UpdateDataObject();
  return !vtkSparseDictionaryVolume::SafeDownCast(this->Superclass::GetInput());
}

bool vtkPDictionaryVolumeWriter::CheckTarget(bool imageInput, int& generation)
{
  if (!this->PieceExists())
  {
    vtkErrorMacro("piece " << this->Piece << " of " << this->NumberOfPieces << " does not exist: Piece must be in [0, "
                           << "NumberOfPieces - 1] and NumberOfPieces >= 1");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return false;
  }
  const bool serial = this->IsSerial();
  if (!serial && !this->IsCollective() && this->NumberOfPieces > 1)
  {
    // every rank would write every piece
    vtkErrorMacro("NumberOfPieces " << this->NumberOfPieces << " needs a Controller of " << this->NumberOfPieces
                                    << " processes (one piece each) or none (one process writes every piece); "
                                    << "the Controller has " << this->Controller->GetNumberOfProcesses());
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return false;
  }
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return false;
  }
  // the folder and the settings, before any file: one error on this writer naming the file asked for
  // (each piece's writer would report them on itself, naming its piece file)
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        lvdif::requireWritable(this->FileName);
        if (serial) // (ranks of a controller would see each other's new pieces before the index)
          RequireNoUnlistedPieces(this->FileName);
        generation = NextGeneration(this->FileName);
        // a serial run writes every piece, a rank its own: each file is checked before the first is written
        for (int p = serial ? 0 : this->Piece; p < (serial ? this->NumberOfPieces : this->Piece + 1); ++p)
          lvdif::requireWritable(PieceFilePath(this->FileName, p, generation));
        lvdif::checkCompressionLevel(this->CompressionLevel, "CompressionLevel");
        if (imageInput) LVDIFVolumeBridge::CheckVolumeSettings(this->ChunkEdge, this->BandWidth);
      }))
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return false;
  }
  return true;
}

void vtkPDictionaryVolumeWriter::WriteData()
{
  vtkImageData* image = this->GetInput();
  auto* sparseInput = vtkSparseDictionaryVolume::SafeDownCast(this->Superclass::GetInput());
  auto* sparse = sparseInput && sparseInput->HasVolume() ? sparseInput : nullptr;
  vtkInformation* inInfo = this->GetInputInformation(0, 0);
  // (again here: ParaView may run WriteData through the executive, not Write)
  int generation = 0;
  if (!this->CheckTarget(!sparseInput, generation))
    return;
  const bool serial = this->IsSerial();
  const bool emptyPiece =
    !serial && sparseInput && !sparse && EmptySparsePiece(inInfo, this->Piece, this->NumberOfPieces);
  if (!emptyPiece &&
    ((!image && !sparse) || !inInfo || (!sparse && !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))))
  {
    // a sparse volume from a producer that failed or made nothing is no missing input:
    // said as the other volume writers say it (it read "no input image or sparse volume")
    vtkErrorMacro(<< (sparseInput && !sparse ? "the input sparse volume holds no dictionary volume"
                                             : "no input image or sparse volume"));
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  int whole[6] = { 0, -1, 0, -1, 0, -1 };
  if (sparse)
  {
    for (int a = 0; a < 3; ++a) // the volume's own (0-based) indices
    {
      whole[2 * a] = 0;
      whole[2 * a + 1] = static_cast<int>(sparse->GetVolume()->dims()[a] - 1);
    }
  }
  else if (!emptyPiece)
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    if (!lvdifvtk::extentIsValid(whole))
    {
      // an image without points (an empty vtkImageData, a source that made
      // nothing) wrote an index of no pieces, removed the old set's pieces and
      // Write() returned 1; its own reader then refused the index ("empty whole_extent")
      vtkErrorMacro("the input image has no points (whole extent " << whole[0] << " " << whole[1] << " " << whole[2]
                                                                   << " " << whole[3] << " " << whole[4] << " " << whole[5]
                                                                   << "): nothing is written, the old file is kept");
      this->SetErrorCode(vtkErrorCode::UnknownError);
      return;
    }
  }
  // The temporary files of writes of this set that were killed (their process
  // is gone) were left beside the pieces: removed first, each by the project's
  // rule (lvdif::removeStaleTemporaries). A rank removes its own piece's only.
  if (serial)
  {
    for (const std::string& name : setFiles(this->FileName, true))
      lvdif::removeStaleTemporaries(lvdifvtk::directoryOf(this->FileName) + name);
  }
  else
  {
    for (int g = 0; g < 2; ++g)
      lvdif::removeStaleTemporaries(PieceFilePath(this->FileName, this->Piece, g));
  }
  // this process's pieces: all of them in a serial run, else its own. Each is
  // written (crash-safely) under the generation the current index does not
  // list, so the old index and its pieces stay whole until the new index
  // replaces the old one, the one switch of the write. Until session 24 the
  // pieces were renamed over the old ones before the index was written: a
  // rename failing after others had succeeded left the old index listing new
  // pieces beside old ones.
  int ok = 1;
  std::vector<std::string> written; // this process's new pieces
  for (int p = serial ? 0 : this->Piece; ok && p < (serial ? this->NumberOfPieces : this->Piece + 1); ++p)
  {
    int ext[6] = { 0, -1, 0, -1, 0, -1 }; // an empty piece: nothing
    if (sparse)
      SparsePieceExtent(sparse->GetVolume()->options(), p, this->NumberOfPieces, ext);
    else if (!emptyPiece)
      PieceExtent(whole, p, this->NumberOfPieces, ext);
    if (!lvdifvtk::extentIsValid(ext))
      continue;
    const std::string path = PieceFilePath(this->FileName, p, generation);
    ok = sparse ? (this->WritePiece(sparse, p, ext, path) ? 1 : 0) : (this->WritePiece(image, p, ext, path) ? 1 : 0);
    if (ok)
      written.push_back(path);
  }

  const int all = this->AgreeOnPieces(ok);
  if (!all && ok)
  {
    vtkErrorMacro("another piece failed; the index is not written");
  }
  ok = all;
  if (ok && (serial || this->Piece == 0))
  {
    lvdifvtk::VolumeIndex index;
    std::copy(whole, whole + 6, index.wholeExtent);
    // origin and spacing of the whole image (index 0), from the pipeline information
    double origin[3], spacing[3];
    for (int a = 0; a < 3; ++a)
    {
      origin[a] = sparse ? sparse->GetVolume()->options().origin[a] : image->GetOrigin()[a];
      spacing[a] = sparse ? sparse->GetVolume()->options().spacing[a] : image->GetSpacing()[a];
    }
    if (inInfo->Has(vtkDataObject::ORIGIN()))
      inInfo->Get(vtkDataObject::ORIGIN(), origin);
    if (inInfo->Has(vtkDataObject::SPACING()))
      inInfo->Get(vtkDataObject::SPACING(), spacing);
    std::copy(origin, origin + 3, index.origin);
    std::copy(spacing, spacing + 3, index.spacing);
    for (int p = 0; p < this->NumberOfPieces; ++p)
    {
      lvdifvtk::VolumeIndexPiece piece;
      if (sparse)
        SparsePieceExtent(sparse->GetVolume()->options(), p, this->NumberOfPieces, piece.extent);
      else
        PieceExtent(whole, p, this->NumberOfPieces, piece.extent);
      if (!lvdifvtk::extentIsValid(piece.extent))
        continue;
      piece.file = lvdifvtk::pieceFileName(this->FileName, p, generation);
      index.pieces.push_back(piece);
    }
    try
    {
      lvdifvtk::writeVolumeIndex(index, this->FileName);
    }
    catch (const lvdif::Error& e)
    {
      vtkErrorMacro(<< e.what());
      ok = 0;
    }
    // the index lists the new pieces: the set's other piece files (the old
    // generation, pieces of a write with more pieces) are no part of it now
    for (const std::string& name : ok ? setFiles(this->FileName, false) : std::vector<std::string>())
    {
      if (std::none_of(index.pieces.begin(), index.pieces.end(),
            [&](const lvdifvtk::VolumeIndexPiece& q) { return q.file == name; }))
        std::remove((lvdifvtk::directoryOf(this->FileName) + name).c_str());
    }
  }
  if (this->IsCollective())
  {
    // also the barrier: the index and every piece exist when Write() returns
    // on any rank; a failed index (piece 0's) fails every rank's Write()
    const int indexOk = this->AgreeOnIndex(ok);
    if (!indexOk && ok)
      vtkErrorMacro("piece 0 could not write the index '" << this->FileName << "'");
    ok = indexOk;
  }
  if (!ok)
  {
    // no index lists them: the old index and its pieces are the volume, as before the write
    for (const std::string& path : written)
      std::remove(path.c_str());
    this->SetErrorCode(vtkErrorCode::UnknownError);
  }
}

void vtkPDictionaryVolumeWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Piece: " << this->Piece << " of " << this->NumberOfPieces << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "CompressionLevel: " << this->CompressionLevel << "\n";
  os << indent << "VolumeName: " << this->VolumeName << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
