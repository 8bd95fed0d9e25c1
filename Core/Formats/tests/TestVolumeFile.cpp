// The volume file: bit-exact round trips (checked against shadow copies of
// what was written, not against the reader), partial reads, crash-safe saves
// and a table of malformed inputs. Malformed files are crafted with an
// independent little-endian patcher following docs/FORMAT.md, so the tests
// also pin the documented layout.
#include "ErrorTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/VolumeFile.h"

#include <gtest/gtest.h>
#include <zstd.h>

#include <cmath>
#include <cstdio>
#include <dirent.h>
#include <fstream>
#include <limits>
#include <random>
#include <sys/stat.h>
#include <unistd.h>

using namespace lvdif;

namespace
{
using Bytes = std::vector<std::uint8_t>;

// ---- layout constants from docs/FORMAT.md (restated on purpose) ----
constexpr std::size_t kHeader = 160, kFooter = 32, kEntry = 24;
constexpr std::size_t kDims = 16, kEdge = 88, kColorCount = 120, kMetaCount = 124, kMetaBytes = 128,
                      kChunkCount = 136, kVersion = 8, kHeaderSum = 152;

std::uint64_t getLe(const Bytes& b, std::size_t at, int n)
{
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v |= std::uint64_t(b[at + i]) << (8 * i);
  return v;
}
void putLe(Bytes& b, std::size_t at, std::uint64_t v, int n)
{
  for (int i = 0; i < n; ++i) b[at + i] = std::uint8_t(v >> (8 * i));
}
void resealHeader(Bytes& b) { putLe(b, kHeaderSum, checksum64(b.data(), kHeaderSum), 8); }
void patchHeader(Bytes& b, std::size_t at, std::uint64_t v, int n)
{
  putLe(b, at, v, n);
  resealHeader(b);
}
std::size_t tableOffset(const Bytes& b) { return static_cast<std::size_t>(getLe(b, b.size() - kFooter, 8)); }
void resealTable(Bytes& b)
{
  const std::size_t t = tableOffset(b);
  putLe(b, b.size() - kFooter + 16, checksum64(b.data() + t, b.size() - kFooter - t), 8);
}

Bytes toBytes(const DictionaryVolume& v, const VolumeFileWriteOptions& o = VolumeFileWriteOptions())
{
  MemorySink sink;
  writeVolume(v, sink, o);
  return sink.buffer();
}
std::unique_ptr<DictionaryVolume> fromBytes(const Bytes& b, const VolumeFileReadOptions& o = VolumeFileReadOptions())
{
  MemorySource src(b.data(), b.size());
  return readVolume(src, o);
}

/// Expects Error(CorruptData) whose message contains `needle`.
void expectCorrupt(const Bytes& b, const std::string& needle, const std::string& label)
{
  const std::string message = errortest::errorMessageOf([&] { fromBytes(b); }, ErrorCode::CorruptData);
  EXPECT_NE(message.find(needle), std::string::npos)
    << label << ": message '" << message << "' does not mention '" << needle << "'";
}

/// A volume with random voxels in some chunks, random uniform chunks and a
/// shadow copy of every voxel (the oracle).
struct RandomVolume
{
  std::unique_ptr<DictionaryVolume> volume;
  std::vector<Voxel> shadow;
  RandomVolume(Index3 dims, int edge, unsigned seed)
  {
    VolumeOptions o;
    o.dims = dims;
    o.chunkEdge = edge;
    o.origin = { -1.5, 2.25, 1e-3 };
    o.spacing = { 0.5, 0.25, 3.0 };
    o.bandWidth = std::numeric_limits<float>::infinity();
    volume = std::make_unique<DictionaryVolume>(o);
    std::mt19937 rng(seed);
    for (int i = 0; i < 40; ++i)
      volume->colors().add(Rgba{ std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng()) });
    const auto ncol = static_cast<std::uint32_t>(volume->colors().size());
    shadow.assign(static_cast<size_t>(volume->voxelCount()), volume->outsideVoxel());
    for (std::int64_t id = 0; id < volume->chunkCount(); ++id)
    {
      const VoxelBox b = volume->chunkBox(id);
      const int kind = static_cast<int>(rng() % 3);
      const Voxel u{ SdfKey(rng()), ColorKey(rng() % ncol) };
      if (kind == 1)
        volume->fillChunk(id, u);
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          {
            Voxel v = kind == 1 ? u : volume->outsideVoxel();
            if (kind == 2)
            {
              v = Voxel{ SdfKey(rng()), ColorKey(rng() % ncol) };
              volume->set(x, y, z, v);
            }
            shadow[static_cast<size_t>(x + dims[0] * (y + dims[1] * z))] = v;
          }
    }
  }
};

