#include "LVDIFFiles.h"
#include "LVDIFPipedSave.h"
#include "LVDIFXmlNesting.h"

#include "LVDIFVolumeBridge.h"

#include "vtkDictionaryVolumeReader.h"
#include "vtkDictionaryVolumeWriter.h"
#include "vtkImageToSparseVolume.h"
#include "vtkLVDIFMeshReader.h"
#include "vtkLegacyBvReader.h"
#include "vtkLegacyBvWriter.h"
#include "vtkPDictionaryVolumeReader.h"
#include "vtkPDictionaryVolumeWriter.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkSparseVolumeToImage.h"
#ifdef LVDIF_WITH_OPENVDB_MODULE
#include "LVDIFOpenVDB.h"
#include "vtkOpenVDBLevelSetReader.h"
#include "vtkOpenVDBLevelSetWriter.h"
#endif

#include "lvdif/ByteStream.h"
#include "lvdif/CNumbers.h"
#include "lvdif/Error.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/Memory.h"
#include "lvdif/PieceTiling.h"
#include "lvdif/VolumeFile.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkErrorCode.h"
#include "vtkWriter.h"
#include "vtkXMLWriter.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkOBJWriter.h"
#include "vtkPLYWriter.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTrivialProducer.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkCellArray.h"

#include <algorithm>
#include <cctype>
#include <functional>

namespace LVDIFFiles
{
namespace
{
/// The deepest nesting of a .vti's XML elements read (VTKFile, ImageData, Piece,
/// PointData, DataArray, InformationKey, Value: 7 at most as VTK writes them).
constexpr int MaxXmlNesting = 64;

/// Runs a VTK algorithm for Core-style callers: progress and cancel through
/// the interrupter, the algorithm's errors turned into one lvdif::Error.
struct Watch
{
  lvdif::Interrupter& interrupter;
  std::string errors;
  std::string innerErrors; // of the objects inside a reader (VTK's XML parser)
  // the executive's "Algorithm vtkX(0x...) returned failure for request: vtkInformation ..." and
  // its dump of the request, a dozen lines: only the algorithm's name kept, said only when
  // neither the algorithm nor a writer's error code says more (VTK's XML writers fail on a full
  // disk without a word)
  std::string executiveErrors;
  vtkNew<vtkCallbackCommand> onProgress, onError, onInnerError, onExecutiveError;
  std::vector<vtkAlgorithm*> writers; // their error codes name a failed write that no message names

