// vtkPDictionaryVolumeWriter / vtkPDictionaryVolumeReader without MPI: one
// Write() of a serial run (no controller) writes the n pieces and the index,
// from an upstream that gives the whole image (the writer crops its pieces). Oracles: the serial
// vtkDictionaryVolumeWriter -> vtkDictionaryVolumeReader round trip of the
// same image (the distributed read must equal it exactly, every array), the
// analytic SDF (within the dictionary's quantisation), the piece files' sizes
// (the translator's extents), a sub-extent read that opens one piece only, and
// the error paths (missing piece, broken index). The reader gives the sparse
// volume: its whole read is decoded by vtkSparseVolumeToImage, and a piece read
// (UpdatePiece, as a pvbatch rank) must hold the serial values on every point of
// its chunks and open only the piece files overlapping them.
#include "PDictionaryVolumeTestUtil.h"

#include "vtkCompositeDataIterator.h"
#include "vtkDataArray.h"

#include <array>
#include <map>

using namespace pvio;


class PVolumeIO : public ::testing::TestWithParam<int>
{
};

TEST_P(PVolumeIO, DistributedWriteEqualsSerialRoundTrip)
{
  const int n = GetParam();
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkSmartPointer<vtkImageData> oracle = serialRoundTrip(img);
  const std::string index = tmpName("vol" + std::to_string(n) + ".lvdvp");
  writePieces(img, index, n);
  ASSERT_TRUE(vtkPDictionaryVolumeReader::CanReadFile(index.c_str()));

  // the piece files hold exactly the translator's extents
  int whole[6];
  img->GetExtent(whole);
  for (int p = 0; p < n; ++p)
  {
    int e[6];
    vtkPDictionaryVolumeWriter::PieceExtent(whole, p, n, e);
    const std::string pf = tmpName("vol" + std::to_string(n) + "_" + std::to_string(p) + ".lvdv");
    vtkNew<vtkDictionaryVolumeReader> pr;
    pr->SetFileName(pf.c_str());
    pr->UpdateInformation();
    int pw[6];
    pr->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), pw);
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(pw[2 * a + 1] + 1, e[2 * a + 1] - e[2 * a] + 1) << "piece " << p << " axis " << a;
  }

  vtkNew<vtkPDictionaryVolumeReader> r;
  r->SetFileName(index.c_str());
  vtkSmartPointer<vtkImageData> decodedAll = decoded(r);
  vtkImageData* out = decodedAll;
  EXPECT_EQ(r->GetPiecesRead(), n);
  EXPECT_TRUE(vtkSparseDictionaryVolume::SafeDownCast(r->GetOutputDataObject(0)) != nullptr);
  int e[6];
  out->GetExtent(e);
  for (int q = 0; q < 3; ++q) // the sparse volume's indices start at 0 ...
    EXPECT_EQ(e[2 * q + 1] - e[2 * q], whole[2 * q + 1] - whole[2 * q]);
  double p0[3], q0[3], s[3]; // ... at the same world positions
  out->GetPoint(0, p0);
  img->GetPoint(0, q0);
  for (int a = 0; a < 3; ++a)
    EXPECT_DOUBLE_EQ(p0[a], q0[a]);
  out->GetSpacing(s);
  EXPECT_DOUBLE_EQ(s[1], 0.5);
  // serial oracle: same values, every array (the serial reader gives 0-based indices)
  ASSERT_EQ(out->GetNumberOfPoints(), oracle->GetNumberOfPoints());
  for (const char* name : { "sdf", "rgba" })
  {
    vtkDataArray* a = out->GetPointData()->GetArray(name);
    vtkDataArray* b = oracle->GetPointData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    ASSERT_NE(b, nullptr) << name;
    ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents());
    long diff = 0;
    for (vtkIdType id = 0; id < a->GetNumberOfTuples(); ++id)
      for (int c = 0; c < a->GetNumberOfComponents(); ++c)
        diff += a->GetComponent(id, c) != b->GetComponent(id, c) ? 1 : 0;
    EXPECT_EQ(diff, 0) << name;
  }
  // analytic oracle near the surface (dictionary step 0.001 up to |d| 4)
  vtkDataArray* sdf = out->GetPointData()->GetArray("sdf");
  double worst = 0;
  for (int k = 0, id = 0; k < NZ; ++k)
    for (int j = 0; j < NY; ++j)
      for (int i = 0; i < NX; ++i, ++id)
        if (std::fabs(analytic(i, j, k)) < 3.9)
          worst = std::max(worst, std::fabs(sdf->GetTuple1(id) - analytic(i, j, k)));
  EXPECT_LT(worst, 0.0006);

  // a sub-extent inside the first piece opens one piece only and equals the whole read there
  int e0[6];
  vtkPDictionaryVolumeWriter::PieceExtent(whole, 0, n, e0);
  for (int a = 0; a < 3; ++a) // in the volume's indices (from 0)
  {
    e0[2 * a] -= whole[2 * a];
    e0[2 * a + 1] -= whole[2 * a];
  }
  int sub[6] = { e0[0] + 1, e0[0] + 5, e0[2] + 1, e0[2] + 4, e0[4] + 1, e0[4] + 3 };
  vtkNew<vtkPDictionaryVolumeReader> rs;
  rs->SetFileName(index.c_str());
  vtkSmartPointer<vtkImageData> so = decoded(rs, sub);
  EXPECT_EQ(rs->GetPiecesRead(), 1);
  int got[6];
  so->GetExtent(got);
  for (int q = 0; q < 6; ++q)
    EXPECT_EQ(got[q], sub[q]);
  for (int k = sub[4]; k <= sub[5]; ++k)
    for (int j = sub[2]; j <= sub[3]; ++j)
      for (int i = sub[0]; i <= sub[1]; ++i)
      {
        int ijk[3] = { i, j, k };
        EXPECT_EQ(so->GetPointData()->GetArray("sdf")->GetTuple1(so->ComputePointId(ijk)),
          sdf->GetTuple1(out->ComputePointId(ijk)));
      }

  for (int p = 0; p < n; ++p)
    std::remove(tmpName("vol" + std::to_string(n) + "_" + std::to_string(p) + ".lvdv").c_str());
  std::remove(index.c_str());
}