void expectVoxelsEqual(const DictionaryVolume& v, const std::vector<Voxel>& shadow, const VoxelBox& box)
{
  const Index3 d = v.dims();
  std::int64_t bad = 0;
  for (std::int64_t z = box.lo[2]; z <= box.hi[2]; ++z)
    for (std::int64_t y = box.lo[1]; y <= box.hi[1]; ++y)
      for (std::int64_t x = box.lo[0]; x <= box.hi[0]; ++x)
        if (v.get(x, y, z) != shadow[static_cast<size_t>(x + d[0] * (y + d[1] * z))] && bad++ < 5)
          ADD_FAILURE() << "voxel (" << x << "," << y << "," << z << ") differs";
  EXPECT_EQ(bad, 0);
}

std::string tempPath(const std::string& name)
{
  const std::string dir = ::testing::TempDir() + "lvdif_vf_" + std::to_string(::getpid());
  ::mkdir(dir.c_str(), 0755);
  return dir + "/" + name;
}

Bytes readFile(const std::string& path)
{
  std::ifstream f(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

std::vector<std::string> listDir(const std::string& dir)
{
  std::vector<std::string> names;
  if (DIR* d = ::opendir(dir.c_str()))
  {
    while (dirent* e = ::readdir(d))
      if (e->d_name[0] != '.') names.push_back(e->d_name);
    ::closedir(d);
  }
  return names;
}

/// The small test file used by the malformed-input table.
Bytes smallFile()
{
  RandomVolume r({ 21, 13, 9 }, 8, 77); // 3 x 2 x 2 chunks
  VolumeFileWriteOptions o;
  o.metadata["name"] = "fuzz seed";
  return toBytes(*r.volume, o);
}
} // namespace

TEST(VolumeFile, ChecksumChangesOnEverySingleBitFlip)
{
  Bytes b(1021);
  std::mt19937 rng(1);
  for (auto& x : b) x = std::uint8_t(rng());
  const std::uint64_t h = checksum64(b.data(), b.size());
  for (std::size_t i = 0; i < b.size() * 8; ++i)
  {
    b[i / 8] ^= std::uint8_t(1u << (i % 8));
    ASSERT_NE(checksum64(b.data(), b.size()), h) << "bit " << i;
    b[i / 8] ^= std::uint8_t(1u << (i % 8));
  }
  const std::uint8_t ab[3] = { 'a', 'b', 0 };
  EXPECT_NE(checksum64(ab, 2), checksum64(ab, 3)); // trailing zero byte is not ignored
}

TEST(VolumeFile, RandomVolumeRoundTripIsBitExact)
{
  for (int edge : { 4, 16, 32 })
  {
    RandomVolume r({ 70, 45, 38 }, edge, 5u + unsigned(edge)); // not multiples of the chunk edge
    VolumeFileWriteOptions wo;
    wo.metadata = { { "name", "random" }, { "source mesh", "" }, { "params", std::string("a\0b=1", 5) } };
    const Bytes b = toBytes(*r.volume, wo);
    MemorySource src(b.data(), b.size());
    VolumeFileInfo info;
    auto v = readVolume(src, VolumeFileReadOptions(), nullInterrupter(), &info);
    expectVoxelsEqual(*v, r.shadow, v->bounds());
    EXPECT_TRUE(v->colors() == r.volume->colors());
    EXPECT_EQ(info.metadata, wo.metadata);
    EXPECT_EQ(v->options().origin, r.volume->options().origin);
    EXPECT_EQ(v->options().spacing, r.volume->options().spacing);
    EXPECT_EQ(v->options().chunkEdge, edge);
    EXPECT_TRUE(std::isinf(v->bandWidth()));
    EXPECT_EQ(info.fileBytes, b.size());
    EXPECT_GT(info.uniformChunks, 0);
  }
}

TEST(VolumeFile, AnalyticSphereWithPaintSavesAndLoadsExactly)
{
  VolumeOptions o;
  o.dims = { 97, 83, 71 };
  o.chunkEdge = 16;
  o.bandWidth = 6.0f;
  o.dictionary.stepB = 0.25; // non-default dictionary parameters travel too
  DictionaryVolume v(o);
  fillFromFunction(v, sphereSdf(48.3, 40.1, 35.7, 29.0));
  const ColorKey red = v.colors().add(Rgba{ 255, 0, 0, 255 }), blue = v.colors().add(Rgba{ 0, 0, 255, 128 });
  std::vector<Voxel> shadow(static_cast<size_t>(v.voxelCount()));
  for (std::int64_t z = 0; z < 71; ++z)
    for (std::int64_t y = 0; y < 83; ++y)
      for (std::int64_t x = 0; x < 97; ++x)
      {
        Voxel w = v.get(x, y, z);
        // the oracle of the SDF is the analytic function itself
        const float d = sphereSdf(48.3, 40.1, 35.7, 29.0)(double(x), double(y), double(z));
        ASSERT_EQ(w.sdf, v.encode(d));
        if (d < 2 && (x / 8 + y / 8 + z / 8) % 2 == 0)
        {
          w.color = (x + z) % 3 ? red : blue; // a checker paint on the shell
          v.set(x, y, z, w);
        }
        shadow[static_cast<size_t>(x + 97 * (y + 83 * z))] = w;
      }
  const std::string path = tempPath("sphere.lvdv");
  VolumeFileWriteOptions wo;
  wo.metadata["name"] = "sphere";
  saveVolume(v, path, wo);
  VolumeFileInfo info;
  auto back = loadVolume(path, VolumeFileReadOptions(), nullInterrupter(), &info);
  expectVoxelsEqual(*back, shadow, back->bounds());
  EXPECT_EQ(back->options().dictionary, o.dictionary);
  EXPECT_EQ(back->bandWidth(), 6.0f);
  EXPECT_TRUE(back->colors() == v.colors());
  EXPECT_EQ(info.metadata.at("name"), "sphere");
  EXPECT_LT(info.chunkCount - info.uniformChunks, info.chunkCount); // far chunks stayed one value
  EXPECT_EQ(back->takeDirtyChunks().size(), 0u);
  std::remove(path.c_str());
}

TEST(VolumeFile, PartialReadsMatchTheFullReadAndReadOnlyTheirChunks)
{
  RandomVolume r({ 70, 45, 38 }, 8, 11);
  const Bytes b = toBytes(*r.volume);
  const auto full = fromBytes(b);
  std::mt19937 rng(2);
  for (int trial = 0; trial < 20; ++trial)
  {
    VoxelBox box;
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t n = r.volume->dims()[a];
      std::int64_t p = rng() % n, q = rng() % n;
      box.lo[a] = std::min(p, q);
      box.hi[a] = std::max(p, q);
    }
    VolumeFileReadOptions ro;
    ro.wholeVolume = false;
    ro.region = box;
    MemorySource src(b.data(), b.size());
    auto part = readVolume(src, ro);
    expectVoxelsEqual(*part, r.shadow, box);
    // bytes read: header, footer, dictionaries, table and only the overlapping payloads
    std::uint64_t expected = b.size() - (tableOffset(b) - (kHeader + 4 * r.volume->colors().size() + 8));
    for (std::int64_t id : full->chunksInBox(box))
      expected += getLe(b, tableOffset(b) + kEntry * id + 8, 4);
    EXPECT_EQ(src.bytesRead(), expected) << "trial " << trial;
  }
  // a damaged chunk outside the region does not matter to a partial read
  Bytes damaged = b;
  const std::size_t t = tableOffset(b);
  std::int64_t last = -1;
  for (std::int64_t id = 0; id < full->chunkCount(); ++id)
    if (getLe(b, t + kEntry * id + 8, 4)) last = id;
  ASSERT_GE(last, 0);
  damaged[getLe(b, t + kEntry * last, 8)] ^= 0x40;
  expectCorrupt(damaged, "chunk " + std::to_string(last) + ": checksum", "damaged payload");
  VolumeFileReadOptions ro;
  ro.wholeVolume = false;
  ro.region = full->chunkBox(0);
  ASSERT_NE(last, 0);
  auto part = fromBytes(damaged, ro);
  expectVoxelsEqual(*part, r.shadow, ro.region);
}