  Watch(lvdif::Interrupter& in, const std::vector<vtkAlgorithm*>& algorithms)
    : interrupter(in)
  {
    this->onProgress->SetClientData(this);
    this->onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
      auto* w = static_cast<Watch*>(client);
      // VTK reports 1.0 after every RequestData, failed or not: "done" is
      // said by end(), after check()
      w->interrupter.progress(std::min(*static_cast<double*>(call), 0.99));
      if (w->interrupter.wasInterrupted()) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    });
    this->onError->SetClientData(this);
    this->onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      auto* w = static_cast<Watch*>(client);
      const std::string text = LVDIFVolumeBridge::MessageText(static_cast<const char*>(call));
      if (w->errors.empty()) w->errors = text; // the first error names the cause
    });
    this->onExecutiveError->SetClientData(this);
    this->onExecutiveError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      auto* w = static_cast<Watch*>(client);
      const std::string text = static_cast<const char*>(call);
      const auto at = text.find("Algorithm "), paren = text.find('(', at == std::string::npos ? 0 : at);
      if (!w->executiveErrors.empty()) return;
      if (at != std::string::npos && paren != std::string::npos && text.find("returned failure", paren) != std::string::npos)
        w->executiveErrors = text.substr(at + 10, paren - at - 10) + " failed without saying why";
      else
        w->executiveErrors = LVDIFVolumeBridge::MessageText(text.substr(0, text.find('\n')).c_str());
    });
    this->onInnerError->SetClientData(this);
    this->onInnerError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      auto* w = static_cast<Watch*>(client);
      if (w->innerErrors.empty()) w->innerErrors = LVDIFVolumeBridge::MessageText(static_cast<const char*>(call));
    });
    for (vtkAlgorithm* a : algorithms)
    {
      if (vtkWriter::SafeDownCast(a) || vtkXMLWriter::SafeDownCast(a)) this->writers.push_back(a);
      a->AddObserver(vtkCommand::ProgressEvent, this->onProgress);
      a->AddObserver(vtkCommand::ErrorEvent, this->onError);
      a->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->onExecutiveError);
      if (auto* xml = vtkXMLReader::SafeDownCast(a))
      {
        // the reader's own XML parser (made at each read) is no observed
        // object: its error printed one more line in VTK's log format. Its
        // text is kept only for a failure the reader itself does not name.
        xml->SetParserErrorObserver(this->onInnerError);
        xml->SetReaderErrorObserver(this->onInnerError);
      }
    }
  }

  /// Throws when the run failed or was cancelled; `what` names the file
  /// ("cannot read 'x'") unless the reader's own message already does.
  void check(bool ok, const std::string& what)
  {
    this->interrupter.checkInterrupt();
    ok = ok && this->executiveErrors.empty(); // (a writer's Write() answered 1 over the executive's failure)
    if (this->errors.empty() && !ok) this->errors = this->innerErrors;
    for (vtkAlgorithm* w : this->writers)
      if (this->errors.empty() && w->GetErrorCode() != vtkErrorCode::NoError)
        this->errors = w->GetErrorCode() == vtkErrorCode::OutOfDiskSpaceError
          ? std::string("the writer ran out of space (the disk full, or a file size limit?)")
          : std::string("the writer failed (") + vtkErrorCode::GetStringFromErrorCode(w->GetErrorCode()) + ")";
    if (this->errors.empty() && !ok) this->errors = this->executiveErrors;
    if (!ok || !this->errors.empty())
    {
      const std::string text =
        !this->errors.empty() ? LVDIFVolumeBridge::WithContext(what + ": ", this->errors)
        : this->writers.empty() ? what + ": failed"
                                : what + ": the writer failed without a reason (the disk full, or a file size limit?)";
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, text);
    }
  }
};

[[noreturn]] void unknown(const std::string& path, Kind kind, bool saving)
{
  // an empty argument ('lvdif convert v.lvdv ""') was "cannot write '': volumes are .lvdv, ... files"
  if (path.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      std::string("no ") + (kind == Kind::Volume ? "volume" : "mesh") + " file name to " + (saving ? "write" : "read") +
        " (an empty argument)");
  std::string list;
  for (const Format& f : Formats())
  {
    if (f.kind == kind && !(saving ? f.writerClass : f.readerClass).empty())
      list += (list.empty() ? "." : ", .") + f.extension;
  }
  throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
    std::string("cannot ") + (saving ? "write" : "read") + " '" + path + "': " +
      (kind == Kind::Volume ? "volumes" : "meshes") + " are " + list + " files");
}

/// The numbers of an attribute of a .vti's header, as written: exactly `n`
/// numbers (each one whole text) or an error. VTK's reader takes a value it
/// cannot parse (Spacing="nan 1 1", "inf") for its default, 1 or 0.
std::vector<double> attributeNumbers(
  vtkXMLDataElement* e, const char* name, std::size_t n, const std::string& what)
{
  const char* text = e->GetAttribute(name);
  if (!text)
    return {};
  std::vector<double> v;
  const char* p = text;
  for (;;)
  {
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
      ++p;
    if (!*p)
      break;
    char* end = nullptr;
    const double x = lvdif::strtodC(p, &end);
    // (decimal only: VTK's reader took "0x1p1" for 0, then its default)
    const bool hex = std::string(p, static_cast<const char*>(end)).find_first_of("xX") != std::string::npos;
    if (end == p || hex || (*end && *end != ' ' && *end != '\t' && *end != '\n' && *end != '\r'))
    {
      v.clear();
      break;
    }
    v.push_back(x);
    p = end;
  }
  if (v.size() != n)
    throw lvdif::Error(lvdif::ErrorCode::CorruptData,
      what + ": " + name + "=\"" + std::string(text).substr(0, 80) + "\" is not " + std::to_string(n) + " numbers");
  return v;
}

