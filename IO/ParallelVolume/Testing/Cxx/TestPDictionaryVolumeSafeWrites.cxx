// vtkPDictionaryVolumeWriter: saving never destroys the old set, and what cannot
// be written is refused before the input runs (duplicate pieces, a write failing
// part-way, killed writes' temporaries, files named as pieces, bad piece files and
// indexes, FIFOs, unwritable targets, cancels). Oracles: the bytes on disk before
// and after, and the upstream's StartEvent count.
#include "PDictionaryVolumeTestUtil.h"

#include "lvdif/VolumeFile.h"

#include <cstring>

using namespace pvio;


namespace
{
/// The reader's first error text for the index at `path` ("" when it read a volume).
std::string readError(const std::string& path)
{
  std::string text;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&text);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* t = static_cast<std::string*>(client);
    if (t->empty()) *t = static_cast<const char*>(call);
  });
  vtkNew<vtkPDictionaryVolumeReader> r;
  r->AddObserver(vtkCommand::ErrorEvent, onError);
  r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, onError);
  vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on
  r->SetFileName(path.c_str());
  r->Update();
  vtkObject::GlobalWarningDisplayOff();
  if (text.empty() && voxels(r) == 0) text = "(no volume and no error)";
  return text;
}

/// The writer's first error text of a Write() that must fail (0).
std::string writeError(vtkPDictionaryVolumeWriter* w)
{
  std::string text;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&text);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* t = static_cast<std::string*>(client);
    if (t->empty()) *t = static_cast<const char*>(call);
  });
  w->AddObserver(vtkCommand::ErrorEvent, onError);
  vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on
  EXPECT_EQ(w->Write(), 0);
  vtkObject::GlobalWarningDisplayOff();
  w->RemoveObserver(onError);
  return text;
}

std::string fileBytes(const std::string& p)
{
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// Another volume than makeImage()'s: other values and colour, another extent and geometry.
vtkSmartPointer<vtkImageData> otherImage()
{
  return makeSdfImage({ 3, 3 + NX - 1, -2, -2 + NY - 1, 5, 5 + NZ - 1 }, { -2.0, 0.5, 3.0 }, { 0.25, 0.5, 0.75 },
    [](int i, int j, int k) { return analytic(i, j, k) + 3.0; },
    [](int, int, int) { return std::array<unsigned char, 4>{ 1, 2, 3, 255 }; });
}

/// The names (sorted) of tmpName(stem...) files in the test folder that contain `part`.
std::vector<std::string> setFiles(const std::string& stem, const std::string& part)
{
  const std::string full = tmpName(stem);
  const std::string prefix = full.substr(full.find_last_of('/') + 1), own = prefix.substr(0, prefix.size() - stem.size());
  std::vector<std::string> names;
  if (DIR* d = ::opendir(std::string(::testing::TempDir()).c_str()))
  {
    while (const dirent* e = ::readdir(d))
    {
      const std::string name = e->d_name;
      if (name.compare(0, prefix.size(), prefix) == 0 && name.find(part) != std::string::npos)
        names.push_back(name.substr(own.size()));
    }
    ::closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

/// Writes img (as a sparse volume) over the set `index` in 3 pieces in one
/// serial Write(), calling `hook` once when the first piece's save reports that
/// it has written every chunk; Write()'s result.
int writeOver(vtkImageData* img, const std::string& index, const std::function<void(vtkPDictionaryVolumeWriter*)>& hook)
{
  vtkNew<vtkImageToSparseVolume> sparse;
  sparse->SetInputData(img);
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputConnection(sparse->GetOutputPort());
  w->SetFileName(index.c_str());
  w->SetNumberOfPieces(3);
  struct Watch
  {
    vtkPDictionaryVolumeWriter* writer;
    const std::function<void(vtkPDictionaryVolumeWriter*)>& hook;
    bool called = false;
  } watch{ w, hook };
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&watch);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* wt = static_cast<Watch*>(client);
    if (!wt->called && *static_cast<double*>(call) >= 0.999)
    {
      wt->called = true;
      wt->hook(wt->writer);
    }
  });
  w->AddObserver(vtkCommand::ProgressEvent, onProgress);
  w->GlobalWarningDisplayOff();
  return w->Write();
}
} // namespace

