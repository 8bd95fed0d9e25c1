// The file registry: every volume format round-trips a sphere volume (against
// the analytic field, within each format's quantization), meshes round-trip
// through every mesh format, unknown extensions give one clear error, and the
// ParaView plugin's reader/writer hints list exactly the registry's extensions
// for each class (the registry is the one source of the formats).
#include "LVDIFFiles.h"

#include "FileTestUtil.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Error.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkBase64Utilities.h"
#include "vtkXMLImageDataWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <limits>
#include <dirent.h>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

namespace
{
std::string temp(const std::string& name)
{
  return std::string(::testing::TempDir()) + "/lvdif_files_" + name;
}

std::shared_ptr<lvdif::DictionaryVolume> sphere()
{
  lvdif::VolumeOptions o;
  o.dims = { 40, 40, 40 }; // cubic: the .bv format has no header
  o.chunkEdge = 16;
  auto v = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*v, lvdif::sphereSdf(19.3, 20.1, 18.7, 12.0));
  return v;
}

/// f(x, y, z, the distance read back) for each voxel of the 40^3 volume `v` that `back` (v saved and
/// read again) covers: a format may crop or pad (OpenVDB: the active box), so by world position.
void forEachVoxelReadBack(const lvdif::DictionaryVolume& v, const lvdif::DictionaryVolume& back,
  const std::function<void(std::int64_t, std::int64_t, std::int64_t, float)>& f)
{
  std::int64_t off[3];
  for (int a = 0; a < 3; ++a)
    off[a] = std::llround((back.options().origin[a] - v.options().origin[a]) / v.options().spacing[a]);
  for (std::int64_t z = 0; z < 40; ++z)
    for (std::int64_t y = 0; y < 40; ++y)
      for (std::int64_t x = 0; x < 40; ++x)
        if (back.inside(x - off[0], y - off[1], z - off[2])) f(x, y, z, back.sdf(x - off[0], y - off[1], z - off[2]));
}
}

TEST(LVDIFFiles, EveryVolumeFormatRoundTrips)
{
  const auto v = sphere();
  const auto analytic = lvdif::sphereSdf(19.3, 20.1, 18.7, 12.0);
  int formats = 0;
  for (const auto& f : LVDIFFiles::Formats())
  {
    if (f.kind != LVDIFFiles::Kind::Volume || f.writerClass.empty() || f.readerClass.empty()) continue;
    ++formats;
    const std::string path = temp("SDF_40_sphere." + f.extension);
    // a fresh write: an earlier run's pieces without their index are refused as another volume's files
    for (const char* piece : { "_0.lvdv", "_0.g1.lvdv" })
      std::remove(temp(std::string("SDF_40_sphere") + piece).c_str());
    LVDIFFiles::SaveVolume(v, path, { { "source mesh", "analytic" } });
    std::shared_ptr<lvdif::DictionaryVolume> back = LVDIFFiles::LoadVolume(path);
    ASSERT_TRUE(back) << f.extension;
    int bad = 0, compared = 0;
    forEachVoxelReadBack(*v, *back, [&](std::int64_t x, std::int64_t y, std::int64_t z, float read) {
      const double d = analytic(static_cast<double>(x), static_cast<double>(y), static_cast<double>(z));
      if (std::fabs(d) > 3.0) return; // the band every format keeps
      ++compared;
      // two dictionaries at most (ours, then the original's for .bv): two half steps
      bad += std::fabs(read - d) > 0.0011;
    });
    EXPECT_GT(compared, 1000) << f.extension;
    EXPECT_EQ(bad, 0) << f.extension;
    std::remove(path.c_str());
  }
  EXPECT_GE(formats, 4); // lvdv, lvdvp, bv, vti (+ vdb with OpenVDB)
}

#ifdef LVDIF_WITH_OPENVDB_MODULE
namespace
{
/// The warnings VTK displays while it is the output window.
class WarningLog : public vtkOutputWindow
{
public:
  static WarningLog* New();
  vtkTypeMacro(WarningLog, vtkOutputWindow);
  void DisplayWarningText(const char* text) override { this->Warnings.push_back(text); }
  std::vector<std::string> Warnings;
};
vtkStandardNewMacro(WarningLog);
}