/// Bytes of a base64 text (whitespace skipped), up to `want` bytes.
std::vector<std::uint8_t> fromBase64(const std::string& text, std::size_t want)
{
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  std::vector<std::uint8_t> out;
  std::uint32_t bits = 0;
  int count = 0;
  for (char c : text)
  {
    const int v = value(c);
    if (v < 0)
    {
      if (c != '=') continue;
      // the padded end of a chunk: its last 1 or 2 bytes ("xx==", "xxx=")
      bits <<= 6 * (4 - count);
      for (int k = 2; k > 3 - count && out.size() < want; --k) out.push_back(std::uint8_t(bits >> (8 * k)));
      break;
    }
    bits = (bits << 6) | std::uint32_t(v);
    if (++count == 4)
    {
      for (int k = 2; k >= 0 && out.size() < want; --k) out.push_back(std::uint8_t(bits >> (8 * k)));
      bits = 0;
      count = 0;
      if (out.size() >= want) break;
    }
  }
  return out;
}

/// The sizes a compressed array's header declares, checked before VTK's reader
/// allocates by them: it allocated the block table (a word per block) and a
/// buffer of the largest block, so a forged count of 2^31 blocks ended in
/// "std::bad_alloc" (or took gigabytes). The table must fit in the file, a
/// block in the array's values (or 16 MiB), a compressed block in the file.
void checkCompressedArrays(
  vtkXMLDataParser* parser, vtkXMLDataElement* root, vtkXMLDataElement* image, const std::string& path, const std::string& what)
{
  if (!root->GetAttribute("compressor"))
    return;
  const char* headerType = root->GetAttribute("header_type");
  const std::uint64_t ws = headerType && std::string(headerType) == "UInt64" ? 8 : 4;
  lvdif::FileSource file(path);
  vtkXMLDataElement* appended = root->FindNestedElementWithName("AppendedData");
  const bool appendedRaw = appended && appended->GetAttribute("encoding") &&
    std::string(appended->GetAttribute("encoding")) == "raw";
  const vtkTypeInt64 appendedAt = parser->GetAppendedDataPosition();
  // the header's words of the array at `at` (raw bytes, or base64 text)
  auto words = [&](std::uint64_t at, bool raw, std::uint64_t n) {
    std::vector<std::uint8_t> bytes;
    const std::uint64_t need = n * ws;
    const std::uint64_t span = raw ? need : (need + 2) / 3 * 4 + 4096; // (whitespace before it)
    if (at >= file.size()) return std::vector<std::uint64_t>();
    std::string buffer(static_cast<std::size_t>(std::min<std::uint64_t>(span, file.size() - at)), '\0');
    file.read(at, &buffer[0], buffer.size());
    if (raw)
      bytes.assign(buffer.begin(), buffer.end());
    else
    {
      const auto first = buffer.find_first_not_of(" \t\r\n>");
      bytes = fromBase64(first == std::string::npos ? std::string() : buffer.substr(first), static_cast<std::size_t>(need));
    }
    std::vector<std::uint64_t> w;
    for (std::uint64_t i = 0; i + ws <= bytes.size() && w.size() < n; i += ws)
    {
      std::uint64_t v = 0;
      for (std::uint64_t b = 0; b < ws; ++b) v |= std::uint64_t(bytes[i + b]) << (8 * b);
      w.push_back(v);
    }
    return w;
  };
  const std::map<std::string, std::uint64_t> typeBytes{ { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 }, { "UInt16", 2 },
    { "Int32", 4 }, { "UInt32", 4 }, { "Float32", 4 }, { "Int64", 8 }, { "UInt64", 8 }, { "Float64", 8 } };
  std::function<void(vtkXMLDataElement*, std::uint64_t)> visit = [&](vtkXMLDataElement* e, std::uint64_t points) {
    const std::string name = e->GetName() ? e->GetName() : "";
    if (name == "Piece")
    {
      int x[6];
      if (e->GetVectorAttribute("Extent", 6, x) != 6) return;
      points = 1;
      for (int a = 0; a < 3; ++a) points *= x[2 * a + 1] >= x[2 * a] ? std::uint64_t(x[2 * a + 1]) - x[2 * a] + 1 : 0;
    }
    if (name == "DataArray")
    {
      const char* format = e->GetAttribute("format");
      const char* type = e->GetAttribute("type");
      const std::string f = format ? format : "";
      std::uint64_t at = 0;
      bool raw = false;
      if (f == "appended" && appended && appendedAt > 0)
      {
        vtkTypeInt64 offset = 0;
        if (!e->GetScalarAttribute("offset", offset) || offset < 0) return;
        at = std::uint64_t(appendedAt) + std::uint64_t(offset);
        raw = appendedRaw;
      }
      else if (f == "binary" && e->GetXMLByteIndex() > 0)
      {
        // the element's text after its start tag
        std::string tag(static_cast<std::size_t>(std::min<std::uint64_t>(65536, file.size() - std::uint64_t(e->GetXMLByteIndex()))), '\0');
        file.read(std::uint64_t(e->GetXMLByteIndex()), &tag[0], tag.size());
        const auto close = tag.find('>');
        if (close == std::string::npos) return;
        at = std::uint64_t(e->GetXMLByteIndex()) + close + 1;
      }
      else
        return;
      const std::vector<std::uint64_t> head = words(at, raw, 3);
      if (head.size() < 3) return; // VTK's reader says the data is short
      const std::string array = "the DataArray '" + std::string(e->GetAttribute("Name") ? e->GetAttribute("Name") : "") + "'";
      if (head[0] > file.size() / ws)
        throw lvdif::Error(lvdif::ErrorCode::CorruptData, what + ": " + array + " declares " +
            std::to_string(head[0]) + " compressed blocks, more than the file's " + std::to_string(file.size()) +
            " bytes can list");
      int components = 1;
      e->GetScalarAttribute("NumberOfComponents", components);
      const auto t = typeBytes.find(type ? type : "");
      const std::uint64_t values = (t == typeBytes.end() ? 8 : t->second) * std::uint64_t(std::max(components, 1)) * points;
      const std::uint64_t most = std::max<std::uint64_t>(values, std::uint64_t(1) << 24);
      if (head[1] > most || head[2] > most)
        throw lvdif::Error(lvdif::ErrorCode::CorruptData, what + ": " + array + " declares blocks of " +
            std::to_string(std::max(head[1], head[2])) + " bytes, more than its " + std::to_string(values) +
            " bytes of values");
      const std::vector<std::uint64_t> all = words(at, raw, 3 + head[0]);
      for (std::size_t b = 3; b < all.size(); ++b)
        if (all[b] > file.size())
          throw lvdif::Error(lvdif::ErrorCode::CorruptData, what + ": " + array + " declares a compressed block of " +
              std::to_string(all[b]) + " bytes, more than the file's " + std::to_string(file.size()));
      return;
    }
    for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) visit(e->GetNestedElement(i), points);
  };
  visit(image, 0);
}