// An index that lists a piece twice, or a piece overlapping the others, was
// read (the first listed won on the shared points, without a word). Now the
// index is refused naming the two pieces and their extents. Oracle: the same
// piece files listed once each read (the writer's index), and the extents of
// the translator's split.
TEST(PVolumeIO, DuplicateOrOverlappingPiecesAreRefused)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("dup.lvdvp");
  writePieces(img, index, 2);
  const std::string whole = tmpName("dup_whole.lvdv");
  {
    vtkNew<vtkDictionaryVolumeWriter> w;
    w->SetInputData(img);
    w->SetFileName(whole.c_str());
    ASSERT_EQ(w->Write(), 1);
  }
  EXPECT_EQ(readError(index), "");
  int ext[6], e0[6], e1[6];
  img->GetExtent(ext);
  vtkPDictionaryVolumeWriter::PieceExtent(ext, 0, 2, e0);
  vtkPDictionaryVolumeWriter::PieceExtent(ext, 1, 2, e1);
  auto text = [](const int* e) {
    std::string s;
    for (int q = 0; q < 6; ++q) s += (q ? " " : "") + std::to_string(e[q]);
    return s;
  };
  auto header = [&](int pieces) {
    return "LVDIF-PVOLUME 1\nwhole_extent " + text(ext) + "\norigin -2 0.5 3\nspacing 0.25 0.5 0.75\npieces " +
      std::to_string(pieces) + "\n";
  };
  const std::string f0 = "lvdif_p_" + std::to_string(getpid()) + "_dup_0.lvdv";
  const std::string f1 = "lvdif_p_" + std::to_string(getpid()) + "_dup_1.lvdv";
  const std::string fw = "lvdif_p_" + std::to_string(getpid()) + "_dup_whole.lvdv";
  const std::string bad = tmpName("dup_bad.lvdvp");
  // piece 0 listed twice
  std::ofstream(bad) << header(3) << "piece " << text(e0) << " " << f0 << "\npiece " << text(e1) << " " << f1
                     << "\npiece " << text(e0) << " " << f0 << "\n";
  std::string error = readError(bad);
  EXPECT_NE(error.find("piece 1 and piece 3 have the same extent " + text(e0)), std::string::npos) << error;
  // the whole volume listed beside its two pieces
  std::ofstream(bad) << header(3) << "piece " << text(e0) << " " << f0 << "\npiece " << text(e1) << " " << f1
                     << "\npiece " << text(ext) << " " << fw << "\n";
  error = readError(bad);
  EXPECT_NE(error.find("piece 1 (extent " + text(e0) + ") and piece 3 (extent " + text(ext) + ") overlap"),
    std::string::npos)
    << error;
  // a hole: piece 1 alone
  std::ofstream(bad) << header(1) << "piece " << text(e1) << " " << f1 << "\n";
  error = readError(bad);
  EXPECT_NE(error.find("is larger than its piece's extent " + text(e1)), std::string::npos) << error;
  for (const std::string& f : { bad, index, whole, tmpName("dup_0.lvdv"), tmpName("dup_1.lvdv") })
    std::remove(f.c_str());
}

// A serial write of n pieces that failed part way (here: cancelled while
// writing piece 1) had already replaced piece 0, and the old index listed the
// new piece 0 with the old piece 1: the saved volume was destroyed. Now the
// pieces are written to temporary files beside theirs and renamed only when
// all of them are written (then the index is written): the old index and pieces stay byte for byte, and no
// temporary file is left. Oracle: the files' bytes before the write.
TEST(PVolumeIO, SerialWriteThatFailsPartWayKeepsTheOldFiles)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("keep.lvdvp");
  writePieces(img, index, 3);
  const std::string piece[3] = { vtkPDictionaryVolumeWriter::PieceFilePath(index, 0),
    vtkPDictionaryVolumeWriter::PieceFilePath(index, 1), vtkPDictionaryVolumeWriter::PieceFilePath(index, 2) };
  const std::string before[4] = { fileBytes(index), fileBytes(piece[0]), fileBytes(piece[1]), fileBytes(piece[2]) };
  // another volume written over it, cancelled when piece 0's save reports it has
  // written every chunk: piece 0 is then saved, and the next piece stops at its first check
  bool cancelled = false;
  EXPECT_EQ(writeOver(otherImage(), index, [&](vtkPDictionaryVolumeWriter* w) {
    cancelled = true;
    w->SetAbortExecute(1);
  }),
    0);
  EXPECT_TRUE(cancelled);
  EXPECT_TRUE(fileBytes(index) == before[0]) << "index";
  for (int p = 0; p < 3; ++p)
    EXPECT_TRUE(fileBytes(piece[p]) == before[1 + p]) << "piece " << p;
  // no temporary file left beside them
  EXPECT_EQ(setFiles("keep", ".tmp-"), std::vector<std::string>());
  vtkNew<vtkPDictionaryVolumeReader> r;
  r->SetFileName(index.c_str());
  expectSameArrays(decoded(r), serialRoundTrip(img));
  for (const std::string& f : { index, piece[0], piece[1], piece[2] })
    std::remove(f.c_str());
}