// A sparse volume written in pieces (cropped keys, nothing re-encoded) reads
// back exactly as the serial round trip of the same image.
TEST_P(PVolumeIO, SparseInputWritesThePiecesItsKeys)
{
  const int n = GetParam();
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkSmartPointer<vtkImageData> oracle = serialRoundTrip(img);
  vtkNew<vtkImageToSparseVolume> sparse; // the writer's default encoding
  sparse->SetInputData(img);
  const std::string index = tmpName("sparse" + std::to_string(n) + ".lvdvp");
  {
    vtkNew<vtkPDictionaryVolumeWriter> w; // serial: one Write() writes every piece
    w->SetController(nullptr);
    w->SetInputConnection(sparse->GetOutputPort());
    w->SetFileName(index.c_str());
    w->SetNumberOfPieces(n);
    ASSERT_TRUE(w->Write());
  }
  vtkNew<vtkPDictionaryVolumeReader> r;
  r->SetFileName(index.c_str());
  vtkSmartPointer<vtkImageData> out = decoded(r);
  ASSERT_EQ(out->GetNumberOfPoints(), oracle->GetNumberOfPoints());
  // the sparse volume's indices start at 0: the same world positions
  double p0[3], q0[3];
  out->GetPoint(0, p0);
  img->GetPoint(0, q0);
  for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(p0[a], q0[a]);
  expectSameArrays(out, oracle);
}

