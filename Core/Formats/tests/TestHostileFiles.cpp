// Hostile files and paths: saves keep the file's mode, write through symlinks,
// refuse non-regular targets and clean the temporaries of killed saves;
// readers refuse FIFOs, directories and devices without blocking, refuse a
// garbage multi-GB file after its first bytes, and report OBJ indices as
// written. Each refusal is one Error line; the old file stays byte-identical.
#include "lvdif/AnalyticFill.h"
#include "lvdif/ByteStream.h"
#include "lvdif/MeshFile.h"
#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include "FileTestUtil.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <cstdio>
#include <fcntl.h>
#include <fstream>
#include <random>
#include <sstream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace lvdif;

namespace
{
struct TempDir
{
  std::string path;
  TempDir()
  {
    char t[] = "/tmp/lvdif-hostile-XXXXXX";
    path = ::mkdtemp(t);
  }
  ~TempDir() { (void)std::system(("rm -rf '" + path + "'").c_str()); }
};

using filetest::slurp;

std::unique_ptr<DictionaryVolume> smallVolume(double r)
{
  VolumeOptions o;
  o.dims = { 24, 24, 24 };
  o.chunkEdge = 8;
  auto v = std::make_unique<DictionaryVolume>(o);
  fillFromFunction(*v, sphereSdf(12, 12, 12, r));
  return v;
}

std::string errorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    return e.what();
  }
  return "no error";
}

pid_t deadPid()
{
  const pid_t p = ::fork();
  if (p == 0)
    ::_exit(0);
  ::waitpid(p, nullptr, 0);
  return p;
}
} // namespace