// A write's pieces were renamed over the old ones before the new index was
// written: a rename failing after others had succeeded (the folder changed
// under the writer) left the old index listing new pieces beside old ones. Now
// the pieces go to the generation the old index does not list (name_<p>.g1.lvdv
// beside name_<p>.lvdv), and only the new index switches: a piece failing after
// others were saved (here piece 2's file becomes a folder during the write)
// leaves the old index and its pieces byte for byte, and the new pieces are
// removed. Oracle: the files' bytes before the write and the serial round trip
// of each volume. A write that succeeds switches generation and removes the
// old pieces; the next one switches back.
TEST(PVolumeIO, AWriteFailingAfterSomePiecesKeepsTheOldSetWhole)
{
  vtkSmartPointer<vtkImageData> img = makeImage(), other = otherImage();
  const std::string index = tmpName("gen.lvdvp");
  writePieces(img, index, 3);
  const std::vector<std::string> plain{ "gen_0.lvdv", "gen_1.lvdv", "gen_2.lvdv" };
  ASSERT_EQ(setFiles("gen_", ""), plain);
  std::vector<std::string> before{ fileBytes(index) };
  for (const std::string& f : plain)
    before.push_back(fileBytes(tmpName(f)));
  const std::string blocker = tmpName("gen_2.g1.lvdv");
  EXPECT_EQ(writeOver(other, index, [&](vtkPDictionaryVolumeWriter*) { ::mkdir(blocker.c_str(), 0755); }), 0);
  ::rmdir(blocker.c_str());
  EXPECT_TRUE(fileBytes(index) == before[0]) << "index";
  for (std::size_t p = 0; p < plain.size(); ++p)
    EXPECT_TRUE(fileBytes(tmpName(plain[p])) == before[1 + p]) << plain[p];
  EXPECT_EQ(setFiles("gen_", ""), plain); // the new pieces 0 and 1 are removed, no temporary is left
  auto read = [&] {
    vtkNew<vtkPDictionaryVolumeReader> r;
    r->SetFileName(index.c_str());
    return vtkSmartPointer<vtkImageData>(decoded(r));
  };
  expectSameArrays(read(), serialRoundTrip(img));
  // the same write without the folder: the new generation, the old pieces removed
  EXPECT_EQ(writeOver(other, index, [](vtkPDictionaryVolumeWriter*) {}), 1);
  const std::vector<std::string> now = setFiles("gen_", ""); // (this sparse volume has chunks for 2 of its 3 pieces)
  EXPECT_FALSE(now.empty());
  for (const std::string& f : now)
  {
    EXPECT_NE(f.find(".g1.lvdv"), std::string::npos) << f;
    EXPECT_NE(fileBytes(index).find(f + "\n"), std::string::npos) << f << " is not in the index";
  }
  expectSameArrays(read(), serialRoundTrip(other));
  // and back, in 2 pieces: the third of generation 1 is no part of the set any more
  writePieces(img, index, 2);
  EXPECT_EQ(setFiles("gen_", ""), std::vector<std::string>(plain.begin(), plain.begin() + 2));
  expectSameArrays(read(), serialRoundTrip(img));
  for (const std::string& f : setFiles("gen", ""))
    std::remove(tmpName(f).c_str());
}

// A write that was killed (or whose machine went down) left its temporary piece
// files beside the set for good (name_<p>.lvdv.tmp-<pid>-staged.lvdv): the next
// write of the set removes those whose process is gone, by the project's rule
// for temporary files (lvdif::removeStaleTemporaries), and only those of the
// set: a live process's, another set's and other files stay.
TEST(PVolumeIO, TemporariesOfAKilledWriteAreRemovedByTheNextWrite)
{
  const pid_t child = ::fork();
  if (child == 0)
    ::_exit(0);
  ASSERT_GT(child, 0);
  ASSERT_EQ(::waitpid(child, nullptr, 0), child); // a process that is gone
  const std::string dead = std::to_string(child), live = std::to_string(::getppid());
  const std::vector<std::string> stale{ "stale_0.lvdv.tmp-" + dead + "-staged.lvdv",
    "stale_1.g1.lvdv.tmp-" + dead + "-Ab12Cd.lvdv", "stale_7.lvdv.tmp-" + dead + "-staged.lvdv",
    "stale_5.g1.lvdv" /* a piece no index lists */ };
  const std::vector<std::string> kept{ "stale_0.lvdv.tmp-" + live + "-staged.lvdv", "stale_0.lvdv.bak",
    "stale_5.g2.lvdv", "stalex_0.lvdv.tmp-" + dead + "-staged.lvdv" };
  // the set has an index (a first write): its killed later writes left the files (a piece no
  // index lists beside a set without an index may be another volume's: the write refuses it,
  // PVolumeIO.AFirstWriteKeepsFilesNamedAsItsPieces)
  const std::string index = tmpName("stale.lvdvp");
  writePieces(makeImage(), index, 2);
  for (const std::string& f : stale)
    std::ofstream(tmpName(f)) << "left";
  for (const std::string& f : kept)
    std::ofstream(tmpName(f)) << "other";
  writePieces(makeImage(), index, 2);
  for (const std::string& f : stale)
    EXPECT_FALSE(std::ifstream(tmpName(f)).good()) << f << " is left";
  for (const std::string& f : kept)
    EXPECT_EQ(fileBytes(tmpName(f)), "other") << f;
  for (const std::string& f : setFiles("stale", ""))
    std::remove(tmpName(f).c_str());
}