TEST(VolumeFile, FailedSaveLeavesThePreviousFileByteIdentical)
{
  RandomVolume a({ 40, 40, 40 }, 8, 1), bvol({ 40, 40, 40 }, 8, 2);
  const std::string path = tempPath("crash.lvdv");
  saveVolume(*a.volume, path);
  const Bytes before = readFile(path);
  const std::uint64_t total = toBytes(*bvol.volume).size();
  // saveVolume is saveAtomically around writeVolume: the same save, through a
  // sink that fails (disk full, killed process) part way
  struct FailingSink : ByteSink
  {
    ByteSink& real;
    std::uint64_t failAt;
    FailingSink(ByteSink& r, std::uint64_t at)
      : real(r)
      , failAt(at)
    {
    }
    void write(const void* data, std::size_t n) override
    {
      if (this->Written + n > this->failAt)
        throw Error(ErrorCode::IoFailure, "injected failure: disk full");
      this->real.write(data, n);
      this->Written += n;
    }
  };
  for (std::uint64_t failAt : { std::uint64_t(0), std::uint64_t(100), total / 2, total - 1 })
  {
    SCOPED_TRACE(failAt);
    errortest::errorMessageOf(
      [&] {
        saveAtomically(path, [&](ByteSink& sink) {
          FailingSink failing(sink, failAt);
          writeVolume(*bvol.volume, failing, VolumeFileWriteOptions());
        });
      },
      ErrorCode::IoFailure);
    EXPECT_EQ(readFile(path), before) << "previous file changed after a failure at byte " << failAt;
    EXPECT_EQ(listDir(path.substr(0, path.rfind('/'))).size(), 1u) << "temporary file left behind";
  }
  // cancellation half way also keeps the previous file
  struct CancelLater : Interrupter
  {
    int calls = 0;
    void progress(double) override { ++calls; }
    bool wasInterrupted() const override { return calls >= 1; }
  } cancel;
  RandomVolume big({ 200, 100, 100 }, 8, 3); // several batches
  EXPECT_THROW(saveVolume(*big.volume, path, VolumeFileWriteOptions(), cancel), Error);
  EXPECT_EQ(readFile(path), before);
  // and a save that succeeds replaces it
  saveVolume(*bvol.volume, path);
  expectVoxelsEqual(*loadVolume(path), bvol.shadow, bvol.volume->bounds());
  std::remove(path.c_str());
}

