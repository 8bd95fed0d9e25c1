// vtkLegacyBvWriter / vtkLegacyBvReader: a hand-made .bv (keys and indices
// written byte by byte from the spec's table, original-code-spec.md 3.2)
// decodes to the values and colours the table gives, with X and Z exchanged
// or not; image -> .bv -> image matches the analytic SDF it was made from and
// the palette colours exactly, and a second export is byte-identical to the
// first (exact at the key level); bad sizes and names give one error each.
#include "vtkDictionaryVolumeReader.h"
#include "vtkLegacyBvReader.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkSparseVolumeToImage.h"
#include "vtkLegacyBvWriter.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/VolumeFile.h"

#include "vtkCommand.h"
#include "vtkCompositeDataSet.h"
#include "vtkContourFilter.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <optional>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace
{
/// The reader's sparse output made dense (the explicit conversion).
vtkSmartPointer<vtkImageData> dense(vtkAlgorithm* reader)
{
  vtkNew<vtkSparseVolumeToImage> d;
  d->SetInputConnection(reader->GetOutputPort());
  d->Update();
  return d->GetOutput();
}
}

namespace
{
std::string tempFile(const std::string& name)
{
  return ::testing::TempDir() + "SDF_" + name + "_lvdifbv" + std::to_string(::getpid()) + ".bv";
}

std::vector<char> slurp(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

struct ErrorCatcher : vtkCommand
{
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Text += static_cast<const char*>(data);
  }
  int Count = 0;
  std::string Text;
};

/// Writes N^3 records; record(x, y, z) gives {their key, colour index}.
template <typename F>
void writeBv(const std::string& path, int n, F record)
{
  std::ofstream f(path, std::ios::binary);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
      {
        const std::pair<std::uint16_t, std::uint16_t> r = record(x, y, z);
        const unsigned char b[4] = { static_cast<unsigned char>(r.first & 0xff),
          static_cast<unsigned char>(r.first >> 8), static_cast<unsigned char>(r.second & 0xff),
          static_cast<unsigned char>(r.second >> 8) };
        f.write(reinterpret_cast<const char*>(b), 4);
      }
}

const int N = 5;
// Their keys (spec 3.2): 2000 = +1.0, 2001 = -1.0, 8024 = +(4 + 0.1*11) = +5.1,
// 8025 = -5.1, 700 = +0.35. Inside-positive: ours is the negation.
std::pair<std::uint16_t, std::uint16_t> handRecord(int x, int y, int z)
{
  if (x == 1 && y == 2 && z == 3)
    return { 2000, 3 };
  if (x == 3 && y == 0 && z == 4)
    return { 8024, 10 };
  if (x == 0 && y == 4 && z == 1)
    return { 700, 1 };
  if (x == 4 && y == 4 && z == 4)
    return { 8025, 0 };
  return { 2001, 0 };
}
double handValueOurs(int x, int y, int z)
{
  if (x == 1 && y == 2 && z == 3)
    return -1.0;
  if (x == 3 && y == 0 && z == 4)
    return -5.1;
  if (x == 0 && y == 4 && z == 1)
    return -0.35;
  if (x == 4 && y == 4 && z == 4)
    return 5.1;
  return 1.0;
}
int handIndex(int x, int y, int z)
{
  return handRecord(x, y, z).second;
}
// The spec's Mouse palette (3.5) as floats; 8-bit colours within one step.
const double MousePalette[11][3] = { { 0, .580, .882 }, { .749, .875, .962 }, { .980, .718, .122 },
  { .627, .796, .231 }, { .925, .322, .596 }, { .882, .973, .859 }, { .067, .655, .592 }, { .851, .322, .149 },
  { .780, .388, .761 }, { 1, .871, .965 }, { .392, .392, .392 } };
} // namespace