// A .vdb keeps the volume's band: `lvdif convert` and the editor save through
// the registry, whose OpenVDB writer wrote 3 voxels (its HalfWidth default)
// of a band of 8 without a word. An unlimited band must become a finite one
// (a level set's background): 3 voxels, said once with both widths.
TEST(LVDIFFiles, VdbKeepsTheVolumesBandAndSaysWhenItCannot)
{
  vtkNew<WarningLog> log;
  vtkOutputWindow* previous = vtkOutputWindow::GetInstance();
  previous->Register(nullptr);
  vtkOutputWindow::SetInstance(log);
  vtkObject::GlobalWarningDisplayOn();
  const auto analytic = lvdif::sphereSdf(19.3, 20.1, 18.7, 12.0);
  const auto v = sphere(); // band 8, the default
  ASSERT_EQ(v->bandWidth(), 8.0f);
  const std::string path = temp("band.vdb");
  LVDIFFiles::SaveVolume(v, path, {});
  EXPECT_TRUE(log->Warnings.empty()) << log->Warnings.front();
  auto back = LVDIFFiles::LoadVolume(path);
  EXPECT_EQ(back->bandWidth(), 8.0f);
  // voxels 3.5 to 7 voxels from the surface (beyond a band of 3): the distances the volume holds
  int between = 0, bad = 0;
  forEachVoxelReadBack(*v, *back, [&](std::int64_t x, std::int64_t y, std::int64_t z, float read) {
    const double d = analytic(double(x), double(y), double(z));
    if (std::fabs(d) < 3.5 || std::fabs(d) > 7.0) return;
    ++between;
    bad += std::fabs(read - v->sdf(x, y, z)) > 1e-4 * std::fabs(d);
  });
  EXPECT_GT(between, 1000);
  EXPECT_EQ(bad, 0);

  lvdif::VolumeOptions o = v->options();
  o.bandWidth = std::numeric_limits<float>::infinity();
  auto unlimited = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*unlimited, analytic);
  LVDIFFiles::SaveVolume(unlimited, path, {});
  ASSERT_EQ(log->Warnings.size(), 1u);
  EXPECT_NE(log->Warnings[0].find("the volume's band (unlimited) is written as a narrow band of 3 voxels"),
    std::string::npos) << log->Warnings[0];
  EXPECT_EQ(LVDIFFiles::LoadVolume(path)->bandWidth(), 3.0f);
  vtkOutputWindow::SetInstance(previous);
  previous->Delete();
  std::remove(path.c_str());
}
#endif

namespace
{
using filetest::slurp;

/// Cancels as soon as a save has begun writing: the target's content changed,
/// or a temporary file beside it ("<name>.tmp-...") appeared.
struct CancelOnceWriting : lvdif::Interrupter
{
  std::string path, old;
  bool cancelled = false, sawTemporary = false;
  void progress(double) override
  {
    if (this->cancelled)
      return;
    const std::string dir = this->path.substr(0, this->path.find_last_of('/'));
    const std::string prefix = this->path.substr(this->path.find_last_of('/') + 1) + ".tmp-";
    if (DIR* d = ::opendir(dir.c_str()))
    {
      while (const dirent* e = ::readdir(d))
        this->sawTemporary = this->sawTemporary || std::string(e->d_name).rfind(prefix, 0) == 0;
      ::closedir(d);
    }
    this->cancelled = this->sawTemporary || slurp(this->path) != this->old;
  }
  bool wasInterrupted() const override { return this->cancelled; }
};
}

// A save that fails while VTK's XML image writer writes (here: cancelled once
// writing has begun) leaves the old .vti as it was: the registry gives that
// writer a temporary file and renames it over the old one only when complete
// (before, the writer truncated the old file first). A save to a missing
// folder is refused before any work, in the CLI's words.
TEST(LVDIFFiles, AFailedVtiSaveKeepsTheOldFile)
{
  const auto v = sphere();
  const std::string path = temp("old_image.vti");
  std::ofstream(path) << "an old image";
  CancelOnceWriting cancel;
  cancel.path = path;
  cancel.old = "an old image";
  EXPECT_THROW(LVDIFFiles::SaveVolume(v, path, {}, cancel), lvdif::Error);
  EXPECT_TRUE(cancel.cancelled); // the writer had begun
  EXPECT_TRUE(slurp(path) == "an old image"); // not the (long) new content in the failure message
  std::remove(path.c_str());
  try
  {
    LVDIFFiles::SaveVolume(v, "/nonexistent_lvdif_folder/v.vti");
    ADD_FAILURE() << "saved into a missing folder";
  }
  catch (const lvdif::Error& e)
  {
    EXPECT_EQ(std::string(e.what()),
      "cannot write '/nonexistent_lvdif_folder/v.vti': the folder '/nonexistent_lvdif_folder' does not exist");
  }
}