TEST(VolumeFile, LoadReportsProgressHonoursCancelAndTheMemoryLimit)
{
  RandomVolume r({ 64, 64, 64 }, 8, 9);
  const Bytes b = toBytes(*r.volume);
  struct Recorder : Interrupter
  {
    double last = 0;
    bool stop = false;
    void progress(double f) override { last = f; }
    bool wasInterrupted() const override { return stop; }
  } rec;
  MemorySource s1(b.data(), b.size());
  readVolume(s1, VolumeFileReadOptions(), rec);
  EXPECT_EQ(rec.last, 1.0);
  rec.stop = true;
  MemorySource s2(b.data(), b.size());
  errortest::errorMessageOf([&] { readVolume(s2, VolumeFileReadOptions(), rec); }, ErrorCode::Cancelled);
  VolumeFileReadOptions small;
  small.memoryLimit = 200000; // the table fits, the expanded chunks do not
  errortest::errorMessageOf([&] { fromBytes(b, small); }, ErrorCode::OutOfMemory);
}

TEST(VolumeFile, WriterRefusesColourKeysMissingFromTheDictionary)
{
  VolumeOptions o;
  o.dims = { 8, 8, 8 };
  o.chunkEdge = 4;
  DictionaryVolume v(o);
  v.set(1, 2, 3, Voxel{ 100, 7 }); // only colour 0 exists
  MemorySink sink;
  EXPECT_THROW(writeVolume(v, sink), Error);
}