// Read as pvbatch ranks do (piece p of m, m = 1..4, from files written by n
// pieces): a piece holds its block of storage chunks (the ownership rule of
// vtkDictionaryVolumeReader), equal to the serial values on every point of its
// chunks and of the layer shared with the next ones, opens only the piece files
// overlapping them, and the pieces' chunk blocks tile the chunk grid.
TEST_P(PVolumeIO, PiecesHoldTheirChunksOnly)
{
  const int n = GetParam();
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkSmartPointer<vtkImageData> oracle = serialRoundTrip(img);
  const std::string index = tmpName("pieces" + std::to_string(n) + ".lvdvp");
  writePieces(img, index, n);
  vtkFloatArray* osdf = vtkFloatArray::SafeDownCast(oracle->GetPointData()->GetArray("sdf"));
  vtkUnsignedCharArray* orgba = vtkUnsignedCharArray::SafeDownCast(oracle->GetPointData()->GetArray("rgba"));
  ASSERT_TRUE(osdf && orgba);
  for (int m = 1; m <= 4; ++m)
  {
    std::int64_t ownedChunks = 0, chunkTotal = 0;
    int emptyPieces = 0;
    for (int p = 0; p < m; ++p)
    {
      vtkNew<vtkPDictionaryVolumeReader> r;
      r->SetFileName(index.c_str());
      r->UpdatePiece(p, m, 0);
      auto* v = vtkSparseDictionaryVolume::SafeDownCast(r->GetOutputDataObject(0));
      ASSERT_TRUE(v != nullptr);
      if (!v->HasVolume())
      {
        // a piece the chunk grid leaves without chunks (m > chunk blocks): nothing read
        EXPECT_EQ(r->GetPiecesRead(), 0) << "piece " << p << " of " << m;
        ++emptyPieces;
        continue;
      }
      const lvdif::DictionaryVolume& vol = *v->GetVolume();
      chunkTotal = vol.chunkCount();
      int owned[6];
      v->GetOwnedChunks(owned);
      ownedChunks += std::int64_t(owned[1] - owned[0] + 1) * (owned[3] - owned[2] + 1) * (owned[5] - owned[4] + 1);
      // the points of its chunks and of the shared layer, in the volume's indices
      lvdif::VoxelBox box;
      for (int a = 0; a < 3; ++a)
      {
        box.lo[a] = std::int64_t(owned[2 * a]) * vol.chunkEdge();
        box.hi[a] = std::min<std::int64_t>(std::int64_t(owned[2 * a + 1] + 1) * vol.chunkEdge(), vol.dims()[a] - 1);
      }
      long wrong = 0;
      for (std::int64_t z = box.lo[2]; z <= box.hi[2]; ++z)
        for (std::int64_t y = box.lo[1]; y <= box.hi[1]; ++y)
          for (std::int64_t x = box.lo[0]; x <= box.hi[0]; ++x)
          {
            const vtkIdType id = x + NX * (y + NY * z);
            const lvdif::Voxel vx = vol.get(x, y, z);
            const lvdif::Rgba c = vol.colors()[vx.color];
            unsigned char oc[4];
            orgba->GetTypedTuple(id, oc);
            wrong += vol.decode(vx.sdf) != osdf->GetValue(id) || c.r != oc[0] || c.g != oc[1] || c.b != oc[2] || c.a != oc[3];
          }
      EXPECT_EQ(wrong, 0) << "piece " << p << " of " << m << " read from " << n << " files";
      // it opened exactly the piece files its points overlap
      int whole[6], expected = 0;
      img->GetExtent(whole);
      for (int q = 0; q < n; ++q)
      {
        int e[6];
        vtkPDictionaryVolumeWriter::PieceExtent(whole, q, n, e);
        bool overlaps = true;
        for (int a = 0; a < 3; ++a)
          overlaps = overlaps && e[2 * a] - whole[2 * a] <= box.hi[a] && e[2 * a + 1] - whole[2 * a] >= box.lo[a];
        expected += overlaps ? 1 : 0;
      }
      EXPECT_EQ(r->GetPiecesRead(), expected) << "piece " << p << " of " << m;
      if (m > 1)
        EXPECT_LT(box.voxelCount(), std::int64_t(NX) * NY * NZ) << "piece " << p << " of " << m;
    }
    EXPECT_EQ(ownedChunks, chunkTotal) << m << " pieces"; // disjoint blocks (PieceChunks) that tile the grid
    EXPECT_LT(emptyPieces, m);
  }
  for (int p = 0; p < n; ++p)
    std::remove(tmpName("pieces" + std::to_string(n) + "_" + std::to_string(p) + ".lvdv").c_str());
  std::remove(index.c_str());
}