TEST(HostileFiles, SaveKeepsTheModeAndWritesThroughSymlinks)
{
  TempDir d;
  const std::string file = d.path + "/v.lvdv", link = d.path + "/link.lvdv";
  for (mode_t mode : { 0600, 0640, 0604, 0755 })
  {
    saveVolume(*smallVolume(5), file);
    ASSERT_EQ(::chmod(file.c_str(), mode), 0);
    saveVolume(*smallVolume(6), file);
    struct stat st;
    ASSERT_EQ(::stat(file.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, mode);
  }
  ASSERT_EQ(::symlink("v.lvdv", link.c_str()), 0);
  saveVolume(*smallVolume(7), link);
  struct stat st;
  ASSERT_EQ(::lstat(link.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(loadVolume(file)->sdf(12, 12, 5), smallVolume(7)->sdf(12, 12, 5));
  // a dangling link: the target is created
  const std::string dangling = d.path + "/dangling.lvdv";
  ASSERT_EQ(::symlink("new.lvdv", dangling.c_str()), 0);
  saveVolume(*smallVolume(4), dangling);
  ASSERT_EQ(::lstat(dangling.c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(::stat((d.path + "/new.lvdv").c_str(), &st), 0);
}

TEST(HostileFiles, SaveRefusesNonRegularTargetsAndCleansKilledSaves)
{
  TempDir d;
  const std::string file = d.path + "/v.lvdv";
  saveVolume(*smallVolume(5), file);
  const std::string before = slurp(file);
  // temporaries of saves whose process is gone are removed; a live one stays
  std::vector<std::string> stale;
  for (int i = 0; i < 3; ++i)
  {
    stale.push_back(file + ".tmp-" + std::to_string(deadPid()) + "-abc12" + char('a' + i));
    std::ofstream(stale.back()) << "half a save";
  }
  // the by-name save keeps the extension on its temporary
  stale.push_back(file + ".tmp-" + std::to_string(deadPid()) + "-abc12z.lvdv");
  std::ofstream(stale.back()) << "half a save";
  const std::string live = file + ".tmp-" + std::to_string(::getpid()) + "-zzzzzz";
  std::ofstream(live) << "a save in progress";
  const std::string other = d.path + "/other.lvdv.tmp-" + std::to_string(deadPid()) + "-qqqqqq";
  std::ofstream(other) << "another file's";
  saveVolume(*smallVolume(5), file);
  for (const auto& s : stale)
    EXPECT_NE(::access(s.c_str(), F_OK), 0) << s;
  EXPECT_EQ(::access(live.c_str(), F_OK), 0);
  EXPECT_EQ(::access(other.c_str(), F_OK), 0);
  EXPECT_EQ(slurp(file), before);
  // a directory, a FIFO, a device: refused, nothing created beside them
  const std::string dir = d.path + "/dir.lvdv", fifo = d.path + "/fifo.lvdv";
  ASSERT_EQ(::mkdir(dir.c_str(), 0755), 0);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  for (const std::string& p : { dir, fifo, std::string("/dev/null") })
    EXPECT_NE(errorOf([&] { saveVolume(*smallVolume(5), p); }).find("not a regular file"), std::string::npos) << p;
}

TEST(HostileFiles, ReadersRefuseNonRegularFilesWithoutBlocking)
{
  TempDir d;
  const std::string fifo = d.path + "/f";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const auto t0 = std::chrono::steady_clock::now();
  for (const std::string& p : { fifo, d.path, std::string("/dev/zero") })
  {
    EXPECT_NE(errorOf([&] { loadVolume(p); }).find("not a regular file"), std::string::npos) << p;
    EXPECT_NE(errorOf([&] { loadMesh(p, MeshFormat::Obj); }).find("not a regular file"), std::string::npos) << p;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
}

TEST(HostileFiles, GarbageMultiGigabyteMeshesAreRefusedAfterTheHead)
{
  TempDir d;
  std::mt19937 rng(18);
  const std::uint64_t rss0 = residentMemoryBytes();
  const std::pair<MeshFormat, const char*> cases[] = { { MeshFormat::Ply, "missing the 'ply' magic line" },
    { MeshFormat::Stl, "neither a binary STL" }, { MeshFormat::Obj, "NUL byte" }, { MeshFormat::Off, "NUL byte" } };
  for (const auto& c : cases)
  {
    const std::string p = d.path + "/big";
    {
      std::ofstream f(p, std::ios::binary);
      std::string head(1000, '\0');
      for (char& ch : head)
        ch = static_cast<char>(rng() % 256);
      head[0] = 'x'; // never 'ply' or 'solid'
      f << head;
    }
    // 3 GiB, sparse: no disk used, and a reader that reads it whole needs 12 GiB
    ASSERT_EQ(::truncate(p.c_str(), off_t(3) << 30), 0);
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_NE(errorOf([&] { loadMesh(p, c.first); }).find(c.second), std::string::npos);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
  }
  if (rss0 > 0)
    EXPECT_LT(residentMemoryBytes(), rss0 + (64u << 20));
}

TEST(HostileFiles, ObjIndicesAreReportedAsWrittenAndVtVnChecked)
{
  std::mt19937 rng(4);
  auto read = [](const std::string& text) {
    MemorySource src(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
    return readMesh(src, MeshFormat::Obj, "t.obj");
  };
  for (int i = 0; i < 50; ++i)
  {
    const int n = 3 + static_cast<int>(rng() % 20), vt = static_cast<int>(rng() % 5), vn = static_cast<int>(rng() % 5);
    std::string obj;
    for (int k = 0; k < n; ++k)
      obj += "v " + std::to_string(k) + " " + std::to_string(k * k % 7) + " " + std::to_string(k % 3) + "\n";
    for (int k = 0; k < vt; ++k)
      obj += "vt 0.5 0.5\n";
    for (int k = 0; k < vn; ++k)
      obj += "vn 0 0 1\n";
    // in range: accepted
    const std::string good = "f 1" + std::string(vt ? "/1" : "") + " 2 " + std::to_string(n) + "\n";
    EXPECT_NO_THROW(read(obj + good)) << obj + good;
    const int bad = n + 1 + static_cast<int>(rng() % 5);
    EXPECT_NE(errorOf([&] { read(obj + "f 1 2 " + std::to_string(bad) + "\n"); })
                .find("vertex index " + std::to_string(bad) + " out of range: " + std::to_string(n) + " vertices"),
      std::string::npos);
    EXPECT_NE(errorOf([&] { read(obj + "f 1 2 -" + std::to_string(bad) + "\n"); })
                .find("vertex index -" + std::to_string(bad) + " out of range"),
      std::string::npos);
    EXPECT_NE(errorOf([&] { read(obj + "f 1/" + std::to_string(vt + 1) + " 2 3\n"); })
                .find("texture coordinate index " + std::to_string(vt + 1) + " out of range"),
      std::string::npos);
    EXPECT_NE(errorOf([&] { read(obj + "f 1//" + std::to_string(vn + 1) + " 2 3\n"); })
                .find("normal index " + std::to_string(vn + 1) + " out of range"),
      std::string::npos);
    if (vt > 0 && vn > 0)
      EXPECT_NO_THROW(read(obj + "f 1/1/1 2/" + std::to_string(vt) + "/" + std::to_string(vn) + " 3//1\n"));
  }
  EXPECT_NE(errorOf([&] { read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n"); }).find("bad face corner"), std::string::npos);
}

TEST(HostileFiles, SaveByNameChecksTheWriterAndKeepsTheOldFile)
{
  TempDir d;
  const std::string file = d.path + "/m.ply";
  std::ofstream(file) << "old";
  ASSERT_EQ(::chmod(file.c_str(), 0600), 0);
  // a writer that writes nothing, and one that throws: the old file stays
  EXPECT_NE(errorOf([&] { saveAtomicallyByName(file, [](const std::string&) {}); }).find("produced nothing"),
    std::string::npos);
  EXPECT_NE(errorOf([&] { saveAtomicallyByName(file, [](const std::string&) { throw Error(ErrorCode::IoFailure, "x"); }); }),
    "no error");
  EXPECT_EQ(slurp(file), "old");
  std::string seen;
  saveAtomicallyByName(file, [&](const std::string& tmp) {
    seen = tmp;
    std::ofstream(tmp) << "new";
  });
  EXPECT_EQ(slurp(file), "new");
  EXPECT_EQ(seen.substr(seen.size() - 4), ".ply"); // writers that append their extension
  struct stat st;
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  // requireWritable: before any work
  EXPECT_NE(errorOf([&] { requireWritable("/nonexistent_dir/x.ply"); }).find("does not exist"), std::string::npos);
  EXPECT_NE(errorOf([&] { requireWritable(d.path); }).find("not a regular file"), std::string::npos);
  EXPECT_EQ(errorOf([&] { requireWritable(d.path + "/new.ply"); }), "no error");
  // a file where a folder should be is named as such (it said "the folder 'F' does not exist")
  EXPECT_EQ(errorOf([&] { requireWritable(file + "/x.ply"); }),
    "cannot write '" + file + "/x.ply': '" + file + "' is a file, not a folder");
  EXPECT_EQ(errorOf([&] { requireWritable(file + "/sub/x.ply"); }),
    "cannot write '" + file + "/sub/x.ply': '" + file + "' is a file, not a folder");
  EXPECT_EQ(errorOf([&] { requireWritable(d.path + "/no/x.ply"); }),
    "cannot write '" + d.path + "/no/x.ply': the folder '" + d.path + "/no' does not exist");
  // ... and when reading (it said "Not a directory")
  EXPECT_EQ(errorOf([&] { FileSource in(file + "/x.ply"); }),
    "cannot open '" + file + "/x.ply': '" + file + "' is a file, not a folder");
}
