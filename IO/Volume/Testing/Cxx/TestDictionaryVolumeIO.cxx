// vtkDictionaryVolumeWriter -> file -> vtkDictionaryVolumeReader: values
// against the analytic SDF the image was made from (within the dictionary's
// quantization), colours exactly, sub-extents equal to the whole read, and
// the error paths; the .vti export through VTK's own XML writer and reader.
#include "vtkDictionaryVolumeReader.h"
#include "vtkDictionaryVolumeWriter.h"
#include "vtkSparseVolumeToImage.h"
#include "SdfImageTestUtil.h"

#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>

namespace
{
const int NX = 45, NY = 38, NZ = 29;

double analytic(int i, int j, int k)
{
  const double dx = i - 21.3, dy = j - 17.8, dz = k - 14.1;
  return std::sqrt(dx * dx + dy * dy + dz * dz) - 11.0;
}

vtkSmartPointer<vtkImageData> makeImage()
{
  return makeSdfImage({ 0, NX - 1, 0, NY - 1, 0, NZ - 1 }, { -2.0, 0.5, 3.0 }, { 0.25, 0.5, 0.75 }, analytic,
    [](int i, int j, int k) {
      return std::array<unsigned char, 4>{ static_cast<unsigned char>(i < 20 ? 255 : 10),
        static_cast<unsigned char>(j % 3 * 60), static_cast<unsigned char>(k < 10 ? 0 : 200), 255 };
    });
}

std::string tempFile(const char* name)
{
  return ::testing::TempDir() + "lvdif_io_" + std::to_string(::getpid()) + "_" + name;
}

/// The voxels of `out` (a volume read back) whose sdf differs from the analytic
/// field clamped to +-band by more than the dictionary's quantisation (group A,
/// |d| <= 4.001: step 0.001; beyond: step 0.1), plus those whose colour differs
/// from `in`'s; -1 (and a failure) when its dimensions or arrays are wrong.
int voxelMismatches(vtkImageData* out, vtkImageData* in, double band)
{
  int dims[3];
  out->GetDimensions(dims);
  auto* sdf = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("sdf"));
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("rgba"));
  auto* inRgba = vtkUnsignedCharArray::SafeDownCast(in->GetPointData()->GetArray("rgba"));
  if (dims[0] != NX || dims[1] != NY || dims[2] != NZ || !sdf || !rgba || !inRgba ||
    rgba->GetNumberOfComponents() != 4)
  {
    ADD_FAILURE() << "read back as " << dims[0] << " x " << dims[1] << " x " << dims[2] << ", sdf "
                  << (sdf != nullptr) << ", rgba " << (rgba != nullptr);
    return -1;
  }
  int bad = 0;
  for (int k = 0, id = 0; k < NZ; ++k)
    for (int j = 0; j < NY; ++j)
      for (int i = 0; i < NX; ++i, ++id)
      {
        const double expected = std::max(-band, std::min(band, analytic(i, j, k)));
        const double tol = std::fabs(expected) <= 4.0 ? 0.0005 + 1e-6 : 0.05 + 1e-6;
        bad += std::fabs(sdf->GetValue(id) - expected) > tol;
        for (int c = 0; c < 4; ++c)
          bad += rgba->GetValue(4 * id + c) != inRgba->GetValue(4 * id + c);
      }
  return bad;
}

struct ErrorCatcher : vtkCommand
{
  static ErrorCatcher* New() { return new ErrorCatcher; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    ++this->Count;
    this->Last += static_cast<const char*>(data); // every message, the executive's too
  }
  int Count = 0;
  std::string Last;
};
} // namespace