TEST(LVDIFFiles, UnknownExtensionsAreOneClearError)
{
  try
  {
    LVDIFFiles::LoadVolume(temp("x.raw"));
    FAIL() << "no error";
  }
  catch (const lvdif::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find(".lvdv"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LVDIFFiles::LoadVolume(temp("missing.lvdv")), lvdif::Error);
  EXPECT_THROW(LVDIFFiles::SaveMesh(vtkPolyData::New(), temp("x.off")), lvdif::Error); // .off is read-only
  // an empty name is named as such (it was "cannot write '': volumes are .lvdv, ... files")
  for (const bool saving : { false, true })
  {
    try
    {
      LVDIFFiles::RequireFormat("", LVDIFFiles::Kind::Volume, saving);
      ADD_FAILURE() << "no error";
    }
    catch (const lvdif::Error& e)
    {
      EXPECT_EQ(std::string(e.what()), std::string("no volume file name to ") + (saving ? "write" : "read") + " (an empty argument)");
    }
  }
  EXPECT_EQ(LVDIFFiles::Extension("/a.b/c.LVDV"), "lvdv");
  EXPECT_EQ(LVDIFFiles::Extension("/a.b/c"), "");
  EXPECT_NE(LVDIFFiles::DialogFilter(LVDIFFiles::Kind::Volume, true).find("(*.lvdv)"), std::string::npos);
}

// A .vti whose image is rotated (VTK writes its direction matrix as the
// Direction attribute) is refused naming the matrix: a dictionary volume is
// axis-aligned, and before the volume came back unrotated without a word.
TEST(LVDIFFiles, ARotatedVtiIsRefused)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 8);
  image->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1); // 90 degrees about z
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(8 * 8 * 8);
  sdf->Fill(1.0);
  image->GetPointData()->SetScalars(sdf);
  const std::string path = temp("rotated.vti");
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  ASSERT_EQ(writer->Write(), 1);
  try
  {
    LVDIFFiles::LoadVolume(path);
    FAIL() << "a rotated image was read as an axis-aligned volume";
  }
  catch (const lvdif::Error& e)
  {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find("'" + path + "'"), std::string::npos) << what;
    EXPECT_NE(what.find("direction matrix is not the identity (0 -1 0 1 0 0 0 0 1)"), std::string::npos) << what;
  }
  // the identity reads as before
  image->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  ASSERT_EQ(writer->Write(), 1);
  EXPECT_EQ(LVDIFFiles::LoadVolume(path)->dims()[0], 8);
  std::remove(path.c_str());
}

TEST(LVDIFFiles, EveryMeshFormatRoundTrips)
{
  vtkNew<vtkSphereSource> s;
  s->SetThetaResolution(16);
  s->SetPhiResolution(12);
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(s->GetOutputPort());
  tri->Update();
  for (const auto& f : LVDIFFiles::Formats())
  {
    if (f.kind != LVDIFFiles::Kind::Mesh || f.writerClass.empty()) continue;
    const std::string path = temp("sphere." + f.extension);
    LVDIFFiles::SaveMesh(tri->GetOutput(), path);
    if (!f.readerClass.empty())
    {
      vtkSmartPointer<vtkPolyData> back = LVDIFFiles::LoadMesh(path);
      EXPECT_EQ(back->GetNumberOfPolys(), tri->GetOutput()->GetNumberOfPolys()) << f.extension;
    }
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    EXPECT_GT(static_cast<long>(in.tellg()), 100) << f.extension;
    std::remove(path.c_str());
  }
}