// Files named as pieces of a set that has no index yet (a user's scan_1.lvdv and scan_2.lvdv
// beside a first write of scan.lvdvp) were overwritten (scan_0.lvdv) or removed (the others, as
// "piece files the new index does not list") without a word. Now the first write is refused before
// anything is written, naming them, and they stay byte for byte; once they are gone it writes.
TEST(PVolumeIO, AFirstWriteKeepsFilesNamedAsItsPieces)
{
  const std::string index = tmpName("foreign.lvdvp");
  const std::vector<std::string> foreign{ "foreign_0.lvdv", "foreign_1.lvdv", "foreign_7.g1.lvdv" };
  for (const std::string& f : foreign)
    std::ofstream(tmpName(f)) << "a user's " << f;
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputData(makeImage());
  w->SetFileName(index.c_str());
  w->SetNumberOfPieces(2);
  const std::string text = writeError(w);
  EXPECT_NE(text.find("'lvdif_p_" + std::to_string(getpid()) + "_foreign_0.lvdv', 'lvdif_p_" +
              std::to_string(getpid()) + "_foreign_1.lvdv', 'lvdif_p_" + std::to_string(getpid()) +
              "_foreign_7.g1.lvdv' lie beside it, named as pieces of its set, but no index lists them"),
    std::string::npos)
    << text;
  EXPECT_FALSE(std::ifstream(index).good()) << "an index was written";
  for (const std::string& f : foreign)
    EXPECT_EQ(fileBytes(tmpName(f)), "a user's " + f) << f;
  for (const std::string& f : foreign)
    std::remove(tmpName(f).c_str());
  writePieces(makeImage(), index, 2);
  for (const std::string& f : setFiles("foreign", ""))
    std::remove(tmpName(f).c_str());
}

// A piece file that is no .lvdv (here: the index itself, a .vti) or a damaged
// one was reported as "cannot read 'x.lvdvp': header: bad magic: ...", naming
// the index only: the user could not tell which of its files was bad. Now the
// error names the piece file.
TEST(PVolumeIO, ABadPieceFileIsNamed)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("named.lvdvp");
  writePieces(img, index, 2);
  const std::string p1 = vtkPDictionaryVolumeWriter::PieceFilePath(index, 1);
  const std::string stem = "lvdif_p_" + std::to_string(getpid()) + "_named_1.lvdv";
  std::ofstream(p1) << "not a volume";
  std::string error = readError(index);
  EXPECT_NE(error.find("piece file '" + stem + "': "), std::string::npos) << error;
  EXPECT_NE(error.find("too short for an LVDIF volume"), std::string::npos) << error;
  // the first piece's (read for the volume's settings)
  const std::string p0 = vtkPDictionaryVolumeWriter::PieceFilePath(index, 0);
  std::ofstream(p0) << std::string(300, 'x');
  error = readError(index);
  EXPECT_NE(error.find("piece file 'lvdif_p_" + std::to_string(getpid()) + "_named_0.lvdv': header: bad magic"),
    std::string::npos)
    << error;
  for (const std::string& f : { index, p0, p1 })
    std::remove(f.c_str());
}