// Read as pvbatch ranks do, the pieces' partitions together are exactly the
// serial read's. Each piece held its chunks and only the shared layer of points
// of the next chunks (the rest of those chunks left outside), so a chunk deep
// inside next to a cut got a partition the serial read has not: ParaView's
// Integrate Variables over 2 ranks of a .lvdvp gave 52,832 for the serial
// 43,264 (the .lvdv reader, which loads the next chunks whole, was right).
// Oracle: the serial read's partitions (world bounds and every point's value).
TEST(PVolumeIO, PiecesPartitionsAreTheSerialReadsOnes)
{
  // a sphere large enough for chunks of 8 wholly inside the band (uniform -8)
  vtkSmartPointer<vtkImageData> img = makeSdfImage({ -4, 56, 2, 45, 0, 52 }, { 1.0, -0.5, 2.0 }, { 0.5, 0.25, 0.75 },
    [](int i, int j, int k) {
      const double dx = i - 26.0, dy = j - 24.0, dz = k - 26.0;
      return std::sqrt(dx * dx + dy * dy + dz * dz) - 20.0;
    },
    [](int, int, int) { return std::array<unsigned char, 4>{ 9, 8, 7, 255 }; });
  const std::string index = tmpName("partitions.lvdvp");
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputData(img);
  w->SetFileName(index.c_str());
  w->SetChunkEdge(8);
  w->SetNumberOfPieces(2);
  ASSERT_TRUE(w->Write());
  using Key = std::array<long long, 6>;
  auto collect = [](vtkSparseDictionaryVolume* v, std::map<Key, std::vector<float>>& into, int& twice) {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(v->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      auto* part = vtkImageData::SafeDownCast(it->GetCurrentDataObject());
      if (!part || part->GetNumberOfPoints() < 2) continue; // a piece's corner points only mark its box
      double b[6];
      part->GetBounds(b);
      Key k;
      for (int i = 0; i < 6; ++i) k[i] = std::llround(b[i] * 1024);
      vtkDataArray* sdf = part->GetPointData()->GetArray("sdf");
      std::vector<float> values;
      for (vtkIdType q = 0; sdf && q < sdf->GetNumberOfTuples(); ++q) values.push_back(static_cast<float>(sdf->GetTuple1(q)));
      twice += into.count(k) ? 1 : 0;
      into[k] = values;
    }
  };
  std::map<Key, std::vector<float>> serial;
  int twice = 0;
  {
    vtkNew<vtkPDictionaryVolumeReader> r;
    r->SetFileName(index.c_str());
    r->Update();
    collect(vtkSparseDictionaryVolume::SafeDownCast(r->GetOutputDataObject(0)), serial, twice);
  }
  ASSERT_GT(serial.size(), 50u);
  for (int m : { 2, 3, 4 })
  {
    std::map<Key, std::vector<float>> together;
    twice = 0;
    for (int p = 0; p < m; ++p)
    {
      vtkNew<vtkPDictionaryVolumeReader> r;
      r->SetFileName(index.c_str());
      r->UpdatePiece(p, m, 0);
      collect(vtkSparseDictionaryVolume::SafeDownCast(r->GetOutputDataObject(0)), together, twice);
    }
    EXPECT_EQ(twice, 0) << m << " pieces: a partition in two pieces";
    EXPECT_EQ(together.size(), serial.size()) << m << " pieces";
    int differ = 0;
    for (const auto& [k, values] : serial)
    {
      const auto at = together.find(k);
      differ += at == together.end() || at->second != values ? 1 : 0;
    }
    EXPECT_EQ(differ, 0) << m << " pieces: partitions missing or with other values";
  }
  for (int p = 0; p < 2; ++p)
    std::remove(vtkPDictionaryVolumeWriter::PieceFilePath(index, p).c_str());
  std::remove(index.c_str());
}