// A .vti of 200,000 nested elements: VTK's XML parser builds their tree and frees it recursively,
// a segmentation fault (as did the header check's walk of a compressed file's elements). Now the
// nesting is read first and refused past 64; comments, a CDATA section, a '>' in an attribute and
// the raw bytes after AppendedData are no elements. Oracle: the nesting as written.
TEST(LVDIFFiles, ADeeplyNestedVtiIsAClearError)
{
  const std::string deep = temp("deep.vti");
  for (const char* compressor : { "", " compressor=\"vtkZLibDataCompressor\"" })
  {
    {
      std::ofstream f(deep, std::ios::binary);
      f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\""
        << compressor << ">\n<ImageData WholeExtent=\"0 3 0 3 0 3\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
        << "<Piece Extent=\"0 3 0 3 0 3\">\n";
      for (int i = 0; i < 200000; ++i) f << "<a>";
      for (int i = 0; i < 200000; ++i) f << "</a>";
      f << "\n</Piece>\n</ImageData>\n</VTKFile>\n";
    }
    try
    {
      LVDIFFiles::LoadVolume(deep);
      ADD_FAILURE() << "read";
    }
    catch (const lvdif::Error& e)
    {
      EXPECT_EQ(std::string(e.what()),
        "cannot read '" + deep + "': XML elements nested more than 64 deep (a VTK file nests a few)");
    }
    lvdif::VolumeOptions grid;
    EXPECT_FALSE(LVDIFFiles::ReadGrid(deep, grid));
  }
  // 64 deep, with what is no element, reads as far as VTK's reader (its words: no image data)
  {
    std::ofstream f(deep, std::ios::binary);
    f << "<?xml version=\"1.0\"?>\n<!-- <a><a><a> --><VTKFile type=\"ImageData\" version=\"1.0\" x=\"<b>\">"
      << "<![CDATA[<c><c>]]><ImageData WholeExtent=\"0 3 0 3 0 3\" Origin=\"0 0 0\" Spacing=\"1 1 1\"><Piece Extent=\"0 3 0 3 0 3\">";
    for (int i = 3; i < 64; ++i) f << "<a>";
    f << "<b/>";
    for (int i = 3; i < 64; ++i) f << "</a>";
    f << "</Piece></ImageData><AppendedData encoding=\"raw\">_" << std::string(300, '<') << "\n</AppendedData></VTKFile>\n";
  }
  try
  {
    LVDIFFiles::LoadVolume(deep);
  }
  catch (const lvdif::Error& e)
  {
    EXPECT_EQ(std::string(e.what()).find("nested"), std::string::npos) << e.what();
  }
  std::remove(deep.c_str());
}

// A mesh save on a full disk (here: a file size limit, RLIMIT_FSIZE) keeps the old file byte for byte and fails. vtkPLYWriter and
// vtkOBJWriter answered 1 over a cut file, which the CLI's save renamed over the
// old one (status 0), and the editor's export wrote in place. Oracle: the old
// file's bytes, and the lvdif::Error.
TEST(LVDIFFiles, AMeshSaveOnAFullDiskKeepsTheOldFile)
{
  vtkNew<vtkSphereSource> s;
  s->SetThetaResolution(120);
  s->SetPhiResolution(120);
  s->Update(); // some 14,000 points: every format's file is far past the limit
  for (const auto& f : LVDIFFiles::Formats())
  {
    if (f.kind != LVDIFFiles::Kind::Mesh || f.writerClass.empty()) continue;
    const std::string path = temp("full." + f.extension);
    {
      std::ofstream old(path, std::ios::binary);
      old << "the old file";
    }
    // a write past the limit fails with EFBIG, as on a full disk (SIGXFSZ ignored); in this
    // process (a forked child's thread pools spun for minutes), lifted again at once
    auto* oldHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit old{};
    ::getrlimit(RLIMIT_FSIZE, &old);
    const rlimit limit{ 8192, old.rlim_max };
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string why = "(saved)";
    try
    {
      LVDIFFiles::SaveMesh(s->GetOutput(), path);
    }
    catch (const lvdif::Error& e)
    {
      why = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, oldHandler);
    EXPECT_EQ(filetest::slurp(path), "the old file") << f.extension;
    // one line naming the file given (VTK's XML writer's failure was the executive's dump of a
    // dozen lines, naming the temporary file)
    EXPECT_EQ(why.rfind("cannot write '" + path + "': ", 0), 0u) << f.extension << ": " << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << f.extension << ": " << why;
    std::remove(path.c_str());
  }
}