// A piece file of the index's size but another grid (a file of another set of the
// same shape copied in: another spacing, or shifted) was read without a word, its
// voxels put where the index says. Now its header is checked against the index
// before the volume is made (origin = the index's origin + spacing x the piece's
// first point; the writer's rule), and the error names the piece file. Oracle:
// the header fields as docs/FORMAT.md lays them out (origin at byte 40, spacing at
// 64, the checksum of bytes [0, 152) at 152).
TEST(PVolumeIO, APieceOfAnotherGridIsRefused)
{
  vtkSmartPointer<vtkImageData> img = makeImage(); // spacing 0.25 0.5 0.75
  const std::string index = tmpName("grid.lvdvp");
  writePieces(img, index, 2);
  const std::string p1 = vtkPDictionaryVolumeWriter::PieceFilePath(index, 1);
  const std::string stem = "lvdif_p_" + std::to_string(getpid()) + "_grid_1.lvdv";
  const std::string good = fileBytes(p1);
  ASSERT_EQ(readError(index), "");
  auto patched = [&](std::size_t at, double value) {
    std::string b = good;
    std::memcpy(&b[at], &value, 8);
    const std::uint64_t sum = lvdif::checksum64(b.data(), 152);
    std::memcpy(&b[152], &sum, 8);
    std::ofstream(p1, std::ios::binary) << b;
  };
  patched(64, 0.5); // spacing x 0.5, not 0.25
  std::string error = readError(index);
  EXPECT_NE(error.find("piece file '" + stem + "' has origin "), std::string::npos) << error;
  EXPECT_NE(error.find(" and spacing 0.5 0.5 0.75, the index puts it at "), std::string::npos) << error;
  EXPECT_NE(error.find(" with spacing 0.25 0.5 0.75 (a piece of another volume?)"), std::string::npos) << error;
  double z = 0;
  std::memcpy(&z, &good[56], 8);
  patched(56, z + 0.75); // one voxel up in z
  error = readError(index);
  EXPECT_NE(error.find("piece file '" + stem + "' has origin "), std::string::npos) << error;
  patched(56, z + 1e-9); // a millionth of a voxel is the same grid
  EXPECT_EQ(readError(index), "");
  for (const std::string& f : { index, vtkPDictionaryVolumeWriter::PieceFilePath(index, 0), p1 })
    std::remove(f.c_str());
}

// An index whose spacing is no spacing ("-1 1 1", "0 1 1") or whose grid leaves the volumes'
// range was read: its information told the pipeline that grid, and the read failed later in the
// volume's own words. Now the index is refused in its information pass by the volumes' one
// geometry rule (DictionaryVolume::checkGeometry); the pieces are the good set's.
TEST(PVolumeIO, AnIndexOfNoGridIsRefusedInItsInformation)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("nogrid.lvdvp");
  writePieces(img, index, 2);
  const std::string text = fileBytes(index);
  const std::size_t at = text.find("\nspacing ");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = text.find('\n', at + 1);
  const std::string bad = tmpName("nogrid_bad.lvdvp");
  for (const char* line : { "spacing -1 0.5 0.75", "spacing 0.25 0 0.75", "spacing 0.25 0.5 1e300" })
  {
    // the bad index lists the good set's pieces by name: they lie beside it
    std::ofstream(bad) << text.substr(0, at + 1) + line + text.substr(end);
    vtkNew<vtkPDictionaryVolumeReader> r;
    r->GlobalWarningDisplayOff();
    r->SetFileName(bad.c_str());
    EXPECT_EQ(r->GetExecutive()->UpdateInformation(), 0) << line;
    const std::string error = readError(bad);
    EXPECT_NE(error.find("': origin and spacing: volume origin "), std::string::npos) << line << ": " << error;
  }
  std::ofstream(bad) << text;
  EXPECT_EQ(readError(bad), "");
  for (const std::string& f : { index, bad, vtkPDictionaryVolumeWriter::PieceFilePath(index, 0),
         vtkPDictionaryVolumeWriter::PieceFilePath(index, 1) })
    std::remove(f.c_str());
}

// A garbage .lvdvp of gigabytes (here 3 GiB, sparse) was read whole before its
// first line was found not to be an index: with the memory limit below it was
// refused for memory ("reading the index needs 3.00 GiB"), without one it took
// the gigabytes. Now the first line is read first: the usual error, at once.
TEST(PVolumeIO, AGarbageIndexOfGigabytesIsRefusedAfterItsHead)
{
  const std::string bad = tmpName("garbage.lvdvp");
  {
    std::ofstream f(bad, std::ios::binary);
    f << "# a comment\nGARBAGE " << std::string(200, 'x') << "\n";
  }
  ASSERT_EQ(::truncate(bad.c_str(), off_t(3) << 30), 0);
  const char* old = std::getenv("LVDIF_MEMORY_LIMIT");
  const std::string kept = old ? old : "";
  ::setenv("LVDIF_MEMORY_LIMIT", "256M", 1);
  const auto t0 = std::chrono::steady_clock::now();
  const std::string error = readError(bad);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (old)
    ::setenv("LVDIF_MEMORY_LIMIT", kept.c_str(), 1);
  else
    ::unsetenv("LVDIF_MEMORY_LIMIT");
  EXPECT_NE(error.find("line 2: not an LVDIF volume index (expected 'LVDIF-PVOLUME <version>')"), std::string::npos)
    << error;
  EXPECT_LT(seconds, 2.0);
  std::remove(bad.c_str());
}