TEST(LegacyBvIO, HandMadeFileDecodesToTheSpecTable)
{
  const std::string path = tempFile("5");
  writeBv(path, N, handRecord);
  for (bool swap : { true, false })
  {
    vtkNew<vtkLegacyBvReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetSwapXZ(swap);
    reader->Update();
    EXPECT_EQ(reader->GetEdge(), N);
    vtkSmartPointer<vtkImageData> out = dense(reader);
    int dims[3];
    out->GetDimensions(dims);
    ASSERT_EQ(dims[0], N);
    ASSERT_EQ(dims[2], N);
    auto* sdf = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("sdf"));
    auto* rgba = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("rgba"));
    ASSERT_NE(sdf, nullptr);
    ASSERT_NE(rgba, nullptr);
    ASSERT_EQ(rgba->GetNumberOfComponents(), 4);
    for (int z = 0; z < N; ++z)
      for (int y = 0; y < N; ++y)
        for (int x = 0; x < N; ++x)
        {
          // file position (fx, fy, fz) lands on ours (fz, fy, fx) when swapped
          const int id = swap ? (z + N * (y + N * x)) : (x + N * (y + N * z));
          const double expected = handValueOurs(x, y, z);
          const double tol = std::fabs(expected) > 4 ? 0.051 : 0.0011;
          EXPECT_NEAR(sdf->GetValue(id), expected, tol) << x << " " << y << " " << z << " swap " << swap;
          const int idx = handIndex(x, y, z);
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(rgba->GetTypedComponent(id, c), 255.0 * MousePalette[idx][c], 1.0)
              << x << " " << y << " " << z << " channel " << c;
        }
  }
  std::remove(path.c_str());
}

TEST(LegacyBvIO, ImageRoundTripIsExactAtTheKeyLevel)
{
  const int n = 20;
  vtkNew<vtkImageData> img;
  img->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(n * n * n);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(n * n * n);
  const std::vector<lvdif::Rgba> palette = lvdif::legacy_bv::defaultPalette();
  const lvdif::Rgba extra{ 1, 2, 3, 255 }; // not in the palette: gets the next index
  auto analytic = [](int i, int j, int k) {
    const double dx = i - 9.3, dy = j - 8.6, dz = k - 10.2;
    return std::sqrt(dx * dx + dy * dy + dz * dz) - 6.5;
  };
  for (int k = 0, id = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++id)
      {
        sdf->SetValue(id, static_cast<float>(analytic(i, j, k)));
        const lvdif::Rgba c = (i == 3 && j == 4) ? extra : palette[(i + 2 * j + 3 * k) % palette.size()];
        const unsigned char t[4] = { c.r, c.g, c.b, c.a };
        rgba->SetTypedTuple(id, t);
      }
  img->GetPointData()->AddArray(sdf);
  img->GetPointData()->AddArray(rgba);

  const std::string first = tempFile("20"), second = tempFile("20b");
  vtkNew<vtkLegacyBvWriter> writer;
  writer->SetInputData(img);
  writer->SetFileName(first.c_str());
  ASSERT_EQ(writer->Write(), 1);
  ASSERT_EQ(slurp(first).size(), std::size_t(4) * n * n * n);

  vtkNew<vtkLegacyBvReader> reader;
  reader->SetFileName(first.c_str());
  reader->Update();
  vtkSmartPointer<vtkImageData> out = dense(reader);
  auto* osdf = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("sdf"));
  auto* orgba = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("rgba"));
  ASSERT_NE(osdf, nullptr);
  ASSERT_NE(orgba, nullptr);
  ASSERT_EQ(osdf->GetNumberOfTuples(), n * n * n);
  std::optional<lvdif::Rgba> extraBack;
  for (int id = 0; id < n * n * n; ++id)
  {
    const int i = id % n, j = (id / n) % n, k = id / (n * n);
    const double a = std::max(-8.0, std::min(8.0, analytic(i, j, k)));
    // our dictionary (0.001 / 0.1 steps) then theirs (same steps): at most two half steps
    const double tol = std::fabs(a) < 3.99 ? 0.0011 : 0.101;
    EXPECT_NEAR(osdf->GetValue(id), a, tol) << i << " " << j << " " << k;
    if (i == 3 && j == 4)
    {
      // index 11 (first colour outside the palette): the file stores no
      // palette, so it comes back as the reader's colour for index 11, one
      // colour for all such voxels and none of the palette's
      unsigned char t[4];
      orgba->GetTypedTuple(id, t);
      const lvdif::Rgba back{ t[0], t[1], t[2], t[3] };
      if (!extraBack.has_value())
        extraBack = back;
      EXPECT_EQ(back, *extraBack) << id;
      for (const lvdif::Rgba& p : palette)
        EXPECT_NE(back, p) << id;
      continue;
    }
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(orgba->GetTypedComponent(id, c), rgba->GetTypedComponent(id, c)) << id;
  }
  ASSERT_TRUE(extraBack.has_value());
  // the file's X/Z exchange: our (i, j, k) is their (k, j, i); an inside voxel
  // (ours -6.5 + ...) is positive there
  {
    const std::vector<char> bytes = slurp(first);
    const int i = 9, j = 9, k = 10; // inside, distance ~ -6.4
    const std::size_t rec = 4 * static_cast<std::size_t>(k + n * (j + n * i));
    const unsigned key = static_cast<unsigned char>(bytes[rec]) | (static_cast<unsigned char>(bytes[rec + 1]) << 8);
    EXPECT_EQ(key % 2, 0u) << "inside must be positive (even key) in the original's convention";
    EXPECT_GT(key, 8003u) << "|value| > 4 lives in group B";
  }

  // read -> write again: the same bytes
  vtkNew<vtkLegacyBvWriter> writer2;
  writer2->SetInputConnection(reader->GetOutputPort());
  writer2->SetFileName(second.c_str());
  ASSERT_EQ(writer2->Write(), 1);
  EXPECT_TRUE(slurp(first) == slurp(second));

  // DistanceScale: read with scale 2 doubles our distances
  vtkNew<vtkLegacyBvReader> scaled;
  scaled->SetFileName(first.c_str());
  scaled->SetDistanceScale(2.0);
  scaled->SetBandWidth(32.0);
  scaled->Update();
  vtkSmartPointer<vtkImageData> scaledImage = dense(scaled);
  auto* ssdf = vtkFloatArray::SafeDownCast(scaledImage->GetPointData()->GetArray("sdf"));
  ASSERT_NE(ssdf, nullptr);
  for (int id = 0; id < n * n * n; id += 7)
  {
    // doubled values past 4 land in our 0.1-step group
    const double twice = 2.0 * osdf->GetValue(id);
    EXPECT_NEAR(ssdf->GetValue(id), twice, std::fabs(twice) > 3.99 ? 0.051 : 0.003) << id;
  }
  std::remove(first.c_str());
  std::remove(second.c_str());
}