TEST(LVDIFFiles, ParaViewHintsListTheRegistrysExtensions)
{
  // class -> extensions named by the plugin's ReaderFactory / WriterFactory hints
  std::map<std::string, std::set<std::string>> readers, writers;
  DIR* dir = opendir(LVDIF_PLUGIN_XML_DIR);
  ASSERT_NE(dir, nullptr);
  const std::regex proxy("class=\"(vtk\\w+)\"");
  const std::regex factory("<(Reader|Writer)Factory\\s+extensions=\"([^\"]*)\"");
  while (dirent* e = readdir(dir))
  {
    const std::string name = e->d_name;
    if (name.size() < 4 || name.substr(name.size() - 4) != ".xml") continue;
    std::ifstream in(std::string(LVDIF_PLUGIN_XML_DIR) + "/" + name);
    std::stringstream text;
    text << in.rdbuf();
    const std::string xml = text.str();
    std::smatch pm, fm;
    if (!std::regex_search(xml, pm, proxy)) continue;
    const std::string cls = pm[1];
    for (auto it = std::sregex_iterator(xml.begin(), xml.end(), factory); it != std::sregex_iterator(); ++it)
    {
      std::istringstream exts((*it)[2]);
      std::string ext;
      while (exts >> ext) ((*it)[1] == "Reader" ? readers : writers)[cls].insert(ext);
    }
  }
  closedir(dir);
  ASSERT_FALSE(readers.empty());
  // ParaView-only readers: vtkXMLSparseVolumeReader reads the .vtpd that VTK's writer makes of a
  // sparse volume back as its partitions, not as a volume (uniform chunks are not in the file), so
  // the front ends' registry, which loads volumes and meshes, has no .vtpd
  const std::set<std::string> paraviewOnly = { "vtkXMLSparseVolumeReader" };
  for (const std::string& cls : paraviewOnly)
  {
    EXPECT_EQ(readers[cls], std::set<std::string>{ "vtpd" }) << cls;
    EXPECT_EQ(LVDIFFiles::Find("x.vtpd", LVDIFFiles::Kind::Volume), nullptr);
    readers.erase(cls);
  }
  for (const auto* table : { &readers, &writers })
  {
    const bool reading = table == &readers;
    for (const auto& kv : *table)
    {
      std::set<std::string> registry;
      for (const auto& f : LVDIFFiles::Formats())
        if ((reading ? f.readerClass : f.writerClass) == kv.first) registry.insert(f.extension);
      EXPECT_EQ(kv.second, registry) << kv.first << (reading ? " reader" : " writer")
                                     << " hints differ from the registry";
    }
  }
}

namespace
{
/// An 8 x 8 x 8 image (sdf = x - 3.5, spacing 0.5 1 2) written by VTK's
/// writer as `setUp` sets it up: the file's text, or "" if the write failed.
template <typename SetUp>
std::string writeSmallVtiWith(const std::string& path, SetUp setUp)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 8);
  image->SetSpacing(0.5, 1, 2);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(8 * 8 * 8);
  for (vtkIdType i = 0; i < 8 * 8 * 8; ++i) sdf->SetValue(i, float(i % 8) - 3.5f);
  image->GetPointData()->SetScalars(sdf);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(image);
  setUp(writer.Get());
  if (writer->Write() != 1) return "";
  return slurp(path);
}

/// The small image as ASCII in `pieces` pieces.
std::string writeSmallVti(const std::string& path, int pieces)
{
  return writeSmallVtiWith(path, [pieces](vtkXMLImageDataWriter* w) {
    w->SetDataModeToAscii();
    w->SetNumberOfPieces(pieces);
  });
}

/// The text with `from` replaced by `to` (which must occur once).
std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::string loadError(const std::string& path)
{
  try
  {
    LVDIFFiles::LoadVolume(path);
  }
  catch (const lvdif::Error& e)
  {
    return e.what();
  }
  return "(read without an error)";
}

/// Writes each text to temp(name) in turn: LoadVolume's error is "cannot read 'path': " + the expected words.
void expectLoadErrors(const std::string& name, const std::vector<std::pair<std::string, std::string>>& cases)
{
  const std::string path = temp(name);
  for (const auto& c : cases)
  {
    std::ofstream(path, std::ios::binary) << c.first;
    EXPECT_EQ(loadError(path), "cannot read '" + path + "': " + c.second) << c.first;
  }
  std::remove(path.c_str());
}
} // namespace