// The reader's progress over a set of 3 pieces went to 1 at each piece file's
// load and back to 0.003 at its copy, so an observer that cancels at "done"
// (or a progress bar) saw the read end three times. Now it only goes forward
// and reaches 1 once, at the end; the volume is the one written.
TEST(PVolumeIO, ReadProgressGoesForwardToOneOnce)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("progress.lvdvp");
  writePieces(img, index, 3);
  std::vector<double> values;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&values);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(call));
  });
  vtkNew<vtkPDictionaryVolumeReader> r;
  r->SetFileName(index.c_str());
  r->AddObserver(vtkCommand::ProgressEvent, onProgress);
  expectSameArrays(decoded(r), serialRoundTrip(img));
  ASSERT_GE(values.size(), 3u);
  int backwards = 0, ones = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    backwards += i > 0 && values[i] < values[i - 1] ? 1 : 0;
    ones += values[i] >= 1.0 ? 1 : 0;
  }
  EXPECT_EQ(backwards, 0) << "progress went back";
  EXPECT_EQ(values.back(), 1.0);
  EXPECT_GT(static_cast<int>(values.size()) - ones, 10) << "progress below 1 on the way";
  for (int p = 0; p < 3; ++p)
    std::remove(vtkPDictionaryVolumeWriter::PieceFilePath(index, p).c_str());
  std::remove(index.c_str());
}

INSTANTIATE_TEST_SUITE_P(Pieces, PVolumeIO, ::testing::Values(1, 2, 3, 4));

TEST(PVolumeIO, ErrorsAreReported)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("err.lvdvp");
  writePieces(img, index, 2);
  vtkNew<vtkPDictionaryVolumeReader> r;
  r->GlobalWarningDisplayOff();
  r->SetFileName(index.c_str());

  // a missing piece file
  const std::string p1 = tmpName("err_1.lvdv");
  std::rename(p1.c_str(), (p1 + ".away").c_str());
  r->Modified();
  r->Update();
  EXPECT_EQ(voxels(r), 0);
  std::rename((p1 + ".away").c_str(), p1.c_str());
  r->Modified();
  r->Update();
  EXPECT_EQ(voxels(r), NX * NY * NZ);

  // broken indices: unknown key, piece outside the whole extent, wrong count, wrong magic
  const char* broken[] = {
    "LVDIF-PVOLUME 1\nwhole_extent 0 9 0 9 0 9\norigin 0 0 0\nspacing 1 1 1\nbogus 3\n",
    "LVDIF-PVOLUME 1\nwhole_extent 0 9 0 9 0 9\norigin 0 0 0\nspacing 1 1 1\npieces 1\npiece 0 9 0 9 0 12 x.lvdv\n",
    "LVDIF-PVOLUME 1\nwhole_extent 0 9 0 9 0 9\norigin 0 0 0\nspacing 1 1 1\npieces 2\npiece 0 9 0 9 0 9 x.lvdv\n",
    "LVDIF-PVOLUME 2\nwhole_extent 0 9 0 9 0 9\norigin 0 0 0\nspacing 1 1 1\npieces 1\npiece 0 9 0 9 0 9 x.lvdv\n",
    "LVDIFVOL\n",
  };
  const std::string bad = tmpName("bad.lvdvp");
  for (const char* text : broken)
  {
    std::ofstream(bad) << text;
    vtkNew<vtkPDictionaryVolumeReader> b;
    b->GlobalWarningDisplayOff();
    b->SetFileName(bad.c_str());
    b->Update();
    EXPECT_EQ(voxels(b), 0) << text;
  }
  std::remove(bad.c_str());
  std::remove(index.c_str());
  std::remove(tmpName("err_0.lvdv").c_str());
  std::remove(p1.c_str());
}