// CanReadFile (ParaView's file dialog asks every reader about every file)
// opened the path with std::ifstream: a FIFO blocked it until something wrote
// to it. Now the project's file check refuses it at once; a real file is still
// recognised (an index after a comment line too). If the call blocks, the test
// opens the FIFO's other end to free it, and fails.
TEST(PVolumeIO, CanReadFileDoesNotBlockOnAFifo)
{
  const std::string fifo = tmpName("fifo.lvdvp");
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (int which = 0; which < 2; ++which)
  {
    auto answer = std::async(std::launch::async, [&] {
      return which == 0 ? vtkPDictionaryVolumeReader::CanReadFile(fifo.c_str())
                        : vtkDictionaryVolumeReader::CanReadFile(fifo.c_str());
    });
    const bool blocked = answer.wait_for(std::chrono::seconds(3)) != std::future_status::ready;
    EXPECT_FALSE(blocked) << (which == 0 ? "vtkPDictionaryVolumeReader" : "vtkDictionaryVolumeReader");
    if (blocked)
    {
      const int w = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK); // the reader's open returns, then EOF
      if (w >= 0) ::close(w);
    }
    EXPECT_FALSE(answer.get());
  }
  std::remove(fifo.c_str());
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("can.lvdvp");
  writePieces(img, index, 1);
  EXPECT_TRUE(vtkPDictionaryVolumeReader::CanReadFile(index.c_str()));
  EXPECT_TRUE(vtkDictionaryVolumeReader::CanReadFile(vtkPDictionaryVolumeWriter::PieceFilePath(index, 0).c_str()));
  EXPECT_FALSE(vtkDictionaryVolumeReader::CanReadFile(index.c_str()));
  const std::string text = fileBytes(index);
  std::ofstream(index) << "# a comment first\n" << text;
  EXPECT_TRUE(vtkPDictionaryVolumeReader::CanReadFile(index.c_str()));
  std::remove(index.c_str());
  std::remove(vtkPDictionaryVolumeWriter::PieceFilePath(index, 0).c_str());
}

