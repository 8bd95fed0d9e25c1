#include "LVDIFFiles.h"

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
#include "vtkOpenVDBLevelSetReader.h"
#include "vtkOpenVDBLevelSetWriter.h"
#endif

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkOBJWriter.h"
#include "vtkPLYWriter.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTrivialProducer.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>
#include <functional>

namespace LVDIFFiles
{
namespace
{
/// Runs a VTK algorithm for Core-style callers: progress and cancel through
/// the interrupter, the algorithm's errors turned into one lvdif::Error.
struct Watch
{
  lvdif::Interrupter& interrupter;
  std::string errors;
  std::string innerErrors; // of the objects inside a reader (VTK's XML parser)
  vtkNew<vtkCallbackCommand> onProgress, onError, onInnerError;

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
    this->onInnerError->SetClientData(this);
    this->onInnerError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      auto* w = static_cast<Watch*>(client);
      if (w->innerErrors.empty()) w->innerErrors = LVDIFVolumeBridge::MessageText(static_cast<const char*>(call));
    });
    for (vtkAlgorithm* a : algorithms)
    {
      a->AddObserver(vtkCommand::ProgressEvent, this->onProgress);
      a->AddObserver(vtkCommand::ErrorEvent, this->onError);
      a->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, this->onError);
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
    if (this->errors.empty() && !ok) this->errors = this->innerErrors;
    if (!ok || !this->errors.empty())
    {
      const std::string text =
        this->errors.empty() ? what + ": failed" : LVDIFVolumeBridge::WithContext(what + ": ", this->errors);
      throw lvdif::Error(lvdif::ErrorCode::IoFailure, text);
    }
  }
};

[[noreturn]] void unknown(const std::string& path, Kind kind, bool saving)
{
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
  if (Extension(path) == "lvdvp") lvdif::requireWritable(vtkPDictionaryVolumeWriter::PieceFilePath(path, 0));
}

std::shared_ptr<lvdif::DictionaryVolume> LoadVolume(const std::string& path, lvdif::Interrupter& interrupter)
{
  const Format* f = &RequireFormat(path, Kind::Volume, false);
  // a file to read, as Core's readers require of theirs (lvdif::FileSource):
  // a folder named x.vti was read by VTK's XML parser, "Error parsing input file"
  {
    lvdif::FileSource file(path);
  }
  const std::string what = "cannot read '" + path + "'";
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
    if (!reader->GetExecutive()->UpdateInformation()) watch.check(false, what);
    int e[6];
    reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), e);
    const std::string image = what + ": the image of " + std::to_string(std::int64_t(e[1]) - e[0] + 1) + " x " +
      std::to_string(std::int64_t(e[3]) - e[2] + 1) + " x " + std::to_string(std::int64_t(e[5]) - e[4] + 1) + " points";
    std::uint64_t bytes = 8;
    for (int a = 0; a < 3; ++a)
      bytes = lvdif::checkedMultiply(bytes, e[2 * a + 1] >= e[2 * a] ? std::uint64_t(e[2 * a + 1]) - e[2 * a] + 1 : 0, image);
    lvdif::requireMemory(bytes, image);
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
    const bool ok = writer->GetExecutive()->Update() != 0;
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
  std::function<int()> write;
  if (f->extension == "ply")
  {
    auto w = vtkSmartPointer<vtkPLYWriter>::New();
    w->SetFileName(path.c_str());
    w->SetFileTypeToBinary();
    w->SetArrayName("rgba");
    w->SetColorModeToDefault();
    w->EnableAlphaOn();
    writer = w;
    write = [w] { return w->Write(); };
  }
  else if (f->extension == "obj")
  {
    auto w = vtkSmartPointer<vtkOBJWriter>::New();
    w->SetFileName(path.c_str());
    writer = w;
    write = [w] { return w->Write(); };
  }
  else if (f->extension == "stl")
  {
    auto w = vtkSmartPointer<vtkSTLWriter>::New();
    w->SetFileName(path.c_str());
    w->SetFileTypeToBinary();
    writer = w;
    write = [w] { return w->Write(); };
  }
  else
  {
    auto w = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    w->SetFileName(path.c_str());
    writer = w;
    write = [w] { return w->Write(); };
  }
  writer->SetInputDataObject(mesh);
  Watch watch(lvdif::nullInterrupter(), { writer });
  const bool ok = write() != 0;
  watch.check(ok, "cannot write '" + path + "'");
}

} // namespace LVDIFFiles