// ---- the malformed-input table (docs/FORMAT.md lists the same cases) ----

TEST(VolumeFileMalformed, TruncatedAtAnyOffset)
{
  const Bytes b = smallFile();
  ASSERT_NO_THROW(fromBytes(b));
  for (std::size_t n = 0; n < b.size(); n += (n < 400 ? 1 : 7))
  {
    const Bytes t(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n));
    const std::string needle = n < kHeader + kFooter ? "too short" : "footer";
    expectCorrupt(t, needle, "truncated to " + std::to_string(n));
  }
  Bytes longer = b;
  longer.push_back(0);
  expectCorrupt(longer, "footer", "one byte appended");
}

TEST(VolumeFileMalformed, FlippedBytesAnywhere)
{
  const Bytes b = smallFile();
  const std::size_t t = tableOffset(b);
  const std::size_t dictEnd = kHeader + getLe(b, kColorCount, 4) * 4 + getLe(b, kMetaBytes, 8) + 8;
  for (std::size_t i = 0; i < b.size(); i += (i >= dictEnd && i < t ? 11 : 1)) // every byte but the payload's
  {
    Bytes f = b;
    f[i] ^= 0x10;
    std::string needle;
    if (i < kHeader)
      needle = "header";
    else if (i < dictEnd)
      needle = "colour dictionary / metadata";
    else if (i < t)
      needle = ": checksum mismatch (payload";
    else if (i < b.size() - kFooter)
      needle = "chunk table";
    else if (i >= b.size() - kFooter + 16 && i < b.size() - kFooter + 24)
      needle = "chunk table: checksum"; // the table's checksum lives in the footer
    else
      needle = "footer";
    expectCorrupt(f, needle, "byte " + std::to_string(i) + " flipped");
  }
}

// `lvdif info` verifies a file without loading it: every damage the reader
// finds in a payload, verifyVolume finds too, with the reader's message,
// while readVolumeInfo (header, dictionaries, table) does not look there.
TEST(VolumeFileMalformed, VerifyFindsPayloadDamageLikeTheReader)
{
  const Bytes b = smallFile();
  {
    MemorySource src(b.data(), b.size());
    const VolumeFileInfo info = verifyVolume(src);
    EXPECT_EQ(src.bytesRead(), b.size()); // every stored chunk was read
    EXPECT_EQ(info.chunkCount, 12);
  }
  const std::size_t t = tableOffset(b);
  const std::size_t dictEnd = kHeader + getLe(b, kColorCount, 4) * 4 + getLe(b, kMetaBytes, 8) + 8;
  int damaged = 0;
  for (std::size_t i = dictEnd; i < t; i += 5)
  {
    Bytes f = b;
    f[i] ^= 0x01;
    SCOPED_TRACE("byte " + std::to_string(i));
    const std::string readError = errortest::errorMessageOf([&] { fromBytes(f); }, ErrorCode::CorruptData);
    MemorySource src(f.data(), f.size());
    EXPECT_NO_THROW(readVolumeInfo(src)) << "byte " << i;
    MemorySource again(f.data(), f.size());
    EXPECT_EQ(errortest::errorMessageOf([&] { verifyVolume(again); }, ErrorCode::CorruptData), readError);
    ++damaged;
  }
  EXPECT_GT(damaged, 10);
}

