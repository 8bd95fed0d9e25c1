// vtkImageToSparseVolume asked for pieces (pvbatch rank r of n; here
// UpdatePiece): each piece must be a block of the whole grid's chunks, so the
// pieces' partitions together are exactly the serial run's. Until session 27
// each rank's volume was its own image's, with its own chunk grid from its
// piece's first point (ParaView's Integrate Variables over 2 ranks differed
// from the serial run), or, where the source gave every rank the whole image,
// every rank held the whole volume. Oracle: the serial run of the same
// filter, partition by partition (world bounds and every point's value), and
// the dense image's own values at those points.
#include "vtkImageToSparseVolume.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkSparseVolumeToImage.h"
#include "vtkDictionaryVolumeToImage.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkCompositeDataIterator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageChangeInformation.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkSmartPointer.h"
#include "vtkTrivialProducer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace
{
using Key = std::array<long long, 6>; // a partition's world bounds, in 1/1024 units
using Partitions = std::map<Key, std::vector<float>>;

/// The partitions of `volume` with more than one point, by world bounds (a
/// piece's corner-point partitions only mark its box, they hold no cell).
void collect(vtkSparseDictionaryVolume* volume, Partitions& into, int& duplicates)
{
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(volume->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* image = vtkImageData::SafeDownCast(it->GetCurrentDataObject());
    if (!image || image->GetNumberOfPoints() < 2) continue;
    double b[6];
    image->GetBounds(b);
    Key k;
    for (int i = 0; i < 6; ++i) k[i] = std::llround(b[i] * 1024);
    vtkDataArray* sdf = image->GetPointData()->GetArray("sdf");
    std::vector<float> values;
    for (vtkIdType p = 0; sdf && p < sdf->GetNumberOfTuples(); ++p) values.push_back(static_cast<float>(sdf->GetTuple1(p)));
    duplicates += into.count(k) ? 1 : 0;
    into[k] = values;
  }
}

/// A non-cubic image with a non-zero whole extent, anisotropic spacing and an
/// origin off zero, whose float scalars cross zero; its source makes any sub-extent.
vtkSmartPointer<vtkAlgorithm> imageSource()
{
  vtkNew<vtkRTAnalyticSource> rt;
  rt->SetWholeExtent(-7, 53, 4, 43, 10, 62); // 61 x 40 x 53 points
  vtkNew<vtkImageShiftScale> shift;
  shift->SetInputConnection(rt->GetOutputPort());
  shift->SetShift(-160.0);
  shift->SetScale(0.1);
  shift->SetOutputScalarTypeToFloat();
  auto info = vtkSmartPointer<vtkImageChangeInformation>::New();
  info->SetInputConnection(shift->GetOutputPort());
  info->SetOutputSpacing(0.5, 0.25, 0.75);
  info->SetOutputOrigin(1.5, -2.0, 0.25);
  return info;
}

vtkSmartPointer<vtkImageToSparseVolume> toSparse(vtkAlgorithmOutput* image)
{
  auto f = vtkSmartPointer<vtkImageToSparseVolume>::New();
  f->SetInputConnection(image);
  f->SetChunkEdge(8);
  f->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS); // the source's scalars
  return f;
}

void checkPieces(vtkAlgorithmOutput* image, const char* what)
{
  vtkSmartPointer<vtkImageToSparseVolume> serial = toSparse(image);
  serial->Update();
  Partitions whole;
  int duplicates = 0;
  collect(vtkSparseDictionaryVolume::SafeDownCast(serial->GetOutputDataObject(0)), whole, duplicates);
  ASSERT_GT(whole.size(), 20u) << what;
  for (int pieces : { 2, 3, 5 })
  {
    Partitions together;
    duplicates = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      vtkSmartPointer<vtkImageToSparseVolume> f = toSparse(image);
      f->UpdatePiece(piece, pieces, 0);
      auto* out = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
      ASSERT_NE(out, nullptr);
      collect(out, together, duplicates);
    }
    EXPECT_EQ(duplicates, 0) << what << ", " << pieces << " pieces: partitions in two pieces";
    EXPECT_EQ(together.size(), whole.size()) << what << ", " << pieces << " pieces";
    int differ = 0;
    for (const auto& [k, values] : whole)
    {
      auto at = together.find(k);
      differ += at == together.end() || at->second != values ? 1 : 0;
    }
    EXPECT_EQ(differ, 0) << what << ", " << pieces << " pieces: partitions missing or with other values";
  }
}
} // namespace