TEST(LegacyBvIO, BadSizeAndNameAreErrors)
{
  vtkNew<ErrorCatcher> catcher;
  // 27 records + 1 byte: not 4 N^3
  const std::string odd = ::testing::TempDir() + "lvdif_odd_" + std::to_string(::getpid()) + ".bv";
  {
    std::ofstream f(odd, std::ios::binary);
    const std::vector<char> zeros(4 * 27 + 1, 0);
    f.write(zeros.data(), static_cast<std::streamsize>(zeros.size()));
  }
  EXPECT_FALSE(vtkLegacyBvReader::CanReadFile(odd.c_str()));
  vtkNew<vtkLegacyBvReader> reader;
  reader->AddObserver(vtkCommand::ErrorEvent, catcher);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
  reader->SetFileName(odd.c_str());
  reader->Update();
  EXPECT_GE(catcher->Count, 1);
  EXPECT_NE(catcher->Text.find("109 bytes is not 4*N^3"), std::string::npos) << catcher->Text;
  EXPECT_FALSE(vtkSparseDictionaryVolume::SafeDownCast(reader->GetOutputDataObject(0))->HasVolume());

  // a 3^3 file named SDF_4_...
  const std::string named = tempFile("4");
  writeBv(named, 3, [](int, int, int) { return std::pair<std::uint16_t, std::uint16_t>(2001, 0); });
  EXPECT_FALSE(vtkLegacyBvReader::CanReadFile(named.c_str()));
  catcher->Count = 0;
  catcher->Text.clear();
  reader->SetFileName(named.c_str());
  reader->Update();
  EXPECT_GE(catcher->Count, 1);
  EXPECT_NE(catcher->Text.find("file name says N = 4 but its size gives N = 3"), std::string::npos) << catcher->Text;

  // writer: a non-cubic image, then a cube under a disagreeing name
  vtkNew<vtkImageData> box;
  box->SetDimensions(4, 4, 5);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(80);
  sdf->Fill(1.0);
  box->GetPointData()->AddArray(sdf);
  vtkNew<vtkLegacyBvWriter> writer;
  writer->AddObserver(vtkCommand::ErrorEvent, catcher);
  writer->SetInputData(box);
  writer->SetFileName(tempFile("x").c_str());
  catcher->Count = 0;
  catcher->Text.clear();
  writer->Write();
  EXPECT_GE(catcher->Count, 1);
  EXPECT_NE(catcher->Text.find("cubic"), std::string::npos) << catcher->Text;

  vtkNew<vtkImageData> cube;
  cube->SetDimensions(4, 4, 4);
  vtkNew<vtkFloatArray> csdf;
  csdf->SetName("sdf");
  csdf->SetNumberOfTuples(64);
  csdf->Fill(-1.0);
  cube->GetPointData()->AddArray(csdf);
  writer->SetInputData(cube);
  const std::string wrong = tempFile("5");
  writer->SetFileName(wrong.c_str());
  catcher->Count = 0;
  catcher->Text.clear();
  writer->Write();
  EXPECT_GE(catcher->Count, 1);
  EXPECT_NE(catcher->Text.find("N = 5"), std::string::npos) << catcher->Text;
  EXPECT_FALSE(std::ifstream(wrong).good()) << "nothing written under a wrong name";
  std::remove(odd.c_str());
  std::remove(named.c_str());
}