TEST(VolumeFileMalformed, CraftedHeadersAndTables)
{
  const Bytes b = smallFile();
  struct Case
  {
    const char* label;
    std::function<void(Bytes&)> patch;
    const char* needle;
  };
  const std::size_t t = tableOffset(b);
  // first compressed chunk entry
  std::size_t firstPacked = 0;
  for (std::size_t e = t; e < b.size() - kFooter; e += kEntry)
    if (getLe(b, e + 8, 4)) { firstPacked = e; break; }
  std::size_t firstUniform = 0;
  for (std::size_t e = t; e < b.size() - kFooter; e += kEntry)
    if (!getLe(b, e + 8, 4)) { firstUniform = e; break; }
  ASSERT_TRUE(firstPacked && firstUniform);
  const std::vector<Case> cases = {
    { "wrong magic", [](Bytes& f) { f[0] = 'X'; }, "magic" },
    { "future version", [](Bytes& f) { patchHeader(f, kVersion, 2, 4); }, "version 2" },
    { "big-endian tag", [](Bytes& f) { patchHeader(f, 12, 0x04030201u, 4); }, "big-endian" },
    { "zero dimension", [](Bytes& f) { patchHeader(f, kDims, 0, 8); }, "dimensions" },
    { "negative dimension", [](Bytes& f) { patchHeader(f, kDims + 8, std::uint64_t(-5), 8); }, "dimensions" },
    { "absurd dimensions", [](Bytes& f) {
       for (int a = 0; a < 3; ++a) putLe(f, kDims + 8 * a, 1u << 20, 8);
       putLe(f, kEdge, 4, 4);
       patchHeader(f, kChunkCount, std::uint64_t(1) << 54, 8); }, "does not fit" },
    { "chunk count mismatch", [](Bytes& f) { patchHeader(f, kChunkCount, 13, 8); }, "chunk count" },
    { "chunk edge not a power of two", [](Bytes& f) { patchHeader(f, kEdge, 24, 4); }, "chunk edge" },
    { "NaN spacing", [](Bytes& f) { patchHeader(f, 64, 0x7ff8000000000000ull, 8); }, "spacing" },
    { "origin near 1e308", [](Bytes& f) { patchHeader(f, 40, 0x7fe1ccf385ebc8a0ull, 8); }, "float vertices" },
    { "spacing near 1e308", [](Bytes& f) { patchHeader(f, 72, 0x7fe1ccf385ebc8a0ull, 8); }, "float vertices" },
    { "spacing 1e-300", [](Bytes& f) { patchHeader(f, 80, 0x01a56e1fc2f8f359ull, 8); }, "spacing >=" },
    { "negative band", [](Bytes& f) { patchHeader(f, 92, 0xbf800000u, 4); }, "band" },
    { "bad dictionary step", [](Bytes& f) { patchHeader(f, 104, 0, 8); }, "SDF dictionary" },
    // a band narrower than the dictionary's first step (0.001): it passed the header's check
    // and was the volume's InvalidArgument, "band width 0.0005 is below ...", naming no file part
    { "band below the dictionary's step", [](Bytes& f) { patchHeader(f, 92, 0x3a03126fu, 4); },
      "header: band width 0.0005 is below the distance dictionary's step of 0.001" },
    { "zero colours", [](Bytes& f) { patchHeader(f, kColorCount, 0, 4); }, "colour dictionary count" },
    { "65536 colours", [](Bytes& f) { patchHeader(f, kColorCount, 65536, 4); }, "colour dictionary count" },
    { "huge colour count", [](Bytes& f) { patchHeader(f, kColorCount, 0xffffffffu, 4); }, "colour dictionary count" },
    { "colours past the table", [](Bytes& f) { patchHeader(f, kColorCount, 60000, 4); }, "does not fit" },
    { "huge metadata", [](Bytes& f) { patchHeader(f, kMetaBytes, std::uint64_t(1) << 40, 8); }, "metadata" },
    { "metadata count too high", [](Bytes& f) { patchHeader(f, kMetaCount, 7, 4); }, "metadata: ends before" },
    { "unknown codec", [](Bytes& f) { patchHeader(f, 148, 9, 4); }, "codec" },
    { "table offset wrong", [](Bytes& f) { putLe(f, f.size() - kFooter, 200, 8); }, "does not fit" },
    { "file size wrong", [](Bytes& f) { putLe(f, f.size() - kFooter + 8, 5, 8); }, "footer" },
    { "chunk offset past the table", [=](Bytes& f) { putLe(f, firstPacked, t, 8); resealTable(f); }, "outside the payload" },
    { "chunk offset inside the header", [=](Bytes& f) { putLe(f, firstPacked, 3, 8); resealTable(f); }, "outside the payload" },
    { "chunk size huge", [=](Bytes& f) { putLe(f, firstPacked + 8, 0xffffffffu, 4); resealTable(f); }, "outside the payload" },
    { "uniform colour out of range", [=](Bytes& f) { putLe(f, firstUniform + 14, 999, 2); resealTable(f); }, "not in the colour dictionary" },
    { "payload checksum wrong", [=](Bytes& f) { f[firstPacked + 16] ^= 1; resealTable(f); }, "checksum mismatch" },
  };
  for (const Case& c : cases)
  {
    Bytes f = b;
    c.patch(f);
    expectCorrupt(f, c.needle, c.label);
  }
}