TEST(vtkImageToSparseVolume, PiecesAreBlocksOfTheWholeGridsChunks)
{
  vtkSmartPointer<vtkAlgorithm> source = imageSource();
  checkPieces(source->GetOutputPort(), "a source of sub-extents");

  // an image that is the whole extent on every rank (a trivial producer)
  source->Update();
  vtkNew<vtkImageData> image;
  image->DeepCopy(source->GetOutputDataObject(0));
  vtkNew<vtkTrivialProducer> tp;
  tp->SetOutput(image);
  checkPieces(tp->GetOutputPort(), "the whole image on every piece");
}

// The oracle's oracle: the serial partitions hold the dense image's values.
TEST(vtkImageToSparseVolume, SerialPartitionsHoldTheImagesValues)
{
  vtkSmartPointer<vtkAlgorithm> source = imageSource();
  source->Update();
  auto* image = vtkImageData::SafeDownCast(source->GetOutputDataObject(0));
  vtkSmartPointer<vtkImageToSparseVolume> serial = toSparse(source->GetOutputPort());
  serial->Update();
  auto* out = vtkSparseDictionaryVolume::SafeDownCast(serial->GetOutputDataObject(0));
  const double band = serial->GetBandWidth();
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(out->NewIterator());
  int checked = 0, wrong = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* part = vtkImageData::SafeDownCast(it->GetCurrentDataObject());
    if (!part) continue;
    vtkDataArray* sdf = part->GetPointData()->GetArray("sdf");
    for (vtkIdType p = 0; sdf && p < part->GetNumberOfPoints(); ++p, ++checked)
    {
      double x[3];
      part->GetPoint(p, x);
      const vtkIdType q = image->FindPoint(x);
      const double want = std::max(-band, std::min(band, image->GetPointData()->GetScalars()->GetTuple1(q)));
      // within half the dictionary's coarsest step (0.1 voxel far from the surface)
      wrong += q < 0 || std::fabs(sdf->GetTuple1(p) - want) > 0.051 ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 1000);
  EXPECT_EQ(wrong, 0);
}

// Image To Sparse Volume of a large image ran with no progress between 0 and 1
// and ignored a cancel (ParaView's, or SetAbortExecute from an observer). Now
// progress over the chunks, and a cancel at the first report past 0 leaves no
// volume. Oracle: the same filter without the cancel holds the volume.
namespace
{
struct Progress
{
  std::vector<double> values;
  bool abortPastZero = false;
};
void onProgress(vtkObject* caller, unsigned long, void* client, void* call)
{
  auto* p = static_cast<Progress*>(client);
  const double v = *static_cast<double*>(call);
  p->values.push_back(v);
  if (p->abortPastZero && v > 0) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
}
} // namespace

TEST(vtkImageToSparseVolume, ReportsProgressAndHonoursACancel)
{
  vtkSmartPointer<vtkAlgorithm> source = imageSource();
  for (const bool cancel : { false, true })
  {
    Progress log;
    log.abortPastZero = cancel;
    vtkSmartPointer<vtkImageToSparseVolume> f = toSparse(source->GetOutputPort());
    vtkNew<vtkCallbackCommand> cb;
    cb->SetCallback(onProgress);
    cb->SetClientData(&log);
    f->AddObserver(vtkCommand::ProgressEvent, cb);
    f->Update();
    auto* out = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
    int within = 0;
    for (const double v : log.values) within += v > 0 && v < 1 ? 1 : 0;
    if (!cancel)
    {
      EXPECT_TRUE(out->HasVolume());
      EXPECT_GT(within, 10) << "progress between 0 and 1";
      EXPECT_EQ(log.values.back(), 1.0);
    }
    else
    {
      EXPECT_FALSE(out->HasVolume()) << "the cancelled filter's output";
      EXPECT_LT(within, 10) << "it stopped soon after the cancel";
    }
  }
}