TEST(DictionaryVolumeIO, WriteThenReadMatchesTheAnalyticField)
{
  auto img = makeImage();
  const std::string path = tempFile("sphere.lvdv");
  vtkNew<vtkDictionaryVolumeWriter> writer;
  writer->SetInputData(img);
  writer->SetFileName(path.c_str());
  writer->SetBandWidth(6.0);
  writer->SetChunkEdge(16);
  writer->SetCompressionLevel(5);
  writer->SetVolumeName("test sphere");
  ASSERT_EQ(writer->Write(), 1);
  ASSERT_TRUE(vtkDictionaryVolumeReader::CanReadFile(path.c_str()));

  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetMetadata("name"), "test sphere");
  vtkNew<vtkSparseVolumeToImage> dense;
  dense->SetInputConnection(reader->GetOutputPort());
  dense->Update();
  vtkImageData* out = dense->GetOutput();
  double origin[3], spacing[3];
  out->GetOrigin(origin);
  out->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(origin[0], -2.0);
  EXPECT_DOUBLE_EQ(spacing[2], 0.75);
  EXPECT_EQ(voxelMismatches(out, img, 6.0), 0);
  std::remove(path.c_str());
}

TEST(DictionaryVolumeIO, SubExtentsEqualTheWholeRead)
{
  auto img = makeImage();
  const std::string path = tempFile("sub.lvdv");
  vtkNew<vtkDictionaryVolumeWriter> writer;
  writer->SetInputData(img);
  writer->SetFileName(path.c_str());
  writer->SetChunkEdge(8);
  ASSERT_EQ(writer->Write(), 1);
  vtkNew<vtkDictionaryVolumeReader> wholeReader;
  wholeReader->SetFileName(path.c_str());
  vtkNew<vtkSparseVolumeToImage> whole;
  whole->SetInputConnection(wholeReader->GetOutputPort());
  whole->Update();
  vtkNew<vtkDictionaryVolumeReader> partReader;
  partReader->SetFileName(path.c_str());
  vtkNew<vtkSparseVolumeToImage> part;
  part->SetInputConnection(partReader->GetOutputPort());
  int ext[6] = { 5, 30, 9, 9, 3, 20 };
  part->UpdateExtent(ext);
  vtkImageData* p = part->GetOutput();
  int got[6];
  p->GetExtent(got);
  for (int a = 0; a < 6; ++a)
    EXPECT_EQ(got[a], ext[a]);
  auto* ws = whole->GetOutput()->GetPointData()->GetArray("sdf");
  auto* ps = p->GetPointData()->GetArray("sdf");
  auto* wc = whole->GetOutput()->GetPointData()->GetArray("rgba");
  auto* pc = p->GetPointData()->GetArray("rgba");
  int bad = 0;
  for (int k = ext[4]; k <= ext[5]; ++k)
    for (int j = ext[2]; j <= ext[3]; ++j)
      for (int i = ext[0]; i <= ext[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        const vtkIdType a = whole->GetOutput()->ComputePointId(ijk), b = p->ComputePointId(ijk);
        bad += ws->GetTuple1(a) != ps->GetTuple1(b);
        bad += wc->GetComponent(a, 1) != pc->GetComponent(b, 1);
      }
  EXPECT_EQ(bad, 0);
  std::remove(path.c_str());
}

TEST(DictionaryVolumeIO, ErrorsAreReportedNotCrashed)
{
  vtkNew<ErrorCatcher> catcher;
  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->AddObserver(vtkCommand::ErrorEvent, catcher);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
  reader->SetFileName(tempFile("missing.lvdv").c_str());
  reader->Update();
  EXPECT_GE(catcher->Count, 1);
  {
    // the file named once (it said "cannot read 'F': cannot open 'F': No such file ...")
    vtkNew<ErrorCatcher> own;
    vtkNew<vtkDictionaryVolumeReader> r;
    r->AddObserver(vtkCommand::ErrorEvent, own);
    const std::string missing = tempFile("missing.lvdv");
    r->SetFileName(missing.c_str());
    r->Update();
    EXPECT_EQ(own->Count, 1) << own->Last;
    EXPECT_NE(own->Last.find(missing), std::string::npos) << own->Last;
    EXPECT_EQ(own->Last.find(missing), own->Last.rfind(missing)) << own->Last;
  }

  // a truncated file names the problem
  auto img = makeImage();
  const std::string path = tempFile("trunc.lvdv");
  vtkNew<vtkDictionaryVolumeWriter> writer;
  writer->SetInputData(img);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
  ASSERT_EQ(::truncate(path.c_str(), 300), 0);
  catcher->Count = 0;
  catcher->Last.clear();
  reader->SetFileName(path.c_str());
  reader->Update();
  EXPECT_GE(catcher->Count, 1);
  EXPECT_NE(catcher->Last.find("footer"), std::string::npos) << catcher->Last;
  std::remove(path.c_str());

  // the writer without an sdf array
  vtkNew<vtkImageData> empty;
  empty->SetDimensions(4, 4, 4);
  vtkNew<vtkDictionaryVolumeWriter> w2;
  w2->AddObserver(vtkCommand::ErrorEvent, catcher);
  w2->SetInputData(empty);
  w2->SetFileName(tempFile("nosdf.lvdv").c_str());
  catcher->Count = 0;
  catcher->Last.clear();
  w2->Write();
  EXPECT_GE(catcher->Count, 1);
  EXPECT_NE(catcher->Last.find("sdf"), std::string::npos);

  // an output folder that does not exist: one error naming the file once (it
  // said "cannot write 'F': cannot write 'F': the folder ... does not exist")
  vtkNew<vtkDictionaryVolumeWriter> w3;
  w3->AddObserver(vtkCommand::ErrorEvent, catcher);
  w3->SetInputData(img);
  const std::string missing = tempFile("no_such_folder") + "/x.lvdv";
  w3->SetFileName(missing.c_str());
  catcher->Count = 0;
  catcher->Last.clear();
  EXPECT_EQ(w3->Write(), 0);
  EXPECT_EQ(catcher->Count, 1) << catcher->Last;
  const std::string& m = catcher->Last;
  EXPECT_NE(m.find("does not exist"), std::string::npos) << m;
  EXPECT_EQ(m.find(missing), m.rfind(missing)) << m;
}

// docs/FORMAT.md, ".vti export": the reader's output through VTK's own XML
// writer, read back by VTK's own XML reader, matches the analytic field the
// volume was made from (within the dictionary's quantization), colours exactly.
TEST(DictionaryVolumeIO, VtiExportThroughVTKsXmlWriter)
{
  auto img = makeImage();
  const std::string lvdv = tempFile("vti.lvdv"), vti = tempFile("export.vti");
  vtkNew<vtkDictionaryVolumeWriter> writer;
  writer->SetInputData(img);
  writer->SetFileName(lvdv.c_str());
  ASSERT_EQ(writer->Write(), 1);

  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->SetFileName(lvdv.c_str());
  vtkNew<vtkSparseVolumeToImage> dense; // the explicit dense conversion
  dense->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkXMLImageDataWriter> xml;
  xml->SetInputConnection(dense->GetOutputPort());
  xml->SetFileName(vti.c_str());
  ASSERT_EQ(xml->Write(), 1);

  vtkNew<vtkXMLImageDataReader> back;
  back->SetFileName(vti.c_str());
  back->Update();
  vtkImageData* out = back->GetOutput();
  double origin[3], spacing[3];
  out->GetOrigin(origin);
  out->GetSpacing(spacing);
  EXPECT_DOUBLE_EQ(origin[1], 0.5);
  EXPECT_DOUBLE_EQ(spacing[1], 0.5);
  EXPECT_EQ(voxelMismatches(out, img, 8.0), 0);
  std::remove(lvdv.c_str());
  std::remove(vti.c_str());
}

// reader -> writer with a damaged input file: Write() must say it failed (it
// answered 1 with nothing written), the file written over must survive
// byte for byte, and the reader's error must come once (vtkWriter::Write ran
// the failed reader a second time). The oracle is the file system.
TEST(DictionaryVolumeIO, WriteFailsWhenTheInputFailsUpstream)
{
  auto img = makeImage();
  const std::string damaged = tempFile("damaged.lvdv"), kept = tempFile("kept.lvdv");
  {
    vtkNew<vtkDictionaryVolumeWriter> writer;
    writer->SetInputData(img);
    writer->SetFileName(damaged.c_str());
    ASSERT_EQ(writer->Write(), 1);
    writer->SetFileName(kept.c_str());
    ASSERT_EQ(writer->Write(), 1);
  }
  ASSERT_EQ(::truncate(damaged.c_str(), 300), 0);
  auto bytes = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  const std::string before = bytes(kept);

  vtkNew<ErrorCatcher> readerErrors;
  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->AddObserver(vtkCommand::ErrorEvent, readerErrors);
  reader->SetFileName(damaged.c_str());
  vtkNew<vtkDictionaryVolumeWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName(kept.c_str());
  EXPECT_EQ(writer->Write(), 0);
  EXPECT_NE(writer->GetErrorCode(), 0UL);
  EXPECT_EQ(readerErrors->Count, 1) << readerErrors->Last;
  EXPECT_EQ(bytes(kept), before);

  // the same writer succeeds again once the input is good
  reader->SetFileName(kept.c_str());
  writer->SetFileName(damaged.c_str());
  EXPECT_EQ(writer->Write(), 1);
  EXPECT_EQ(writer->GetErrorCode(), 0UL);
  std::remove(damaged.c_str());
  std::remove(kept.c_str());
}

// A folder whose mode lets us in but that takes no new files (/proc: as root,
// access() passes): the save said "cannot create a temporary file beside
// '/proc/x.lvdv': No such file or directory"; now one error saying the folder
// cannot be written (the one output guard, lvdif::requireWritable), and the
// writer refuses before encoding. Oracle: a file cannot be created there.
TEST(DictionaryVolumeIO, AFolderThatTakesNoFilesIsNamedNotWritable)
{
  const std::string path = "/proc/lvdif_x.lvdv";
  {
    std::ofstream probe(path);
    if (probe.good())
      GTEST_SKIP() << "/proc takes files here";
  }
  auto img = makeImage();
  vtkNew<ErrorCatcher> catcher;
  vtkNew<vtkDictionaryVolumeWriter> w;
  w->AddObserver(vtkCommand::ErrorEvent, catcher);
  w->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, catcher);
  w->SetInputData(img);
  w->SetFileName(path.c_str());
  EXPECT_EQ(w->Write(), 0);
  EXPECT_EQ(catcher->Count, 1) << catcher->Last;
  EXPECT_NE(catcher->Last.find("cannot write '" + path + "': the folder '/proc' is not writable"), std::string::npos)
    << catcher->Last;
  EXPECT_EQ(catcher->Last.find("No such file"), std::string::npos) << catcher->Last;
}