/// The header of a .vti as written (after UpdateInformation, which parsed it):
/// its pieces must tile its WholeExtent (a point no piece holds was made up,
/// the memory VTK allocates left as it was) and its Origin and Spacing pass the
/// volumes' one geometry rule (DictionaryVolume::checkGeometry: finite, spacing
/// >= 1e-30), before the data is read.
void checkImageHeader(vtkXMLImageDataReader* reader, const int whole[6], const std::string& what)
{
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* image = root ? root->FindNestedElementWithName("ImageData") : nullptr;
  if (!image)
    return; // VTK's reader said what is missing
  lvdif::VoxelBox wholeBox;
  lvdif::VolumeOptions o;
  for (int a = 0; a < 3; ++a)
  {
    wholeBox.lo[a] = whole[2 * a];
    wholeBox.hi[a] = whole[2 * a + 1];
    o.dims[a] = std::max<std::int64_t>(1, std::int64_t(whole[2 * a + 1]) - whole[2 * a] + 1);
  }
  const std::vector<double> origin = attributeNumbers(image, "Origin", 3, what);
  const std::vector<double> spacing = attributeNumbers(image, "Spacing", 3, what);
  attributeNumbers(image, "Direction", 9, what); // (its value is checked by the conversion)
  for (int a = 0; a < 3; ++a)
  {
    o.spacing[a] = spacing.empty() ? 1.0 : spacing[a];
    o.origin[a] = origin.empty() ? 0.0 : origin[a];
    if (whole[2 * a] != 0) o.origin[a] += whole[2 * a] * o.spacing[a]; // (0 x nan would blame the origin)
  }
  const std::string geometry = lvdif::DictionaryVolume::checkGeometry(o);
  if (!geometry.empty())
    throw lvdif::Error(lvdif::ErrorCode::CorruptData, what + ": " + geometry);
  std::vector<lvdif::VoxelBox> pieces;
  for (int i = 0; i < image->GetNumberOfNestedElements(); ++i)
  {
    vtkXMLDataElement* piece = image->GetNestedElement(i);
    if (std::string(piece->GetName() ? piece->GetName() : "") != "Piece")
      continue;
    int e[6];
    if (piece->GetVectorAttribute("Extent", 6, e) != 6)
      return; // VTK's reader says "Extent attribute is not 6 integers"
    lvdif::VoxelBox b;
    for (int a = 0; a < 3; ++a)
    {
      b.lo[a] = e[2 * a];
      b.hi[a] = e[2 * a + 1];
    }
    pieces.push_back(b);
  }
  const std::string tiling = lvdif::pieceTilingProblem(wholeBox, pieces, "piece", true);
  if (!tiling.empty())
    throw lvdif::Error(lvdif::ErrorCode::CorruptData, what + ": " + tiling);
  checkCompressedArrays(parser, root, image, reader->GetFileName() ? reader->GetFileName() : "", what);
}