// A .lvdvp write into a missing folder (or a folder where a piece file would
// go, without a name, with CompressionLevel 0, with a piece that does not
// exist, an image input with a bad ChunkEdge) ran the whole pipeline above it
// (a mesh's conversion: minutes) and only then refused. Now Write() refuses
// first: one error naming the cause, Write() 0, the reader above never ran,
// and an existing index stays byte for byte; then a good write runs it once.
// Oracle: the reader's StartEvent count and the files on disk.
TEST(PVolumeIO, AnUnwritableTargetIsRefusedBeforeTheInputRuns)
{
  // ErrorEvent fires only with the global warning display on (other tests turn it off)
  const int display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOn();
  struct Restore
  {
    int Display;
    ~Restore() { vtkObject::SetGlobalWarningDisplay(this->Display); }
  } restore{ display };
  struct ErrorCatcher : vtkCommand
  {
    static ErrorCatcher* New() { return new ErrorCatcher; }
    void Execute(vtkObject*, unsigned long, void* data) override
    {
      ++this->Count;
      this->Last += static_cast<const char*>(data);
    }
    int Count = 0;
    std::string Last;
  };
  struct Counter : vtkCommand
  {
    static Counter* New() { return new Counter; }
    void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
    int Count = 0;
  };
  auto bytes = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string source = tmpName("before_source.lvdv"), index = tmpName("before.lvdvp");
  {
    vtkNew<vtkDictionaryVolumeWriter> w;
    w->SetInputData(img);
    w->SetFileName(source.c_str());
    ASSERT_EQ(w->Write(), 1);
  }
  writePieces(img, index, 2);
  const std::string missing = tmpName("no_such_folder") + "/x.lvdvp";
  for (const bool imageInput : { false, true })
  {
    const std::string before = bytes(index); // (the second round: the first's good write)
    // folders where piece 2 of a 3-piece write would go (either generation; a
    // good write removes the empty folders named like its set's piece files)
    for (int g = 0; g < 2; ++g)
      ::mkdir(vtkPDictionaryVolumeWriter::PieceFilePath(index, 2, g).c_str(), 0755);
    vtkNew<Counter> runs;
    vtkNew<vtkDictionaryVolumeReader> reader;
    reader->AddObserver(vtkCommand::StartEvent, runs);
    reader->SetFileName(source.c_str());
    vtkNew<vtkSparseVolumeToImage> dense;
    dense->SetInputConnection(reader->GetOutputPort());
    vtkNew<vtkPDictionaryVolumeWriter> writer;
    writer->SetController(nullptr);
    writer->SetInputConnection(imageInput ? dense->GetOutputPort() : reader->GetOutputPort());
    struct Case
    {
      std::string name;
      int level, chunkEdge, piece, pieces;
      std::string says;
    };
    std::vector<Case> cases = { { missing, 3, 32, 0, 1, "the folder" }, { "", 3, 32, 0, 1, "no file name" },
      { index, 0, 32, 0, 1, "CompressionLevel" }, { index, 3, 32, 0, 3, "before_2" },
      { index, 3, 32, 2, 2, "does not exist" } };
    if (imageInput)
      cases.push_back({ index, 3, 5, 0, 1, "5" }); // a chunk edge applies to an image input only
    for (const Case& c : cases)
    {
      vtkNew<ErrorCatcher> errors;
      const unsigned long a = writer->AddObserver(vtkCommand::ErrorEvent, errors);
      const unsigned long b = writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
      writer->SetFileName(c.name.c_str());
      writer->SetCompressionLevel(c.level);
      writer->SetChunkEdge(c.chunkEdge);
      writer->SetPiece(c.piece);
      writer->SetNumberOfPieces(c.pieces);
      EXPECT_EQ(writer->Write(), 0) << c.says;
      EXPECT_NE(writer->GetErrorCode(), 0UL) << c.says;
      EXPECT_EQ(errors->Count, 1) << errors->Last;
      EXPECT_NE(errors->Last.find(c.says), std::string::npos) << errors->Last;
      EXPECT_EQ(runs->Count, 0) << "the reader ran for a write refused before the work: " << c.says;
      EXPECT_EQ(bytes(index), before) << c.says;
      writer->RemoveObserver(a);
      writer->GetExecutive()->RemoveObserver(b);
    }
    // the same writer, fixed: the reader runs once and the volume is written
    writer->SetFileName(index.c_str());
    writer->SetCompressionLevel(3);
    writer->SetChunkEdge(32);
    writer->SetPiece(0);
    writer->SetNumberOfPieces(1);
    EXPECT_EQ(writer->Write(), 1);
    EXPECT_EQ(runs->Count, 1);
    vtkNew<vtkPDictionaryVolumeReader> back;
    back->SetFileName(index.c_str());
    back->Update();
    EXPECT_EQ(voxels(back), NX * NY * NZ);
  }
  for (int g = 0; g < 2; ++g)
    ::rmdir(vtkPDictionaryVolumeWriter::PieceFilePath(index, 2, g).c_str());
  for (const std::string& f : { source, index, vtkPDictionaryVolumeWriter::PieceFilePath(index, 0, 0),
         vtkPDictionaryVolumeWriter::PieceFilePath(index, 0, 1), vtkPDictionaryVolumeWriter::PieceFilePath(index, 1, 0) })
    std::remove(f.c_str());
}

