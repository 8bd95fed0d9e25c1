// vtkLVDIFEditor: edits seen through its image source against analytic SDFs,
// undo/redo bit-identical, events naming every mesh chunk whose mesh the
// changed voxels (found by brute-force image comparison) can change, script errors with line and
// column, record -> play bit-exact through the VTK API.
#include "vtkLVDIFEditor.h"

#include "LVDIFFiles.h"
#include "vtkCallbackCommand.h"
#include "vtkDictionaryVolumeToImage.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "FileTestUtil.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/VolumeFile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
struct Snapshot
{
  int dims[3] = { 0, 0, 0 };
  std::vector<float> sdf;
  std::vector<unsigned char> rgba;
  bool operator==(const Snapshot& o) const
  {
    // bit-identical: compare the bytes, not the floats
    return sdf.size() == o.sdf.size() && rgba == o.rgba &&
      std::memcmp(sdf.data(), o.sdf.data(), sdf.size() * sizeof(float)) == 0;
  }
};

Snapshot snap(vtkLVDIFEditor* ed)
{
  vtkDictionaryVolumeToImage* src = ed->GetImageSource();
  src->Update();
  vtkImageData* img = src->GetOutput();
  Snapshot s;
  img->GetDimensions(s.dims);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetArray("rgba"));
  EXPECT_NE(sdf, nullptr);
  EXPECT_NE(rgba, nullptr);
  if (!sdf || !rgba)
    return s;
  s.sdf.assign(sdf->GetPointer(0), sdf->GetPointer(0) + sdf->GetNumberOfValues());
  s.rgba.assign(rgba->GetPointer(0), rgba->GetPointer(0) + rgba->GetNumberOfValues());
  return s;
}

// Mesh chunk ids (chunks of e cells) whose meshes a change of the differing
// voxels can change: a point p is read by the cells p-1..p and, through the
// central-difference normals, by the cells p-2..p+1 on each axis. Brute force
// over every differing voxel: the oracle for the events, which must name at
// least these (the session's rule names the chunks of the changed voxels' box).
std::set<vtkIdType> invalidatedMeshChunks(const Snapshot& a, const Snapshot& b, int e)
{
  std::set<vtkIdType> ids;
  int ncells[3], nc[3];
  for (int k = 0; k < 3; ++k)
  {
    ncells[k] = a.dims[k] - 1;
    nc[k] = (ncells[k] + e - 1) / e;
  }
  for (int z = 0; z < a.dims[2]; ++z)
    for (int y = 0; y < a.dims[1]; ++y)
      for (int x = 0; x < a.dims[0]; ++x)
      {
        const std::size_t i = static_cast<std::size_t>(x + a.dims[0] * (y + a.dims[1] * z));
        if (std::memcmp(&a.sdf[i], &b.sdf[i], sizeof(float)) == 0 && std::memcmp(&a.rgba[4 * i], &b.rgba[4 * i], 4) == 0)
          continue;
        const int p[3] = { x, y, z };
        int lo[3], hi[3];
        for (int k = 0; k < 3; ++k)
        {
          lo[k] = std::max(0, p[k] - 2) / e;
          hi[k] = std::min(ncells[k] - 1, p[k] + 1) / e;
        }
        for (int cz = lo[2]; cz <= hi[2]; ++cz)
          for (int cy = lo[1]; cy <= hi[1]; ++cy)
            for (int cx = lo[0]; cx <= hi[0]; ++cx)
              ids.insert(static_cast<vtkIdType>(cx + nc[0] * (cy + nc[1] * cz)));
      }
  return ids;
}

bool includes(const std::set<vtkIdType>& big, const std::set<vtkIdType>& small)
{
  return std::includes(big.begin(), big.end(), small.begin(), small.end());
}