// A .vti whose WholeExtent is larger than its one piece's Extent was read: the
// points outside the piece were whatever the allocated memory held. Now one
// error names both extents; VTK's own split into pieces still reads, and so
// does a .vti as VTK writes it (oracle: the values written, sdf = x - 3.5).
TEST(LVDIFFiles, AVtiWhosePiecesDoNotFillItsExtentIsRefused)
{
  const std::string path = temp("extent.vti");
  for (const int pieces : { 1, 3 })
  {
    ASSERT_FALSE(writeSmallVti(path, pieces).empty());
    const auto v = LVDIFFiles::LoadVolume(path);
    ASSERT_EQ(v->dims(), (lvdif::Index3{ 8, 8, 8 })) << pieces;
    double worst = 0;
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          worst = std::max(worst, std::fabs(v->decode(v->get(x, y, z).sdf) - (x - 3.5)));
    EXPECT_LT(worst, 0.01) << pieces << " pieces";
  }
  const std::string vti = writeSmallVti(path, 1);
  std::ofstream(path) << replaced(vti, "WholeExtent=\"0 7 0 7 0 7\"", "WholeExtent=\"0 7 0 7 0 8\"");
  EXPECT_EQ(loadError(path), "cannot read '" + path + "': the whole extent 0 7 0 7 0 8 is larger than its piece's " +
      "extent 0 7 0 7 0 7: the points outside it would be made up");
  std::remove(path.c_str());
}

// An empty .vti (a save that never wrote, a truncated copy) was reported in VTK's
// words: "Error parsing input file.  ReadXMLInformation aborting.". Now in ours,
// as every reader names an empty file.
TEST(LVDIFFiles, AnEmptyVtiIsNamedAsEmpty)
{
  expectLoadErrors("empty.vti", { { "", "the file is empty: no VTK image in it" },
                                  { "\n \r\n\t\n", "the file is empty (blank): no VTK image in it" } });
}

// A .vti that is not XML, or one cut off inside its XML (a copy that stopped
// early), was VTK's "Error parsing input file". Now one message in our words.
TEST(LVDIFFiles, ANonXmlOrTruncatedVtiIsNamedAsSuch)
{
  const std::string path = temp("cut.vti");
  const std::string vti = writeSmallVti(path, 1);
  ASSERT_GT(vti.size(), 200u);
  const std::string said = "not a VTK XML image (truncated or another format)";
  expectLoadErrors("cut.vti", { { "This is not a VTK XML file\n", said }, { vti.substr(0, 120), said } });
}

// An error in a .lvdvp index named the index itself ("index 'x.lvdvp', line 2:
// ..."), so the readers' one guard, which adds "cannot read 'x':" unless the
// message names the file, left the prefix every other reader's error has. Now
// the index's errors are "line N: what" behind that prefix, and a byte order
// mark before the index is skipped, as in every text format.
TEST(LVDIFFiles, AnLvdvpErrorHasTheReadersPrefix)
{
  expectLoadErrors("bad.lvdvp", { { "LVDIF-PVOLUME 1\nbogus 1\n", "line 2: unknown key 'bogus'" }, { "", "empty file" },
                                  { "\xEF\xBB\xBFLVDIF-PVOLUME 1\nbogus 1\n", "line 2: unknown key 'bogus'" } });
}

// Spacing="nan 1 1" (or inf) in a .vti was read as spacing 1 (VTK's reader takes
// what it cannot parse for its default), 0 and negative spacings were read
// (a zero spacing until the conversion refused it, after reading the data).
// Now each is refused from the header by the volumes' one geometry rule.
TEST(LVDIFFiles, AVtiWithABadSpacingIsRefused)
{
  const std::string path = temp("spacing.vti");
  const std::string vti = writeSmallVti(path, 1);
  ASSERT_FALSE(vti.empty());
  for (const std::string& bad : { "nan 1 2", "inf 1 2", "0 1 2", "-0.5 1 2" })
  {
    std::ofstream(path) << replaced(vti, "Spacing=\"0.5 1 2\"", "Spacing=\"" + bad + "\"");
    const std::string error = loadError(path);
    EXPECT_NE(error.find("cannot read '" + path + "': volume origin 0 and spacing "), std::string::npos) << error;
    EXPECT_NE(error.find(" on axis x must be finite, spacing >= 1e-30"), std::string::npos) << error;
  }
  std::ofstream(path) << replaced(vti, "Spacing=\"0.5 1 2\"", "Spacing=\"0.5 1\"");
  EXPECT_EQ(loadError(path), "cannot read '" + path + "': Spacing=\"0.5 1\" is not 3 numbers");
  // a hexadecimal number: VTK's reader took "0x1p1" for 0 and then its default 1
  std::ofstream(path) << replaced(vti, "Spacing=\"0.5 1 2\"", "Spacing=\"0x1p1 1 2\"");
  EXPECT_EQ(loadError(path), "cannot read '" + path + "': Spacing=\"0x1p1 1 2\" is not 3 numbers");
  std::ofstream(path) << replaced(vti, "Origin=\"0 0 0\"", "Origin=\"0 nan 0\"");
  EXPECT_NE(loadError(path).find("volume origin nan"), std::string::npos) << loadError(path);
  std::remove(path.c_str());
}