// The reader and the import (the CLI's `lvdif convert`) say the same thing about
// a file that is not a .bv, because they use Core's one rule: oracle, the text of
// lvdif::loadLegacyBv's error for the same file. The reader had its own copy of
// the size rule and its own words ("cannot open the file" for a missing file,
// where the import names the path and the system's reason).
TEST(LegacyBvIO, ReaderSaysWhatTheImportSays)
{
  const std::string dir = ::testing::TempDir() + "lvdif_bvrule_" + std::to_string(::getpid());
  ASSERT_EQ(::mkdir(dir.c_str(), 0755), 0);
  struct Case
  {
    std::string name;
    int bytes; // -1: not made
  };
  const std::vector<Case> cases = { { "missing.bv", -1 }, { "empty.bv", 0 }, { "odd.bv", 4 * 27 + 1 },
    { "SDF_4_three.bv", 4 * 27 }, { "short.bv", 4 * 26 } };
  for (const Case& c : cases)
  {
    const std::string path = dir + "/" + c.name;
    if (c.bytes >= 0)
    {
      std::ofstream f(path, std::ios::binary);
      const std::vector<char> zeros(static_cast<std::size_t>(c.bytes), 0);
      f.write(zeros.data(), static_cast<std::streamsize>(zeros.size()));
    }
    std::string oracle;
    try
    {
      lvdif::loadLegacyBv(path);
    }
    catch (const lvdif::Error& e)
    {
      oracle = e.what();
    }
    ASSERT_FALSE(oracle.empty()) << c.name << ": the import took it";
    vtkNew<ErrorCatcher> catcher;
    vtkNew<vtkLegacyBvReader> reader;
    reader->AddObserver(vtkCommand::ErrorEvent, catcher);
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_EQ(catcher->Count, 1) << c.name << ": " << catcher->Text;
    // the reader's line: "cannot read '<path>': " unless Core's words already name the path
    const std::string expected =
      oracle.find("'" + path + "'") != std::string::npos ? oracle : "cannot read '" + path + "': " + oracle;
    EXPECT_NE(catcher->Text.find(expected), std::string::npos) << c.name << ": reader said\n  " << catcher->Text
                                                                << "\nthe import says\n  " << oracle;
    EXPECT_FALSE(vtkLegacyBvReader::CanReadFile(path.c_str())) << c.name;
    std::remove(path.c_str());
  }
  ::rmdir(dir.c_str());
}

// A volume the format cannot hold (not a cube, or not the edge the file's
// SDF_<N>_ name gives) was refused only after the whole pipeline above the
// writer had run (a mesh's conversion: minutes). Now Write() refuses it from
// the input's information pass: one error naming the file and the rule, Write()
// 0, the reader above never read its voxels (its StartEvent: RequestData), no
// file made; a cube of the right edge is then written. Oracle: the reader's
// StartEvent count and the file system.
TEST(LegacyBvIO, AVolumeTheFormatCannotHoldIsRefusedBeforeTheInputRuns)
{
  struct Counter : vtkCommand
  {
    static Counter* New() { return new Counter; }
    void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
    int Count = 0;
  };
  const std::string dir = ::testing::TempDir() + "lvdif_bvgrid_" + std::to_string(::getpid());
  ASSERT_EQ(::mkdir(dir.c_str(), 0755), 0);
  struct Case
  {
    lvdif::Index3 dims;
    std::string target, says;
  };
  for (const Case& c : { Case{ { 12, 10, 8 }, dir + "/box.bv", ".bv holds only cubic volumes; this one is 12 x 10 x 8" },
         Case{ { 8, 8, 8 }, dir + "/SDF_16_named.bv", "file name says N = 16 but the volume's edge is 8" } })
  {
    lvdif::VolumeOptions o;
    o.dims = c.dims;
    o.chunkEdge = 4;
    const std::string source = dir + "/source.lvdv";
    lvdif::saveVolume(lvdif::DictionaryVolume(o), source);
    vtkNew<Counter> runs;
    vtkNew<vtkDictionaryVolumeReader> reader;
    reader->AddObserver(vtkCommand::StartEvent, runs);
    reader->SetFileName(source.c_str());
    vtkNew<ErrorCatcher> errors;
    vtkNew<vtkLegacyBvWriter> writer;
    writer->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetInputConnection(reader->GetOutputPort());
    writer->SetFileName(c.target.c_str());
    EXPECT_EQ(writer->Write(), 0) << c.says;
    EXPECT_EQ(errors->Count, 1) << errors->Text;
    EXPECT_NE(errors->Text.find(c.says), std::string::npos) << errors->Text;
    EXPECT_NE(errors->Text.find(c.target), std::string::npos) << errors->Text;
    EXPECT_EQ(runs->Count, 0) << "the reader ran for a write refused before the work: " << c.says;
    EXPECT_NE(::access(c.target.c_str(), F_OK), 0) << c.target;
    std::remove(source.c_str());
  }
  // a cube named by its edge: written, the reader ran once
  lvdif::VolumeOptions o;
  o.dims = { 8, 8, 8 };
  o.chunkEdge = 4;
  const std::string source = dir + "/cube.lvdv", target = dir + "/SDF_8_cube.bv";
  lvdif::saveVolume(lvdif::DictionaryVolume(o), source);
  vtkNew<Counter> runs;
  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->AddObserver(vtkCommand::StartEvent, runs);
  reader->SetFileName(source.c_str());
  vtkNew<vtkLegacyBvWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName(target.c_str());
  EXPECT_EQ(writer->Write(), 1);
  EXPECT_EQ(runs->Count, 1);
  struct stat st;
  EXPECT_TRUE(::stat(target.c_str(), &st) == 0 && st.st_size == 4 * 8 * 8 * 8) << target;
  std::remove(source.c_str());
  std::remove(target.c_str());
  ::rmdir(dir.c_str());
}