TEST(VolumeFileMalformed, ValidFramesWithBadContent)
{
  // Payloads whose checksum is right but whose content is not: a frame of
  // the wrong size, garbage that is not zstd, colour keys out of range.
  const Bytes b = smallFile();
  const std::size_t t = tableOffset(b);
  std::size_t entry = 0;
  for (std::size_t e = t; e < b.size() - kFooter; e += kEntry)
    if (getLe(b, e + 8, 4)) { entry = e; break; }
  const std::size_t edge = getLe(b, kEdge, 4), raw = edge * edge * edge * 4;
  auto withPayload = [&](const Bytes& payload) {
    // append the payload before the table, move the table and footer
    Bytes f(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(t));
    const std::size_t at = f.size();
    f.insert(f.end(), payload.begin(), payload.end());
    const std::size_t newTable = f.size();
    f.insert(f.end(), b.begin() + static_cast<std::ptrdiff_t>(t), b.end());
    const std::size_t e = newTable + (entry - t);
    putLe(f, e, at, 8);
    putLe(f, e + 8, payload.size(), 4);
    putLe(f, e + 16, checksum64(payload.data(), payload.size()), 8);
    putLe(f, f.size() - kFooter, newTable, 8);
    putLe(f, f.size() - kFooter + 8, f.size(), 8);
    resealTable(f);
    return f;
  };
  auto zstd = [](const Bytes& plain) {
    Bytes out(ZSTD_compressBound(plain.size()));
    out.resize(ZSTD_compress(out.data(), out.size(), plain.data(), plain.size(), 1));
    return out;
  };
  expectCorrupt(withPayload(zstd(Bytes(raw / 2, 0))), "does not declare the chunk size", "short frame");
  expectCorrupt(withPayload(Bytes(100, 0xab)), "does not declare", "not zstd");
  Bytes planes(raw, 0);
  planes[3 * raw / 4 + 5] = 0x7f; // high byte of one colour key
  expectCorrupt(withPayload(zstd(planes)), "not in the colour dictionary", "colour key out of range");
  ASSERT_NO_THROW(fromBytes(withPayload(zstd(Bytes(raw, 0))))); // the harness itself builds valid files
}

// Origins and spacings from tiny to huge: a volume is either refused, or every
// voxel's world position is finite in float (what mesh vertices are).
TEST(VolumeFileMalformed, GeometryIsRefusedOrFiniteInFloat)
{
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> e(-45, 45);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 2000; ++i)
  {
    VolumeOptions o;
    o.dims = { 8, 16, 4 };
    o.chunkEdge = 8;
    for (int a = 0; a < 3; ++a)
    {
      o.origin[a] = (rng() % 2 ? -1 : 1) * std::pow(10.0, e(rng));
      o.spacing[a] = std::pow(10.0, e(rng));
    }
    try
    {
      DictionaryVolume v(o);
      ++accepted;
      for (int a = 0; a < 3; ++a)
      {
        const float far = static_cast<float>(o.origin[a] + double(o.dims[a] - 1) * o.spacing[a]);
        const float step = static_cast<float>(o.spacing[a]);
        EXPECT_TRUE(std::isfinite(far) && std::isfinite(static_cast<float>(o.origin[a])));
        EXPECT_GT(step, 0.0f);
      }
    }
    catch (const Error& x)
    {
      ++refused;
      EXPECT_EQ(x.code(), ErrorCode::InvalidArgument);
      EXPECT_NE(std::string(x.what()).find("float vertices"), std::string::npos) << x.what();
    }
  }
  EXPECT_GT(accepted, 100);
  EXPECT_GT(refused, 100);
  for (double huge : { 1e308, -1e308, 1e31, std::numeric_limits<double>::infinity() })
  {
    VolumeOptions o;
    o.dims = { 8, 8, 8 };
    o.origin = { huge, 0, 0 };
    EXPECT_THROW(DictionaryVolume v(o), Error);
    o.origin = { 0, 0, 0 };
    o.spacing = { 1, std::fabs(huge), 1 };
    EXPECT_THROW(DictionaryVolume v(o), Error);
  }
}