struct EventLog
{
  int chunkEvents = 0;
  int modifiedEvents = 0;
  std::set<vtkIdType> lastIds;
  static void Callback(vtkObject*, unsigned long event, void* client, void* callData)
  {
    auto* self = static_cast<EventLog*>(client);
    if (event == vtkLVDIFEditor::ChunksModifiedEvent)
    {
      ++self->chunkEvents;
      self->lastIds.clear();
      auto* ids = static_cast<vtkIdTypeArray*>(callData);
      for (vtkIdType i = 0; i < ids->GetNumberOfValues(); ++i)
        self->lastIds.insert(ids->GetValue(i));
    }
    else if (event == vtkCommand::ModifiedEvent)
      ++self->modifiedEvents;
  }
};

// tolerance of the SDF dictionary's quantization (docs/FORMAT.md): stepA/2 near the surface
double tolerance(double d)
{
  return std::fabs(d) <= 4.0 ? 6e-4 : 0.06;
}
} // namespace

TEST(LVDIFEditor, DabMatchesAnalyticSphereAndUndoRedoAreBitIdentical)
{
  vtkNew<vtkLVDIFEditor> ed;
  ed->SetChunkEdge(16);
  ASSERT_EQ(ed->NewVolume(48, 40, 44, false), 1) << ed->GetLastError();
  EventLog log;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(&EventLog::Callback);
  cb->SetClientData(&log);
  ed->AddObserver(vtkLVDIFEditor::ChunksModifiedEvent, cb);
  ed->AddObserver(vtkCommand::ModifiedEvent, cb);

  const Snapshot empty = snap(ed);
  ed->SetOperationToAdd();
  ed->SetPrimitiveToSphere();
  ed->SetRadius(9.5);
  ed->SetColor(10, 200, 30, 255);
  ASSERT_EQ(ed->Dab(20.25, 17.5, 22.0), 1) << ed->GetLastError();
  const Snapshot dab = snap(ed);
  EXPECT_EQ(log.chunkEvents, 1);
  EXPECT_GE(log.modifiedEvents, 1);
  // oracle: the union of "outside everywhere" (+band) and the sphere is the sphere, saturated to the band
  int checked = 0;
  for (int z = 0; z < 44; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 48; ++x)
      {
        const double d = std::sqrt((x - 20.25) * (x - 20.25) + (y - 17.5) * (y - 17.5) + (z - 22.0) * (z - 22.0)) - 9.5;
        const double expect = std::max(-8.0, std::min(8.0, d));
        const std::size_t i = static_cast<std::size_t>(x + 48 * (y + 40 * z));
        ASSERT_NEAR(dab.sdf[i], expect, tolerance(expect)) << x << " " << y << " " << z;
        if (d <= 1.5) // the colour skin (Brush.h): brush colour inside the sphere plus 1.5 voxels
        {
          EXPECT_EQ(dab.rgba[4 * i + 1], 200);
          ++checked;
        }
      }
  EXPECT_GT(checked, 3000);
  // the event names every mesh chunk whose mesh the dab can have changed
  ASSERT_EQ(ed->GetMeshChunkEdge(), 16);
  const std::set<vtkIdType> invalidated = invalidatedMeshChunks(empty, dab, 16);
  EXPECT_FALSE(invalidated.empty());
  EXPECT_TRUE(includes(log.lastIds, invalidated));

  ASSERT_TRUE(ed->CanUndo());
  EXPECT_FALSE(ed->CanRedo());
  ASSERT_EQ(ed->Undo(), 1);
  EXPECT_TRUE(snap(ed) == empty);
  EXPECT_TRUE(includes(log.lastIds, invalidated));
  ASSERT_TRUE(ed->CanRedo());
  ASSERT_EQ(ed->Redo(), 1);
  EXPECT_TRUE(snap(ed) == dab);
  EXPECT_EQ(log.chunkEvents, 3);

  // a stroke is one undo step; subtract then undo restores the single-dab volume
  ed->SetOperationToSubtract();
  ed->SetRadius(3);
  ed->SetBrushKind(vtkLVDIFEditor::BrushKindBasic);
  ASSERT_EQ(ed->BeginStroke(), 1);
  for (int i = 0; i <= 10; ++i)
    ASSERT_EQ(ed->AddSample(12.0 + i, 17.5, 22.0, -1), 1);
  ASSERT_EQ(ed->EndStroke(), 1) << ed->GetLastError();
  const Snapshot cut = snap(ed);
  EXPECT_FALSE(cut == dab);
  EXPECT_GT(cut.sdf[static_cast<std::size_t>(16 + 48 * (17 + 40 * 22))], 0.0f); // carved out
  EXPECT_EQ(ed->GetUndoCount(), 2);
  ASSERT_EQ(ed->Undo(), 1);
  EXPECT_TRUE(snap(ed) == dab);
  ASSERT_EQ(ed->Undo(), 1);
  EXPECT_TRUE(snap(ed) == empty);
  EXPECT_EQ(ed->Undo(), 0); // nothing left
}