// reader of a damaged file -> the distributed writer: Write() says it failed
// (it answered 1, nothing written) and the index written over survives byte
// for byte; the same rule as the single-file writers (vtkLVDIFVolumeWriter).
TEST(PVolumeIO, WriteFailsWhenTheInputFailsUpstream)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const std::string index = tmpName("upstream.lvdvp"), damaged = tmpName("upstream_damaged.lvdv");
  writePieces(img, index, 1);
  {
    vtkNew<vtkDictionaryVolumeWriter> w;
    w->SetInputData(img);
    w->SetFileName(damaged.c_str());
    ASSERT_EQ(w->Write(), 1);
  }
  ASSERT_EQ(::truncate(damaged.c_str(), 300), 0);
  auto bytes = [](const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  const std::string before = bytes(index);
  vtkNew<vtkDictionaryVolumeReader> reader;
  reader->GlobalWarningDisplayOff();
  reader->SetFileName(damaged.c_str());
  vtkNew<vtkPDictionaryVolumeWriter> writer;
  writer->SetInputConnection(reader->GetOutputPort());
  writer->SetFileName(index.c_str());
  EXPECT_EQ(writer->Write(), 0);
  EXPECT_EQ(bytes(index), before);
  std::remove(damaged.c_str());
  std::remove(index.c_str());
  std::remove(tmpName("upstream_0.lvdv").c_str());
}

// A serial run with NumberOfPieces 2 (no controller, Piece left at 0): it wrote
// an index of 2 pieces and only piece 0, without a word (the reader then failed
// on the missing piece). Now every piece is written; oracle: the serial
// round trip of the same image (image input) and of the same sparse volume.
// A piece file that cannot be written is refused before anything is written:
// the old index stays byte for byte, no piece is made.
TEST(PVolumeIO, SerialRunWritesEveryPiece)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkSmartPointer<vtkImageData> oracle = serialRoundTrip(img);
  vtkNew<vtkImageToSparseVolume> sparse;
  sparse->SetInputData(img);
  for (const bool sparseInput : { false, true })
  {
    const std::string index = tmpName(std::string("serial2") + (sparseInput ? "s" : "i") + ".lvdvp");
    vtkNew<vtkPDictionaryVolumeWriter> w;
    w->SetController(nullptr);
    if (sparseInput)
      w->SetInputConnection(sparse->GetOutputPort());
    else
      w->SetInputData(img);
    w->SetFileName(index.c_str());
    w->SetNumberOfPieces(2);
    ASSERT_TRUE(w->Write()) << (sparseInput ? "sparse" : "image");
    for (int p = 0; p < 2; ++p)
      EXPECT_TRUE(std::ifstream(vtkPDictionaryVolumeWriter::PieceFilePath(index, p)).good()) << "piece " << p;
    vtkNew<vtkPDictionaryVolumeReader> r;
    r->SetFileName(index.c_str());
    vtkSmartPointer<vtkImageData> out = decoded(r);
    EXPECT_EQ(r->GetPiecesRead(), 2);
    ASSERT_EQ(out->GetNumberOfPoints(), oracle->GetNumberOfPoints());
    expectSameArrays(out, oracle);
    for (int p = 0; p < 2; ++p)
      std::remove(vtkPDictionaryVolumeWriter::PieceFilePath(index, p).c_str());
    std::remove(index.c_str());
  }

  // piece 1's file is a folder: refused before writing, the old index intact
  const std::string index = tmpName("serial2old.lvdvp");
  {
    std::ofstream old(index);
    old << "old index\n";
  }
  const std::string piece0 = vtkPDictionaryVolumeWriter::PieceFilePath(index, 0);
  const std::string piece1 = vtkPDictionaryVolumeWriter::PieceFilePath(index, 1);
  std::remove(piece0.c_str());
  ASSERT_EQ(::mkdir(piece1.c_str(), 0755), 0);
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputData(img);
  w->SetFileName(index.c_str());
  w->SetNumberOfPieces(2);
  struct Errors
  {
    int count = 0;
    std::string text;
  } errors;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* e = static_cast<Errors*>(client);
    ++e->count;
    e->text += static_cast<const char*>(call);
  });
  w->AddObserver(vtkCommand::ErrorEvent, onError);
  w->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, onError);
  vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on (other tests turn it off)
  EXPECT_EQ(w->Write(), 0);
  EXPECT_EQ(errors.count, 1) << errors.text;
  EXPECT_NE(errors.text.find(piece1), std::string::npos) << errors.text;
  std::ifstream in(index);
  const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "old index\n");
  EXPECT_FALSE(std::ifstream(piece0).good()) << "piece 0 written before the refusal";
  ::rmdir(piece1.c_str());
  std::remove(index.c_str());
}