// An image written as .lvdvp goes through one .lvdv writer per piece, whose
// progress and cancel were its own: the .lvdvp writer reported no progress
// between 0 and 1 and a cancel (AbortExecute from a progress observer, ParaView's
// or a Qt dialog's) could not reach the pieces: the write ran to the end and
// replaced the old set. Now the pieces' progress is the writer's (piece p of n
// its p-th n-th) and its cancel theirs: Write() answers 0, the old index and
// pieces stay byte for byte, no temporary file is left; uncancelled, the same
// write reports progress in (0, 1) and is read back as the image. Oracles: the
// files' bytes before the write, the serial round trip.
TEST(PVolumeIO, AnImageWriteReportsProgressAndCanBeCancelled)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("cancelimg.lvdvp");
  writePieces(img, index, 3);
  const std::string piece[3] = { vtkPDictionaryVolumeWriter::PieceFilePath(index, 0),
    vtkPDictionaryVolumeWriter::PieceFilePath(index, 1), vtkPDictionaryVolumeWriter::PieceFilePath(index, 2) };
  const std::string before[4] = { fileBytes(index), fileBytes(piece[0]), fileBytes(piece[1]), fileBytes(piece[2]) };
  struct Watch
  {
    bool cancel;
    std::vector<double> progress;
  };
  for (const bool cancel : { true, false })
  {
    Watch watch{ cancel, {} };
    vtkNew<vtkPDictionaryVolumeWriter> w;
    w->SetController(nullptr);
    w->SetInputData(otherImage());
    w->SetFileName(index.c_str());
    w->SetNumberOfPieces(3);
    vtkNew<vtkCallbackCommand> onProgress;
    onProgress->SetClientData(&watch);
    onProgress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
      auto* wt = static_cast<Watch*>(client);
      const double p = *static_cast<double*>(call);
      wt->progress.push_back(p);
      if (wt->cancel && p > 0.0 && p < 1.0) // within the write: piece 1 or 2 starts
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    });
    w->AddObserver(vtkCommand::ProgressEvent, onProgress);
    const int written = w->Write();
    const bool reported = std::any_of(
      watch.progress.begin(), watch.progress.end(), [](double p) { return p > 0.0 && p < 1.0; });
    EXPECT_TRUE(reported) << "no progress between 0 and 1 (" << watch.progress.size() << " reports)";
    if (cancel)
    {
      EXPECT_EQ(written, 0) << "cancelled";
      EXPECT_TRUE(fileBytes(index) == before[0]) << "index";
      for (int p = 0; p < 3; ++p)
        EXPECT_TRUE(fileBytes(piece[p]) == before[1 + p]) << "piece " << p;
      EXPECT_EQ(setFiles("cancelimg", ".tmp-"), std::vector<std::string>());
    }
    else
    {
      EXPECT_EQ(written, 1);
      vtkNew<vtkPDictionaryVolumeReader> r;
      r->SetFileName(index.c_str());
      expectSameArrays(decoded(r), serialRoundTrip(otherImage()));
    }
  }
  std::remove(index.c_str());
  for (int g = 0; g < 2; ++g)
    for (int p = 0; p < 3; ++p)
      std::remove(vtkPDictionaryVolumeWriter::PieceFilePath(index, p, g).c_str());
}

// A new user's empty vtkImageData (or a source that made nothing) written over
// an existing set: Write() returned 1, the old pieces were removed and the index
// rewritten with no pieces and an empty whole extent, which the reader refuses.
// Now the write is refused with one error and the old set stays byte for byte.
// Oracle: the files' bytes before, and the serial round trip of the old volume.
TEST(PVolumeIO, AnEmptyImageIsRefusedAndKeepsTheOldSet)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("emptyover.lvdvp");
  writePieces(img, index, 2);
  const std::string piece[2] = { vtkPDictionaryVolumeWriter::PieceFilePath(index, 0),
    vtkPDictionaryVolumeWriter::PieceFilePath(index, 1) };
  const std::string before[3] = { fileBytes(index), fileBytes(piece[0]), fileBytes(piece[1]) };
  ASSERT_FALSE(before[1].empty());
  vtkNew<vtkImageData> empty;
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputData(empty);
  w->SetFileName(index.c_str());
  w->SetNumberOfPieces(2);
  const std::string error = writeError(w);
  EXPECT_NE(error.find("no points"), std::string::npos) << error;
  EXPECT_TRUE(fileBytes(index) == before[0]) << "index";
  for (int p = 0; p < 2; ++p)
    EXPECT_TRUE(fileBytes(piece[p]) == before[1 + p]) << "piece " << p;
  EXPECT_EQ(readError(index), "");
  vtkNew<vtkPDictionaryVolumeReader> r;
  r->SetFileName(index.c_str());
  expectSameArrays(decoded(r), serialRoundTrip(img));
  for (const std::string& f : { index, piece[0], piece[1] })
    std::remove(f.c_str());
}

// A sparse volume that holds no volume (its producer failed or made nothing)
// given to the .lvdvp writer was "no input image or sparse volume", as if
// nothing were connected; the .lvdv, .vdb and .bv writers say "the input
// sparse volume holds no dictionary volume", and so does this one now. The old
// set stays byte for byte (oracle: the files' bytes before).
TEST(PVolumeIO, ASparseVolumeWithoutVolumeIsNamedAsSuch)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("novolume.lvdvp");
  writePieces(img, index, 2);
  const std::string piece0 = vtkPDictionaryVolumeWriter::PieceFilePath(index, 0);
  const std::string before[2] = { fileBytes(index), fileBytes(piece0) };
  vtkNew<vtkSparseDictionaryVolume> none;
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputData(none);
  w->SetFileName(index.c_str());
  w->SetNumberOfPieces(2);
  const std::string error = writeError(w);
  EXPECT_NE(error.find("the input sparse volume holds no dictionary volume"), std::string::npos) << error;
  EXPECT_TRUE(fileBytes(index) == before[0]) << "index";
  EXPECT_TRUE(fileBytes(piece0) == before[1]) << "piece 0";
  for (const std::string& f : { index, piece0, vtkPDictionaryVolumeWriter::PieceFilePath(index, 1) })
    std::remove(f.c_str());
}