TEST(LVDIFEditor, RefusesBadCallsWithoutChangingTheVolume)
{
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  EXPECT_EQ(ed->Dab(1, 2, 3), 0);
  EXPECT_NE(std::string(ed->GetLastError()).find("no volume"), std::string::npos);
  ASSERT_EQ(ed->NewVolume(24, 24, 24, true), 1);
  const Snapshot full = snap(ed);
  EXPECT_LT(full.sdf[0], 0.0f); // filled = inside
  ed->SetRadius(-2);            // refused, radius unchanged
  EXPECT_GT(ed->GetRadius(), 0.0);
  EXPECT_EQ(ed->Dab(NAN, 2, 3), 0);
  EXPECT_FALSE(std::string(ed->GetLastError()).empty());
  EXPECT_EQ(ed->EndStroke(), 0);
  EXPECT_EQ(ed->LoadVolume("/nonexistent/x.lvdif"), 0);
  EXPECT_EQ(ed->NewVolume(0, 4, 4, false), 0);
  EXPECT_TRUE(snap(ed) == full);
  EXPECT_EQ(ed->PlayRecording("/nonexistent/r.lvrec"), 0);
  EXPECT_TRUE(snap(ed) == full);
}

TEST(LVDIFEditor, ScriptErrorsCarryLineAndColumn)
{
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  ASSERT_EQ(ed->NewVolume(32, 32, 32, false), 1);
  const Snapshot empty = snap(ed);
  // syntax error: nothing runs
  EXPECT_EQ(ed->RunScript("sphere 16 16 16 5\nlet a = 3\n  frobnicate 1 2\n"), 0);
  EXPECT_EQ(ed->GetLastErrorLine(), 3);
  EXPECT_EQ(ed->GetLastErrorColumn(), 3);
  EXPECT_NE(std::string(ed->GetLastError()).find("frobnicate"), std::string::npos);
  EXPECT_TRUE(snap(ed) == empty);
  // run-time error on line 2: the first line's edit is kept and undoable
  EXPECT_EQ(ed->RunScript("sphere 16, 16, 16, 5\nradius -1\n"), 0);
  EXPECT_EQ(ed->GetLastErrorLine(), 2);
  EXPECT_EQ(ed->GetLastErrorColumn(), 8); // the bad value's column (the statement's, 1, until session 24)
  EXPECT_FALSE(snap(ed) == empty);
  EXPECT_TRUE(ed->CanUndo());
  ASSERT_EQ(ed->Undo(), 1);
  EXPECT_TRUE(snap(ed) == empty);
  // success clears the error; the script's edits are undo steps of this editor
  ASSERT_EQ(ed->RunScript("for i in 0..3 { sphere 8 + 8*i, 16, 16, 3 }"), 1) << ed->GetLastError();
  EXPECT_STREQ(ed->GetLastError(), "");
  EXPECT_EQ(ed->GetLastErrorLine(), 0);
  EXPECT_EQ(ed->GetUndoCount(), 3);
  // `canvas` replaces the volume and the image source follows it
  ASSERT_EQ(ed->RunScript("canvas 20 24 28\nsphere 10 12 14 4"), 1) << ed->GetLastError();
  const Snapshot c = snap(ed);
  EXPECT_EQ(c.dims[0], 20);
  EXPECT_EQ(c.dims[2], 28);
  EXPECT_NEAR(c.sdf[static_cast<std::size_t>(10 + 20 * (12 + 24 * 14))], -4.0, 6e-4);
}