// A writer whose file cannot be written (a missing folder, an empty name) or
// whose settings are refused (CompressionLevel 0) said so only after
// Write() had brought its input up to date: the whole pipeline above it ran
// first (a mesh's conversion to a volume: minutes at 512^3), then the writer
// refused. Now Write() checks the place and the settings before the input is
// updated: one error, 0, and the reader above never ran (its StartEvent, which
// the executive sends before RequestData, never came). Then the same writer
// with a good name writes, and the reader runs once.
TEST(DictionaryVolumeIO, AnUnwritableTargetIsRefusedBeforeTheInputRuns)
{
  auto img = makeImage();
  const std::string source = tempFile("upstream.lvdv"), target = tempFile("target.lvdv");
  {
    vtkNew<vtkDictionaryVolumeWriter> writer;
    writer->SetInputData(img);
    writer->SetFileName(source.c_str());
    ASSERT_EQ(writer->Write(), 1);
  }
  struct Counter : vtkCommand
  {
    static Counter* New() { return new Counter; }
    void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
    int Count = 0;
  };
  vtkNew<Counter> runs;
  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->AddObserver(vtkCommand::StartEvent, runs);
  reader->SetFileName(source.c_str());
  vtkNew<vtkDictionaryVolumeWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  const std::string missing = ::testing::TempDir() + "lvdif_no_such_folder_" + std::to_string(::getpid()) + "/x.lvdv";
  struct Case
  {
    std::string name;
    int level;
    std::string says;
  };
  for (const Case& c : { Case{ missing, 3, "cannot write '" + missing + "'" }, Case{ "", 3, "no file name" },
         Case{ target, 0, "CompressionLevel" } })
  {
    vtkNew<ErrorCatcher> errors;
    const unsigned long a = writer->AddObserver(vtkCommand::ErrorEvent, errors);
    const unsigned long b = writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    writer->SetFileName(c.name.c_str());
    writer->SetCompressionLevel(c.level);
    EXPECT_EQ(writer->Write(), 0) << c.says;
    EXPECT_NE(writer->GetErrorCode(), 0UL) << c.says;
    EXPECT_EQ(errors->Count, 1) << errors->Last;
    EXPECT_NE(errors->Last.find(c.says), std::string::npos) << errors->Last;
    EXPECT_EQ(runs->Count, 0) << "the reader ran for a write refused before the work: " << c.says;
    writer->RemoveObserver(a);
    writer->GetExecutive()->RemoveObserver(b);
  }
  std::ifstream none(target);
  EXPECT_FALSE(none.good()) << "nothing written";
  writer->SetFileName(target.c_str());
  writer->SetCompressionLevel(3);
  EXPECT_EQ(writer->Write(), 1);
  EXPECT_EQ(runs->Count, 1);
  std::ifstream written(target);
  EXPECT_TRUE(written.good());
  std::remove(source.c_str());
  std::remove(target.c_str());
}