namespace
{
/// The small image of writeSmallVti, compressed (zlib), in a data mode.
std::string writeCompressedVti(const std::string& path, int mode, bool encoded, bool header64)
{
  return writeSmallVtiWith(path, [&](vtkXMLImageDataWriter* w) {
    w->SetCompressorTypeToZLib();
    w->SetDataMode(mode);
    w->SetEncodeAppendedData(encoded);
    if (header64) w->SetHeaderTypeToUInt64();
  });
}
} // namespace

// VTK's reader allocates by a compressed array's header (a word per block, a
// buffer of a block): a .vti declaring 2^31 - 1 blocks ended in
// "lvdif convert: std::bad_alloc" (or took gigabytes). Now the header's counts
// are checked against the file and the array before: one error naming the
// array. The writer's own compressed files in every data mode still read
// (oracle: the values written).
TEST(LVDIFFiles, AVtiWithForgedCompressionHeadersIsRefusedBeforeAllocating)
{
  const std::string path = temp("compressed.vti");
  for (const int mode : { vtkXMLWriter::Appended, vtkXMLWriter::Binary })
    for (const bool encoded : { true, false })
      for (const bool header64 : { false, true })
      {
        ASSERT_FALSE(writeCompressedVti(path, mode, encoded, header64).empty());
        const auto v = LVDIFFiles::LoadVolume(path);
        EXPECT_LT(std::fabs(v->decode(v->get(7, 3, 2).sdf) - 3.5), 0.01) << mode << encoded << header64;
      }
  // appended, base64: the header of 'sdf' is the first 24 characters after '_' (4 words of 4 bytes)
  const std::string vti = writeCompressedVti(path, vtkXMLWriter::Appended, true, false);
  const std::size_t at = vti.find('_', vti.find("<AppendedData")) + 1;
  ASSERT_NE(at, std::string::npos + 1);
  unsigned char words[18] = {};
  ASSERT_EQ(vtkBase64Utilities::DecodeSafely(
              reinterpret_cast<const unsigned char*>(vti.data() + at), 24, words, sizeof(words)),
    16u);
  auto forged = [&](int word, std::uint32_t value) {
    unsigned char w[16];
    std::memcpy(w, words, 16);
    for (int b = 0; b < 4; ++b) w[4 * word + b] = static_cast<unsigned char>(value >> (8 * b));
    unsigned char text[32];
    const unsigned long n = vtkBase64Utilities::Encode(w, 16, text);
    std::string out = vti;
    out.replace(at, 24, reinterpret_cast<const char*>(text), n);
    return out;
  };
  std::ofstream(path) << forged(0, 0x7fffffffu);
  EXPECT_EQ(loadError(path), "cannot read '" + path + "': the DataArray 'sdf' declares 2147483647 compressed blocks, " +
      "more than the file's " + std::to_string(vti.size()) + " bytes can list");
  std::ofstream(path) << forged(1, 0xfffffff0u);
  EXPECT_EQ(loadError(path), "cannot read '" + path + "': the DataArray 'sdf' declares blocks of 4294967280 bytes, " +
      "more than its 2048 bytes of values");
  std::ofstream(path) << forged(3, 0xfffffff0u);
  EXPECT_EQ(loadError(path), "cannot read '" + path + "': the DataArray 'sdf' declares a compressed block of " +
      "4294967280 bytes, more than the file's " + std::to_string(vti.size()));
  std::remove(path.c_str());
}