TEST(LVDIFEditor, RunScriptFileRefusesWhatIsNoFile)
{
  // A folder was opened by std::ifstream, read as an empty script, and the call
  // succeeded; a FIFO blocked. The one script reader refuses both, naming the path.
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  ASSERT_EQ(ed->NewVolume(16, 16, 16, false), 1);
  const std::string dir = ::testing::TempDir();
  EXPECT_EQ(ed->RunScriptFile(dir.c_str()), 0);
  EXPECT_NE(std::string(ed->GetLastError()).find("not a regular file"), std::string::npos) << ed->GetLastError();
  EXPECT_EQ(ed->RunScriptFile("/nonexistent/s.lvs"), 0);
  EXPECT_NE(std::string(ed->GetLastError()).find("/nonexistent/s.lvs"), std::string::npos) << ed->GetLastError();
  const std::string path = dir + "/lvdif_editor_script.lvs";
  FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("sphere 8, 8, 8, 3\r\n", f);
  std::fclose(f);
  EXPECT_EQ(ed->RunScriptFile(path.c_str()), 1) << ed->GetLastError();
  EXPECT_EQ(ed->GetUndoCount(), 1);
  std::remove(path.c_str());
}

TEST(LVDIFEditor, RecordThenPlayIsBitExact)
{
  const std::string path = std::string(::testing::TempDir()) + "/lvdif_editor_record.lvrec";
  vtkNew<vtkLVDIFEditor> a;
  ASSERT_EQ(a->NewVolume(40, 40, 40, false), 1);
  ASSERT_EQ(a->StartRecording(), 1);
  EXPECT_TRUE(a->IsRecording());
  a->SetRadius(7.3);
  a->SetColor(200, 10, 10, 255);
  ASSERT_EQ(a->Dab(20.1, 19.7, 20.3), 1);
  a->SetPrimitiveToCube();
  a->SetBlend(2.0);
  ASSERT_EQ(a->Dab(26.0, 20.0, 20.0), 1);
  a->SetOperationToSubtract();
  a->SetPrimitiveToSphere();
  a->SetBlend(0);
  a->SetBrushKind(vtkLVDIFEditor::BrushKindDynamic);
  a->SetRadius(3.1);
  ASSERT_EQ(a->BeginStroke(), 1);
  for (int i = 0; i < 12; ++i)
    ASSERT_EQ(a->AddSample(10.0 + 1.37 * i, 20.0 + 0.5 * std::sin(i), 20.0, 0.5 + 0.04 * i), 1);
  ASSERT_EQ(a->EndStroke(), 1);
  a->SetOperationToPaint();
  a->SetColor(0, 0, 255, 255);
  a->SetRadius(5);
  ASSERT_EQ(a->Dab(20, 27, 20), 1);
  ASSERT_EQ(a->Undo(), 1);
  ASSERT_EQ(a->Redo(), 1);
  ASSERT_EQ(a->Undo(), 1);
  ASSERT_EQ(a->RunScript("color 0 255 0\nop add\nsphere 30, 30, 30, 4"), 1) << a->GetLastError();
  ASSERT_EQ(a->StopRecording(path.c_str()), 1) << a->GetLastError();
  EXPECT_FALSE(a->IsRecording());
  const Snapshot recorded = snap(a);

  vtkNew<vtkLVDIFEditor> b;
  ASSERT_EQ(b->NewVolume(40, 40, 40, false), 1);
  const Snapshot empty = snap(b);
  EXPECT_FALSE(recorded == empty);
  ASSERT_EQ(b->PlayRecording(path.c_str()), 1) << b->GetLastError();
  EXPECT_TRUE(snap(b) == recorded);
  // the played edits are undoable like live ones (undo/redo events included)
  while (b->CanUndo())
    ASSERT_EQ(b->Undo(), 1);
  EXPECT_TRUE(snap(b) == empty);
  std::remove(path.c_str());
}