// Under pieces (pvbatch rank r of n), every rank's read of a .bv held the whole
// volume as its partitions: ParaView's Contour over the pieces gave each
// triangle n times, Integrate Variables n times the volume (2 ranks: 28,664
// triangles for 14,332). The file has no index and is still read whole, but a
// piece now owns only its block of chunks, by the .lvdv reader's rule. Oracle:
// VTK's vtkContourFilter on the dense image of the whole read; the pieces'
// contours over their partitions must add up to it, each piece contributing.
TEST(LegacyBvIO, PiecesOwnTheirChunksOnly)
{
  const int n = 72; // 3 x 3 x 3 chunks of 32
  vtkNew<vtkImageData> img;
  img->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(n * n * n);
  for (int k = 0, id = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++id)
      {
        const double dx = i - 35.3, dy = j - 36.6, dz = k - 34.2;
        sdf->SetValue(id, static_cast<float>(std::sqrt(dx * dx + dy * dy + dz * dz) - 27.5));
      }
  img->GetPointData()->AddArray(sdf);
  const std::string path = tempFile("72");
  {
    vtkNew<vtkLegacyBvWriter> writer;
    writer->SetInputData(img);
    writer->SetFileName(path.c_str());
    ASSERT_EQ(writer->Write(), 1);
  }
  vtkNew<vtkLegacyBvReader> whole;
  whole->SetFileName(path.c_str());
  vtkNew<vtkSparseVolumeToImage> dense;
  dense->SetInputConnection(whole->GetOutputPort());
  vtkNew<vtkContourFilter> oracle;
  oracle->SetInputConnection(dense->GetOutputPort());
  oracle->SetValue(0, 0.0);
  oracle->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  oracle->Update();
  const vtkIdType expected = oracle->GetOutput()->GetNumberOfCells();
  ASSERT_GT(expected, 1000);
  for (int pieces = 1; pieces <= 4; ++pieces)
  {
    vtkIdType sum = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      vtkNew<vtkLegacyBvReader> reader;
      reader->SetFileName(path.c_str());
      vtkNew<vtkContourFilter> contour;
      contour->SetInputConnection(reader->GetOutputPort());
      contour->SetValue(0, 0.0);
      contour->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
      contour->UpdatePiece(piece, pieces, 0);
      vtkIdType cells = 0;
      if (auto* out = vtkCompositeDataSet::SafeDownCast(contour->GetOutputDataObject(0)))
        cells = out->GetNumberOfCells();
      else if (auto* ds = vtkDataSet::SafeDownCast(contour->GetOutputDataObject(0)))
        cells = ds->GetNumberOfCells();
      EXPECT_GT(cells, 0) << "piece " << piece << " of " << pieces;
      sum += cells;
    }
    EXPECT_EQ(sum, expected) << pieces << " pieces";
  }
  std::remove(path.c_str());
}