// A write cancelled through AbortExecute (a progress observer, ParaView's or a
// Qt dialog's cancel) wrote nothing and kept the old file, as it should, but
// Write() answered 1: a Python caller checking Write() took the old file (or
// none) for the volume it had asked for. Now 0, with no error message and the
// error code NoError (a cancel is no error); the old file is kept byte for byte
// and no temporary file is left. Oracle: the file's bytes before the write.
TEST(DictionaryVolumeIO, ACancelledWriteAnswersZeroAndKeepsTheOldFile)
{
  auto bytes = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  const std::string target = tempFile("cancelled.lvdv"), fresh = tempFile("cancelled_new.lvdv");
  auto img = makeImage();
  {
    vtkNew<vtkDictionaryVolumeWriter> w;
    w->SetInputData(img);
    w->SetFileName(target.c_str());
    ASSERT_EQ(w->Write(), 1);
  }
  const std::string before = bytes(target);
  ASSERT_FALSE(before.empty());
  // another volume over it
  auto other = makeSdfImage({ 0, 95, 0, 95, 0, 95 }, { -2.0, 0.5, 3.0 }, { 0.25, 0.5, 0.75 },
    [](int i, int j, int k) { return std::sin(0.3 * i) + std::cos(0.2 * j) * std::sin(0.1 * k); },
    [](int, int, int) { return std::array<unsigned char, 4>{ 1, 2, 3, 255 }; });
  struct CancelOnProgress : vtkCommand
  {
    static CancelOnProgress* New() { return new CancelOnProgress; }
    void Execute(vtkObject* caller, unsigned long, void* data) override
    {
      const double p = *static_cast<double*>(data);
      // the save's own progress (its last report comes before the file is
      // committed; a small image reports only 0 and that)
      if (this->Armed && p > 0.0 && this->Cancels == 0)
      {
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
        ++this->Cancels;
      }
    }
    bool Armed = true;
    int Cancels = 0;
  };
  for (const std::string& path : { target, fresh })
  {
    std::remove(fresh.c_str());
    vtkNew<CancelOnProgress> cancel;
    vtkNew<ErrorCatcher> errors;
    vtkNew<vtkDictionaryVolumeWriter> w;
    w->AddObserver(vtkCommand::ProgressEvent, cancel);
    w->AddObserver(vtkCommand::ErrorEvent, errors);
    w->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    // chunks of 4: 13,824 of them, so the save reports progress between its
    // batches of 64 chunks a thread (one batch reports only its end, after which the file is committed)
    w->SetInputData(other);
    w->SetChunkEdge(4);
    w->SetFileName(path.c_str());
    EXPECT_EQ(w->Write(), 0) << path << ": cancelled, nothing written";
    EXPECT_GE(cancel->Cancels, 1);
    EXPECT_EQ(w->GetErrorCode(), 0UL) << "a cancel is no error";
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    if (path == target)
      EXPECT_TRUE(bytes(target) == before) << "the old file changed";
    else
      EXPECT_NE(::access(fresh.c_str(), F_OK), 0) << "a cancelled write made a new file";
    // the same writer, not cancelled: written
    cancel->Armed = false;
    w->SetAbortExecute(0);
    EXPECT_EQ(w->Write(), 1) << path;
    EXPECT_FALSE(bytes(path) == before) << path;
  }
  std::remove(target.c_str());
  std::remove(fresh.c_str());
}