TEST(LVDIFEditor, SaveAndLoadRoundTrip)
{
  const std::string path = std::string(::testing::TempDir()) + "/lvdif_editor_volume.lvdv";
  vtkNew<vtkLVDIFEditor> a;
  ASSERT_EQ(a->NewVolume(33, 20, 17, false), 1);
  a->SetColor(1, 2, 3, 255);
  ASSERT_EQ(a->Dab(16, 10, 8), 1);
  ASSERT_EQ(a->SaveVolume(path.c_str()), 1) << a->GetLastError();
  vtkNew<vtkLVDIFEditor> b;
  ASSERT_EQ(b->LoadVolume(path.c_str()), 1) << b->GetLastError();
  EXPECT_FALSE(b->CanUndo());
  EXPECT_TRUE(snap(b) == snap(a));
  std::remove(path.c_str());
}

// The editors' one smallest canvas (2 voxels per axis: the session meshes its
// volume), with the words of DictionaryVolume::checkCanvasDimensions that the
// script, the Qt editor and `lvdif demo` report; a refused canvas keeps the volume.
TEST(LVDIFEditor, NewVolumeRefusesAThinCanvasWithTheOneRule)
{
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  ASSERT_EQ(ed->NewVolume(20, 20, 20, false), 1) << ed->GetLastError();
  for (const lvdif::Index3& d : { lvdif::Index3{ 1, 1, 1 }, lvdif::Index3{ 20, 1, 20 }, lvdif::Index3{ 0, 5, 5 },
         lvdif::Index3{ lvdif::DictionaryVolume::MaxDimension + 1, 2, 2 }, lvdif::Index3{ 1, 1048576, 1048576 } })
  {
    EXPECT_EQ(ed->NewVolume(int(d[0]), int(d[1]), int(d[2]), false), 0);
    EXPECT_EQ(std::string(ed->GetLastError()), "NewVolume: " + lvdif::DictionaryVolume::checkCanvasDimensions(d));
    int dims[3];
    ed->GetDimensions(dims);
    EXPECT_EQ(dims[1], 20); // the previous canvas stays
  }
  EXPECT_EQ(ed->NewVolume(2, 2, 2, false), 1) << ed->GetLastError();
}

// A file may hold a volume thinner than a canvas (files mesh to nothing); the
// editor's session refuses it with the same words, and keeps its own volume
// (before, the old session was dropped first: the editor was left without one).
TEST(LVDIFEditor, LoadingAThinVolumeKeepsTheCurrentOne)
{
  const std::string path = std::string(::testing::TempDir()) + "/lvdif_editor_thin.lvdv";
  lvdif::VolumeOptions o;
  o.dims = { 8, 1, 8 };
  o.chunkEdge = 8;
  lvdif::saveVolume(lvdif::DictionaryVolume(o), path); // Core's writer: not the editor's
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  ASSERT_EQ(ed->NewVolume(20, 20, 20, true), 1) << ed->GetLastError();
  const Snapshot before = snap(ed);
  EXPECT_EQ(ed->LoadVolume(path.c_str()), 0);
  EXPECT_EQ(std::string(ed->GetLastError()), "LoadVolume: " + lvdif::DictionaryVolume::checkCanvasDimensions(o.dims));
  ASSERT_TRUE(ed->HasVolume());
  EXPECT_TRUE(snap(ed) == before);
  EXPECT_EQ(ed->Dab(10, 10, 10), 1) << ed->GetLastError(); // and still edits it
  std::remove(path.c_str());
}

using filetest::fileExists;
using filetest::slurp;