std::shared_ptr<lvdif::DictionaryVolume> volumeOf(vtkAlgorithm* a)
{
  auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(a->GetOutputDataObject(0));
  return sparse ? sparse->GetVolume() : nullptr;
}

} // namespace

const std::vector<Format>& Formats()
{
  static const std::vector<Format> formats = {
    { "lvdv", "LVDIF Dictionary Volume Files", Kind::Volume, "vtkDictionaryVolumeReader",
      "vtkDictionaryVolumeWriter" },
    { "lvdvp", "LVDIF Distributed Dictionary Volume Files", Kind::Volume, "vtkPDictionaryVolumeReader",
      "vtkPDictionaryVolumeWriter" },
    { "bv", "Original LVDIF volume", Kind::Volume, "vtkLegacyBvReader", "vtkLegacyBvWriter" },
#ifdef LVDIF_WITH_OPENVDB_MODULE
    { "vdb", "OpenVDB level set", Kind::Volume, "vtkOpenVDBLevelSetReader", "vtkOpenVDBLevelSetWriter" },
#endif
    { "vti", "VTK image (dense sdf, rgba)", Kind::Volume, "vtkXMLImageDataReader", "vtkXMLImageDataWriter" },
    { "ply", "PLY mesh", Kind::Mesh, "vtkLVDIFMeshReader", "vtkPLYWriter" },
    { "obj", "Wavefront OBJ mesh", Kind::Mesh, "vtkLVDIFMeshReader", "vtkOBJWriter" },
    { "stl", "STL mesh", Kind::Mesh, "vtkLVDIFMeshReader", "vtkSTLWriter" },
    { "off", "OFF mesh", Kind::Mesh, "vtkLVDIFMeshReader", "" },
    { "vtp", "VTK polydata", Kind::Mesh, "", "vtkXMLPolyDataWriter" },
  };
  return formats;
}