// The rule protects the world coordinates of the voxels (origin + index x
// spacing, index 0 .. dims - 1): it counted |origin| + spacing x dims, so a grid
// around a mesh spanning [-4e29, 4e29] was refused although every voxel of it
// lies within +-4.2e29. Oracle: the coordinates of the first and last voxel,
// computed here, against the +-1e30 range; accepted exactly when both are in it.
TEST(VolumeFileMalformed, GeometryCountsTheVoxelsWorldCoordinatesExactly)
{
  VolumeOptions o;
  o.dims = { 128, 4, 4 };
  o.chunkEdge = 8;
  o.spacing = { 8.2e29 / 127, 1, 1 };
  o.origin = { -4.1e29, 0, 0 };
  EXPECT_EQ(DictionaryVolume::checkGeometry(o), "");
  EXPECT_NO_THROW(DictionaryVolume v(o));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.2e30, 1.2e30);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const double first = u(rng), lastWanted = u(rng);
    o.dims[0] = 2 + static_cast<std::int64_t>(rng() % 300);
    o.origin[0] = std::min(first, lastWanted);
    o.spacing[0] = (std::max(first, lastWanted) - o.origin[0]) / double(o.dims[0] - 1);
    if (!(o.spacing[0] >= DictionaryVolume::MinSpacing))
      continue;
    const double last = o.origin[0] + double(o.dims[0] - 1) * o.spacing[0];
    const bool inRange = std::fabs(o.origin[0]) <= 1e30 && std::fabs(last) <= 1e30;
    EXPECT_EQ(DictionaryVolume::checkGeometry(o).empty(), inRange) << o.origin[0] << " + " << o.spacing[0] << " x "
                                                                   << o.dims[0] - 1 << " = " << last;
    (inRange ? accepted : refused) += 1;
  }
  EXPECT_GT(accepted, 200);
  EXPECT_GT(refused, 200);
}

TEST(VolumeFile, CompressionLevelOutsideZstdsRangeIsRefusedBeforeAnyByte)
{
  // the one rule of every writer's level (the VTK writers check it before any work)
  EXPECT_NO_THROW(checkCompressionLevel(1));
  EXPECT_NO_THROW(checkCompressionLevel(19));
  RandomVolume a({ 20, 12, 9 }, 4, 3);
  const std::string path = tempPath("level.lvdv");
  saveVolume(*a.volume, path);
  const Bytes before = readFile(path);
  for (int level : { 0, 20, -3 })
  {
    VolumeFileWriteOptions o;
    o.compressionLevel = level;
    SCOPED_TRACE(level);
    EXPECT_EQ(errortest::errorMessageOf([&] { saveVolume(*a.volume, path, o); }, ErrorCode::InvalidArgument),
      "compression level must be a zstd level in [1, 19], not " + std::to_string(level));
    EXPECT_TRUE(readFile(path) == before) << level;
    EXPECT_EQ(errortest::errorMessageOf([&] { checkCompressionLevel(level, "CompressionLevel"); }, ErrorCode::InvalidArgument),
      "CompressionLevel must be a zstd level in [1, 19], not " + std::to_string(level));
  }
}