// SaveVolume/LoadVolume go through the one file registry (before, every name
// got .lvdv content and LoadVolume read only .lvdv): a save to each registered
// volume extension, read back by the registry's reader for that extension (not
// the editor), holds the editor's voxels within the format's quantization
// (.lvdv: the very keys, read by Core's own reader); the editor loads it too.
TEST(LVDIFEditor, SavesAndLoadsEveryRegisteredVolumeFormat)
{
  vtkNew<vtkLVDIFEditor> ed;
  ASSERT_EQ(ed->NewVolume(40, 40, 40, false), 1); // cubic: .bv has no header
  ed->SetRadius(11);
  ed->SetColor(200, 40, 10, 255);
  ASSERT_EQ(ed->Dab(19, 21, 18), 1) << ed->GetLastError();
  const std::shared_ptr<lvdif::DictionaryVolume> mine = ed->GetVolume();
  int formats = 0;
  for (const LVDIFFiles::Format& f : LVDIFFiles::Formats())
  {
    if (f.kind != LVDIFFiles::Kind::Volume || f.writerClass.empty() || f.readerClass.empty())
      continue;
    ++formats;
    const std::string path = std::string(::testing::TempDir()) + "/lvdif_editor_all." + f.extension;
    // a fresh write: an earlier run's pieces without their index are refused as another volume's files
    for (const char* piece : { "_0.lvdv", "_0.g1.lvdv" })
      std::remove((std::string(::testing::TempDir()) + "/lvdif_editor_all" + piece).c_str());
    ASSERT_EQ(ed->SaveVolume(path.c_str()), 1) << f.extension << ": " << ed->GetLastError();
    std::shared_ptr<lvdif::DictionaryVolume> back = LVDIFFiles::LoadVolume(path);
    ASSERT_TRUE(back) << f.extension;
    std::int64_t off[3]; // a format may crop to its active box (OpenVDB): compare by world position
    for (int a = 0; a < 3; ++a)
      off[a] = std::llround((back->options().origin[a] - mine->options().origin[a]) / mine->options().spacing[a]);
    int compared = 0, bad = 0;
    for (std::int64_t z = 0; z < 40; ++z)
      for (std::int64_t y = 0; y < 40; ++y)
        for (std::int64_t x = 0; x < 40; ++x)
        {
          const float d = mine->sdf(x, y, z);
          if (std::fabs(d) > 3.0f || !back->inside(x - off[0], y - off[1], z - off[2]))
            continue; // the band every format keeps
          ++compared;
          bad += std::fabs(back->sdf(x - off[0], y - off[1], z - off[2]) - d) > 0.0011f;
        }
    EXPECT_GT(compared, 1000) << f.extension;
    EXPECT_EQ(bad, 0) << f.extension;
    if (f.extension == "lvdv")
    {
      std::unique_ptr<lvdif::DictionaryVolume> core = lvdif::loadVolume(path);
      for (std::int64_t z = 0; z < 40; ++z)
        for (std::int64_t y = 0; y < 40; ++y)
          for (std::int64_t x = 0; x < 40; ++x)
            ASSERT_EQ(core->get(x, y, z).sdf, mine->get(x, y, z).sdf) << x << " " << y << " " << z;
    }
    vtkNew<vtkLVDIFEditor> other;
    EXPECT_EQ(other->LoadVolume(path.c_str()), 1) << f.extension << ": " << other->GetLastError();
    int dims[3];
    other->GetDimensions(dims);
    EXPECT_EQ(dims[0], back->dims()[0]) << f.extension; // mesh points = voxels
    std::remove(path.c_str());
  }
  EXPECT_GE(formats, 4); // lvdv, lvdvp, bv, vti (+ vdb with OpenVDB)
}