std::string Extension(const std::string& path)
{
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::string();
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

const Format* Find(const std::string& path, Kind kind)
{
  const std::string ext = Extension(path);
  for (const Format& f : Formats())
    if (f.kind == kind && f.extension == ext) return &f;
  return nullptr;
}

const Format& RequireFormat(const std::string& path, Kind kind, bool forSaving)
{
  const Format* f = Find(path, kind);
  if (!f || (forSaving ? f->writerClass : f->readerClass).empty()) unknown(path, kind, forSaving);
  return *f;
}

std::string DialogFilter(Kind kind, bool forSaving)
{
  std::string all, each;
  for (const Format& f : Formats())
  {
    if (f.kind != kind || (forSaving ? f.writerClass : f.readerClass).empty()) continue;
    all += (all.empty() ? "*." : " *.") + f.extension;
    each += ";;" + f.description + " (*." + f.extension + ")";
  }
  return std::string(kind == Kind::Volume ? "Volumes" : "Meshes") + " (" + all + ")" + each;
}

void RequireWritable(const std::string& path)
{
  lvdif::requireWritable(path);
  // a single process writes piece 0 (ranks their own, each checked by its writer)
  if (Extension(path) == "lvdvp")
  {
    lvdif::requireWritable(vtkPDictionaryVolumeWriter::PieceFilePath(
      path, 0, vtkPDictionaryVolumeWriter::NextGeneration(path)));
    vtkPDictionaryVolumeWriter::RequireNoUnlistedPieces(path);
  }
}

std::string GridProblem(const std::string& path, const lvdif::Index3& dims, const double* spacing)
{
  const std::string ext = Extension(path);
  if (ext == "bv")
    return lvdif::checkLegacyBvDims(dims, path);
#ifdef LVDIF_WITH_OPENVDB_MODULE
  if (ext == "vdb" && spacing)
  {
    try
    {
      lvdif::vdb::checkExportSpacing(spacing);
    }
    catch (const lvdif::Error& e)
    {
      return e.what();
    }
  }
#else
  (void)spacing;
#endif
  return std::string();
}

bool ReadGrid(const std::string& path, lvdif::VolumeOptions& grid)
{
  const std::string ext = Extension(path);
  try
  {
    if (ext == "lvdv")
    {
      grid = lvdif::readVolumeInfo(path).options;
      return true;
    }
    if (ext != "vti")
      return false;
    RequireXmlNestingBelow(path, MaxXmlNesting, "cannot read '" + path + "'");
    auto reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
    reader->SetFileName(path.c_str());
    Watch watch(lvdif::nullInterrupter(), { reader }); // keeps VTK's errors (the load says what is wrong)
    if (!reader->GetExecutive()->UpdateInformation() || !watch.errors.empty() || !watch.innerErrors.empty())
      return false;
    vtkInformation* info = reader->GetOutputInformation(0);
    int e[6];
    double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
    if (info->Has(vtkDataObject::SPACING())) info->Get(vtkDataObject::SPACING(), spacing);
    if (info->Has(vtkDataObject::ORIGIN())) info->Get(vtkDataObject::ORIGIN(), origin);
    for (int a = 0; a < 3; ++a)
    {
      grid.dims[a] = std::max<std::int64_t>(1, std::int64_t(e[2 * a + 1]) - e[2 * a] + 1);
      grid.spacing[a] = spacing[a];
      grid.origin[a] = origin[a] + e[2 * a] * spacing[a];
    }
    return true;
  }
  catch (const lvdif::Error&)
  {
    return false;
  }
}

std::shared_ptr<lvdif::DictionaryVolume> LoadVolume(const std::string& path, lvdif::Interrupter& interrupter)
{
  const Format* f = &RequireFormat(path, Kind::Volume, false);
  // a file to read, as Core's readers require of theirs (lvdif::FileSource):
  // a folder named x.vti was read by VTK's XML parser, "Error parsing input file"
  const std::string what = "cannot read '" + path + "'";
  {
    lvdif::FileSource file(path);
    // an empty (or blank) .vti was VTK's "Error parsing input file. ReadXMLInformation aborting."
    if (f->extension == "vti" && file.size() <= 4096)
    {
      std::string text(static_cast<std::size_t>(file.size()), '\0');
      if (!text.empty()) file.read(0, &text[0], text.size());
      if (text.find_first_not_of(" \t\r\n") == std::string::npos)
        throw lvdif::Error(lvdif::ErrorCode::CorruptData,
          what + ": the file is empty" + (text.empty() ? "" : " (blank)") + ": no VTK image in it");
    }
  }
  if (f->extension == "vti")
    RequireXmlNestingBelow(path, MaxXmlNesting, what);
  vtkSmartPointer<vtkAlgorithm> reader, last;
  if (f->extension == "lvdv")
  {
    auto r = vtkSmartPointer<vtkDictionaryVolumeReader>::New();
    r->SetFileName(path.c_str());
    reader = last = r;
  }
  else if (f->extension == "lvdvp")
  {
    auto r = vtkSmartPointer<vtkPDictionaryVolumeReader>::New(); // the pieces' keys, no re-encoding
    r->SetFileName(path.c_str());
    reader = last = r;
  }
  else if (f->extension == "bv")
  {
    auto r = vtkSmartPointer<vtkLegacyBvReader>::New();
    r->SetFileName(path.c_str());
    reader = last = r;
  }
#ifdef LVDIF_WITH_OPENVDB_MODULE
  else if (f->extension == "vdb")
  {
    auto r = vtkSmartPointer<vtkOpenVDBLevelSetReader>::New();
    r->SetFileName(path.c_str());
    reader = last = r;
  }
#endif
  else
  {
    // images (.vti) become the sparse volume with the defaults (band 8, chunk edge 32)
    auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
    auto toSparse = vtkSmartPointer<vtkImageToSparseVolume>::New();
    toSparse->SetInputConnection(reader->GetOutputPort());
    last = toSparse;
  }
  Watch watch(interrupter, { reader, last });
  if (f->extension == "vti")
  {
    // VTK's reader allocates the dense arrays of the header's whole extent
    // before it reads them: a forged extent ended in "std::bad_alloc". Its
    // size is known from the header (UpdateInformation reads no data): at
    // least 4 bytes a point for the sdf, up to 4 more for the sparse volume.
    if (!reader->GetExecutive()->UpdateInformation())
    {
      // VTK's XML parser found no XML image: its words were "Error parsing input file"
      if ((watch.errors + watch.innerErrors).find("Error parsing") != std::string::npos)
        throw lvdif::Error(lvdif::ErrorCode::CorruptData, what + ": not a VTK XML image (truncated or another format)");
      watch.check(false, what);
    }
    int e[6];
    reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
    const std::string image = what + ": the image of " + std::to_string(std::int64_t(e[1]) - e[0] + 1) + " x " +
      std::to_string(std::int64_t(e[3]) - e[2] + 1) + " x " + std::to_string(std::int64_t(e[5]) - e[4] + 1) + " points";
    std::uint64_t bytes = 8;
    for (int a = 0; a < 3; ++a)
      bytes = lvdif::checkedMultiply(bytes, e[2 * a + 1] >= e[2 * a] ? std::uint64_t(e[2 * a + 1]) - e[2 * a] + 1 : 0, image);
    lvdif::requireMemory(bytes, image);
    checkImageHeader(vtkXMLImageDataReader::SafeDownCast(reader), e, what);
  }
  interrupter.start("read volume");
  const bool ok = last->GetExecutive()->Update() != 0;
  watch.check(ok, what);
  interrupter.end(); // only a stage that succeeded is "done"
  std::shared_ptr<lvdif::DictionaryVolume> volume = volumeOf(last);
  if (!volume) throw lvdif::Error(lvdif::ErrorCode::IoFailure, what + ": no volume");
  return volume;
}

void SaveVolume(const std::shared_ptr<lvdif::DictionaryVolume>& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& interrupter)
{
  const Format* f = &RequireFormat(path, Kind::Volume, true);
  RequireWritable(path); // before any work (a .vti's dense conversion), in the CLI's words
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  vtkNew<vtkTrivialProducer> source;
  source->SetOutput(sparse);
  vtkSmartPointer<vtkAlgorithm> writer, dense;
  vtkSmartPointer<vtkXMLImageDataWriter> byName; // a VTK writer that writes in place: given a temporary name
  if (f->extension == "lvdv")
  {
    auto w = vtkSmartPointer<vtkDictionaryVolumeWriter>::New();
    w->SetFileName(path.c_str());
    for (const auto& kv : metadata) w->AddMetadata(kv.first, kv.second);
    writer = w;
  }
  else if (f->extension == "lvdvp")
  {
    auto w = vtkSmartPointer<vtkPDictionaryVolumeWriter>::New();
    w->SetFileName(path.c_str());
    writer = w;
  }
  else if (f->extension == "bv")
  {
    auto w = vtkSmartPointer<vtkLegacyBvWriter>::New();
    w->SetFileName(path.c_str());
    writer = w;
  }
#ifdef LVDIF_WITH_OPENVDB_MODULE
  else if (f->extension == "vdb")
  {
    auto w = vtkSmartPointer<vtkOpenVDBLevelSetWriter>::New();
    w->SetFileName(path.c_str());
    writer = w;
  }
#endif
  else
  {
    byName = vtkSmartPointer<vtkXMLImageDataWriter>::New();
    writer = byName;
    dense = vtkSmartPointer<vtkSparseVolumeToImage>::New(); // states the memory, refuses above the limit
    dense->SetInputConnection(source->GetOutputPort());
  }
  writer->SetInputConnection(dense ? dense->GetOutputPort() : source->GetOutputPort());
  std::vector<vtkAlgorithm*> watched{ writer };
  if (dense) watched.push_back(dense);
  Watch watch(interrupter, watched);
  interrupter.start("save volume");
  auto write = [&] {
    const bool ok = writer->GetExecutive()->Update() != 0 && writer->GetErrorCode() == 0;
    watch.check(ok, "cannot write '" + path + "'");
  };
  if (byName)
  {
    // the LVDIF writers save atomically themselves; VTK's XML writer would
    // truncate the old file first, so it writes a temporary file renamed over it
    lvdif::saveAtomicallyByName(path, [&](const std::string& tmp) {
      byName->SetFileName(tmp.c_str());
      write();
    });
  }
  else
    write();
  interrupter.end();
}

vtkSmartPointer<vtkPolyData> LoadMesh(const std::string& path)
{
  const Format* f = &RequireFormat(path, Kind::Mesh, false);
  vtkNew<vtkLVDIFMeshReader> reader;
  reader->SetFileName(path.c_str());
  Watch watch(lvdif::nullInterrupter(), { reader });
  const bool ok = reader->GetExecutive()->Update() != 0;
  watch.check(ok, "cannot read '" + path + "'");
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(reader->GetOutput());
  return mesh;
}

void SaveMesh(vtkPolyData* mesh, const std::string& path)
{
  const Format* f = &RequireFormat(path, Kind::Mesh, true);
  vtkSmartPointer<vtkAlgorithm> writer;
  std::function<int(const std::string& target)> write; // the writer writes to `target`
  // A save never destroys the old file: the writer writes a temporary file renamed over it
  // (the editor's export wrote in place, so a failing write lost the old mesh). The PLY and
  // OBJ writers never check their writes (on a full disk Write() answered 1 over a cut file):
  // their bytes go through a pipe into the save's checked sink (SaveThroughPipe).
  enum class Route
  {
    ByName, // a writer that reports a failed write itself
    Pipe
  } route = Route::ByName;
  if (f->extension == "ply")
  {
    auto w = vtkSmartPointer<vtkPLYWriter>::New();
    route = Route::Pipe;
    w->SetFileTypeToBinary();
    w->SetArrayName("rgba");
    w->SetColorModeToDefault();
    w->EnableAlphaOn();
    writer = w;
    write = [w](const std::string& target) {
      w->SetFileName(target.c_str());
      return w->Write();
    };
  }
  else if (f->extension == "obj")
  {
    auto w = vtkSmartPointer<vtkOBJWriter>::New();
    route = Route::Pipe;
    writer = w;
    write = [w](const std::string& target) {
      w->SetFileName(target.c_str());
      return w->Write();
    };
  }
  else if (f->extension == "stl")
  {
    auto w = vtkSmartPointer<vtkSTLWriter>::New();
    w->SetFileTypeToBinary();
    writer = w;
    write = [w](const std::string& target) {
      w->SetFileName(target.c_str());
      return w->Write();
    };
  }
  else
  {
    auto w = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    writer = w;
    write = [w](const std::string& target) {
      w->SetFileName(target.c_str());
      return w->Write();
    };
  }
  writer->SetInputDataObject(mesh);
  Watch watch(lvdif::nullInterrupter(), { writer });
  auto run = [&](const std::string& target) {
    // (VTK's XML writer answered 1 on a full disk, its error code set)
    watch.check(write(target) != 0 && writer->GetErrorCode() == 0, "cannot write '" + path + "'");
  };
  try
  {
    if (route == Route::ByName)
      lvdif::saveAtomicallyByName(path, run); // (a temporary of the same extension)
    else if (!SaveThroughPipe(path, run))
      lvdif::saveAtomicallyByName(path, run); // a folder without links: as before, a full disk unseen
  }
  catch (const lvdif::Error& e)
  {
    // the save's own failures name its temporary file: the file given first, as the volumes' saves
    throw lvdif::Error(e.code(), LVDIFVolumeBridge::WithContext("cannot write '" + path + "': ", e.what()));
  }
}

} // namespace LVDIFFiles