// Sparse Volume To Image reported no progress at all and could not be
// cancelled. Now progress over the planes, and a cancel at the first report
// past 0 leaves an empty image (no points, no arrays: never a part-filled one).
// On a non-cubic grid of unequal spacing and a non-zero origin; oracle for
// the finished image: the Core volume's own voxel accessor and grid.
TEST(vtkSparseVolumeToImage, ReportsProgressAndHonoursACancel)
{
  lvdif::VolumeOptions o;
  o.dims = { 37, 90, 13 };
  o.chunkEdge = 8;
  o.origin = { -3.5, 2.0, 10.25 };
  o.spacing = { 0.5, 0.25, 2.0 };
  auto volume = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*volume, lvdif::sphereSdf(18, 45, 6, 9));
  // and vtkDictionaryVolumeToImage (a Core volume held by C++ code), which had neither either
  for (const bool sourceOfCoreVolume : { false, true })
  for (const bool cancel : { false, true })
  {
    vtkNew<vtkSparseDictionaryVolume> sparse;
    sparse->SetVolume(volume);
    vtkSmartPointer<vtkImageAlgorithm> f;
    if (sourceOfCoreVolume)
    {
      auto source = vtkSmartPointer<vtkDictionaryVolumeToImage>::New();
      source->SetVolume(volume);
      f = source;
    }
    else
    {
      auto toImage = vtkSmartPointer<vtkSparseVolumeToImage>::New();
      toImage->SetInputData(sparse);
      f = toImage;
    }
    SCOPED_TRACE(sourceOfCoreVolume ? "vtkDictionaryVolumeToImage" : "vtkSparseVolumeToImage");
    Progress log;
    log.abortPastZero = cancel;
    vtkNew<vtkCallbackCommand> cb;
    cb->SetCallback(onProgress);
    cb->SetClientData(&log);
    f->AddObserver(vtkCommand::ProgressEvent, cb);
    f->Update();
    vtkImageData* image = vtkImageData::SafeDownCast(f->GetOutputDataObject(0));
    int within = 0;
    for (const double v : log.values) within += v > 0 && v < 1 ? 1 : 0;
    if (!cancel)
    {
      EXPECT_GT(within, 5) << "progress between 0 and 1";
      ASSERT_FALSE(log.values.empty());
      EXPECT_EQ(log.values.back(), 1.0);
      int dims[3];
      image->GetDimensions(dims);
      ASSERT_EQ(dims[0], 37);
      ASSERT_EQ(dims[1], 90);
      ASSERT_EQ(dims[2], 13);
      double origin[3], spacing[3];
      image->GetOrigin(origin);
      image->GetSpacing(spacing);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(origin[a], o.origin[a]);
        EXPECT_EQ(spacing[a], o.spacing[a]);
      }
      vtkDataArray* sdf = image->GetPointData()->GetArray("sdf");
      ASSERT_NE(sdf, nullptr);
      vtkIdType wrong = 0, p = 0;
      for (int z = 0; z < 13; ++z)
        for (int y = 0; y < 90; ++y)
          for (int x = 0; x < 37; ++x, ++p)
            wrong += sdf->GetTuple1(p) == volume->sdf(x, y, z) ? 0 : 1;
      EXPECT_EQ(wrong, 0);
    }
    else
    {
      EXPECT_EQ(image->GetNumberOfPoints(), 0) << "the cancelled filter's output";
      EXPECT_EQ(image->GetPointData()->GetNumberOfArrays(), 0);
      EXPECT_LT(within, 3) << "it stopped at the plane after the cancel";
    }
  }
}