// An extension the registry does not write is refused with its list of
// formats, before anything is written; an existing file under that name, or
// under a registered one whose save then fails, is left as it was.
TEST(LVDIFEditor, SaveVolumeRefusesUnknownExtensionsAndKeepsTheOldFile)
{
  const std::string dir = ::testing::TempDir();
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  ASSERT_EQ(ed->NewVolume(24, 24, 24, true), 1);
  const std::string fresh = dir + "/lvdif_editor_model.lvdif";
  std::remove(fresh.c_str());
  EXPECT_EQ(ed->SaveVolume(fresh.c_str()), 0);
  EXPECT_EQ(std::string(ed->GetLastError()),
    "SaveVolume: cannot write '" + fresh + "': volumes are .lvdv, .lvdvp, .bv, " +
#ifdef LVDIF_WITH_OPENVDB_MODULE
      ".vdb, " +
#endif
      ".vti files");
  EXPECT_FALSE(fileExists(fresh));
  const std::string old = dir + "/lvdif_editor_old.lvdif";
  std::ofstream(old) << "an old file";
  EXPECT_EQ(ed->SaveVolume(old.c_str()), 0);
  EXPECT_EQ(slurp(old), "an old file");
  // a registered extension whose save fails (the dense .vti over the memory limit)
  const std::string vti = dir + "/lvdif_editor_old.vti";
  std::ofstream(vti) << "an old image";
  ::setenv("LVDIF_MEMORY_LIMIT", "4K", 1);
  EXPECT_EQ(ed->SaveVolume(vti.c_str()), 0);
  ::unsetenv("LVDIF_MEMORY_LIMIT");
  EXPECT_NE(std::string(ed->GetLastError()).find("SaveVolume: "), std::string::npos);
  EXPECT_EQ(slurp(vti), "an old image");
  std::remove(old.c_str());
  std::remove(vti.c_str());
}

// SaveVolume into a missing folder names the folder (lvdif::requireWritable,
// the CLI's output check), not the temporary file it could not create.
TEST(LVDIFEditor, SaveVolumeIntoAMissingFolderNamesTheFolder)
{
  const std::string dir = "/nonexistent_lvdif_folder";
  vtkNew<vtkLVDIFEditor> ed;
  ed->GlobalWarningDisplayOff();
  ASSERT_EQ(ed->NewVolume(16, 16, 16, false), 1);
  EXPECT_EQ(ed->SaveVolume((dir + "/v.lvdv").c_str()), 0);
  EXPECT_EQ(std::string(ed->GetLastError()),
    "SaveVolume: cannot write '" + dir + "/v.lvdv': the folder '" + dir + "' does not exist");
}

namespace
{
/// Every error text that reaches VTK's output window (an object nobody observes).
class ErrorLog : public vtkOutputWindow
{
public:
  static ErrorLog* New();
  vtkTypeMacro(ErrorLog, vtkOutputWindow);
  void DisplayErrorText(const char* text) override { this->Errors.emplace_back(text ? text : ""); }
  void DisplayText(const char*) override {}
  std::vector<std::string> Errors;
};
vtkStandardNewMacro(ErrorLog);
}

// LoadVolume of a .vti that is not XML: one error, the editor's (its
// GetLastError names the file and the cause). VTK's XML parser, inside the
// reader, printed its own error line before it ("Error parsing XML in stream").
// Oracle: the texts VTK's output window receives.
TEST(LVDIFEditor, LoadVolumeOfAFileThatIsNotXmlIsOneError)
{
  const std::string path = std::string(::testing::TempDir()) + "/lvdif_editor_junk_" + std::to_string(::getpid()) + ".vti";
  {
    std::ofstream f(path);
    f << "not xml\n";
  }
  vtkNew<ErrorLog> log;
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(log);
  const bool display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOn();
  vtkNew<vtkLVDIFEditor> ed;
  const int loaded = ed->LoadVolume(path.c_str());
  vtkObject::SetGlobalWarningDisplay(display);
  vtkOutputWindow::SetInstance(previous);
  std::remove(path.c_str());
  EXPECT_EQ(loaded, 0);
  const std::string last = ed->GetLastError();
  EXPECT_NE(last.find("cannot read '" + path + "'"), std::string::npos) << last;
  ASSERT_EQ(log->Errors.size(), 1u) << "first: " << log->Errors.front() << "\nlast: " << log->Errors.back();
  EXPECT_NE(log->Errors[0].find("vtkLVDIFEditor"), std::string::npos) << log->Errors[0];
  EXPECT_NE(log->Errors[0].find(last), std::string::npos) << log->Errors[0];
}
