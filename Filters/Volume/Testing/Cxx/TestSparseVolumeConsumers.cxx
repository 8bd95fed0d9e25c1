// Consumers of the sparse volume that keep the partitions' pointers: VTK's
// vtkCompositeDataSet::GetDataSets and vtkArrayCalculator (ParaView's
// Calculator) collect every leaf before they use one. Until session 26 the
// iterator released each decoded partition at its next step and these read
// freed memory (a segmentation fault). Oracle: the Core volume's own voxel
// accessor (DictionaryVolume::sdf), at every point of every partition.
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"

#include "vtkArrayCalculator.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkExtractVOI.h"
#include "vtkSparseVolumeToImage.h"
#include "vtkPartitionedDataSet.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStringOutputWindow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace
{
/// Two spheres on a non-cubic grid with chunk edge 8: many partitions.
std::shared_ptr<lvdif::DictionaryVolume> twoSpheres()
{
  lvdif::VolumeOptions o;
  o.dims = { 45, 30, 21 };
  o.chunkEdge = 8;
  o.origin = { 1.0, -2.0, 0.25 };
  o.spacing = { 0.5, 0.25, 0.5 };
  auto v = std::make_shared<lvdif::DictionaryVolume>(o);
  const auto a = lvdif::sphereSdf(12, 14, 10, 7);
  const auto b = lvdif::sphereSdf(33, 15, 11, 6);
  lvdif::fillFromFunction(*v, [&](double x, double y, double z) { return std::min(a(x, y, z), b(x, y, z)); });
  return v;
}

/// Points of `leaf` whose array `name` is not factor x the Core volume's sdf at that point.
int mismatches(const lvdif::DictionaryVolume& v, vtkDataSet* leaf, const char* name, double factor)
{
  auto* image = vtkImageData::SafeDownCast(leaf);
  if (!image) return -1;
  vtkDataArray* values = image->GetPointData()->GetArray(name);
  if (!values) return -1;
  int ext[6];
  image->GetExtent(ext);
  int bad = 0;
  vtkIdType i = 0;
  for (int z = ext[4]; z <= ext[5]; ++z)
    for (int y = ext[2]; y <= ext[3]; ++y)
      for (int x = ext[0]; x <= ext[1]; ++x, ++i)
        bad += values->GetComponent(i, 0) != factor * static_cast<double>(v.sdf(x, y, z));
  return bad;
}

/// vtkArrayCalculator (ParaView's Calculator) on `input`, run: array "twice" = 2 x sdf.
vtkSmartPointer<vtkArrayCalculator> twiceTheSdf(vtkDataObject* input)
{
  vtkNew<vtkArrayCalculator> calculator;
  calculator->SetInputData(input);
  calculator->AddScalarArrayName("sdf");
  calculator->SetFunction("sdf*2");
  calculator->SetResultArrayName("twice");
  calculator->Update();
  return calculator.GetPointer();
}
}

// GetDataSets walks an iterator to the end, deletes it, and returns raw
// pointers: every one must still be the decoded partition it was.
TEST(SparseVolumeConsumers, GetDataSetsPointersStayValid)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  ASSERT_FALSE(sparse->GetReleasePartitionsAfterUse()) << "held is the default";
  const auto leaves = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse);
  ASSERT_EQ(leaves.size(), sparse->GetNumberOfPartitions());
  ASSERT_GT(leaves.size(), 10u);
  vtkIdType points = 0;
  for (std::size_t i = 0; i < leaves.size(); ++i)
  {
    EXPECT_EQ(mismatches(*volume, leaves[i], "sdf", 1.0), 0) << "partition " << i;
    points += leaves[i]->GetNumberOfPoints();
  }
  EXPECT_EQ(points, sparse->GetNumberOfPoints());
  // held: about GetPartitionBytes() (8 bytes a point), and a second walk hands out the same objects
  EXPECT_GE(sparse->GetHeldPartitionBytes(), sparse->GetPartitionBytes());
  EXPECT_LT(sparse->GetHeldPartitionBytes(), 1.2 * sparse->GetPartitionBytes() + 64 * 1024.0 * leaves.size());
  const auto again = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse);
  EXPECT_EQ(again, leaves);
  sparse->ReleaseDecodedPartitions();
  EXPECT_EQ(sparse->GetHeldPartitionBytes(), 0.0);
}

// vtkArrayCalculator (ParaView's Calculator) on the partitions: one output
// leaf per partition, each with 2 x the Core volume's sdf.
TEST(SparseVolumeConsumers, ArrayCalculatorRunsOnThePartitions)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  const auto calculator = twiceTheSdf(sparse);
  auto* out = vtkCompositeDataSet::SafeDownCast(calculator->GetOutputDataObject(0));
  ASSERT_NE(out, nullptr);
  const auto leaves = vtkCompositeDataSet::GetDataSets<vtkDataSet>(out);
  ASSERT_EQ(leaves.size(), sparse->GetNumberOfPartitions());
  vtkIdType points = 0;
  for (std::size_t i = 0; i < leaves.size(); ++i)
  {
    EXPECT_EQ(mismatches(*volume, leaves[i], "twice", 2.0), 0) << "partition " << i;
    points += leaves[i]->GetNumberOfPoints();
  }
  EXPECT_EQ(points, sparse->GetNumberOfPoints());
}

// Released after use: the iterator holds only the partition it stands on, and
// the object holds none after a walk; each leaf is right while it is current.
// The environment variable sets the default of new objects.
TEST(SparseVolumeConsumers, ReleasedAfterUseHoldsNothingAfterAWalk)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  sparse->ReleasePartitionsAfterUseOn();
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(sparse->NewIterator());
  unsigned int visited = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem(), ++visited)
  {
    EXPECT_EQ(mismatches(*volume, vtkDataSet::SafeDownCast(it->GetCurrentDataObject()), "sdf", 1.0), 0);
  }
  EXPECT_EQ(visited, sparse->GetNumberOfPartitions());
  EXPECT_EQ(sparse->GetHeldPartitionBytes(), 0.0);

  ::setenv("LVDIF_RELEASE_PARTITIONS", "1", 1);
  vtkNew<vtkSparseDictionaryVolume> released;
  ::unsetenv("LVDIF_RELEASE_PARTITIONS");
  vtkNew<vtkSparseDictionaryVolume> held;
  EXPECT_TRUE(released->GetReleasePartitionsAfterUse());
  EXPECT_FALSE(held->GetReleasePartitionsAfterUse());
}

// ParaView's post filter shallow-copies every output: the copy shares the
// held partitions (no second decode), and when the original's volume changes
// (VolumeModified) the copy keeps what it handed out.
TEST(SparseVolumeConsumers, ShallowCopiesShareTheHeldPartitions)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  vtkNew<vtkSparseDictionaryVolume> copy;
  copy->ShallowCopy(sparse);
  const auto leaves = vtkCompositeDataSet::GetDataSets<vtkDataSet>(copy);
  ASSERT_GT(leaves.size(), 0u);
  EXPECT_GT(sparse->GetHeldPartitionBytes(), 0.0) << "the copy's decoded partitions are the original's";
  EXPECT_EQ(vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse), leaves);
  sparse->VolumeModified();
  EXPECT_EQ(sparse->GetHeldPartitionBytes(), 0.0);
  EXPECT_GT(copy->GetHeldPartitionBytes(), 0.0);
  for (std::size_t i = 0; i < leaves.size(); ++i)
    EXPECT_EQ(mismatches(*volume, leaves[i], "sdf", 1.0), 0) << "partition " << i;
}

namespace
{
/// Sets LVDIF_MEMORY_LIMIT and captures VTK's messages while it lives; restores both.
class LimitAndMessages
{
public:
  explicit LimitAndMessages(const std::string& limit)
  {
    const char* old = std::getenv("LVDIF_MEMORY_LIMIT");
    this->HadOld = old != nullptr;
    this->Old = old ? old : "";
    this->Set(limit);
    this->Previous = vtkOutputWindow::GetInstance();
    vtkOutputWindow::SetInstance(this->Window);
  }
  ~LimitAndMessages()
  {
    vtkOutputWindow::SetInstance(this->Previous);
    if (this->HadOld)
      ::setenv("LVDIF_MEMORY_LIMIT", this->Old.c_str(), 1);
    else
      ::unsetenv("LVDIF_MEMORY_LIMIT");
  }
  void Set(const std::string& limit) { ::setenv("LVDIF_MEMORY_LIMIT", limit.c_str(), 1); }
  std::string Messages() { return this->Window->GetOutput(); }
  /// How many times `what` occurs in the messages so far.
  std::size_t Count(const std::string& what)
  {
    const std::string m = this->Messages();
    std::size_t n = 0;
    for (std::size_t at = m.find(what); at != std::string::npos; at = m.find(what, at + 1)) ++n;
    return n;
  }

private:
  bool HadOld = false;
  std::string Old;
  vtkNew<vtkStringOutputWindow> Window;
  vtkSmartPointer<vtkOutputWindow> Previous;
};

std::string bytesText(double bytes)
{
  return std::to_string(static_cast<long long>(bytes));
}
}

// Held partitions are all decoded or none: when they do not fit the memory
// limit (LVDIF_MEMORY_LIMIT) together, none is decoded (images without points
// stand for them, never null leaves) with one error for the volume, so no
// consumer (a writer, a copy) takes a part of the volume for all of it;
// released, they all decode again under a larger limit.
TEST(SparseVolumeConsumers, HeldPartitionsAreAllDecodedOrNone)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  const double all = sparse->GetPartitionBytes();
  std::vector<vtkDataSet*> leaves, again;
  std::string messages;
  std::size_t refusals = 0;
  {
    LimitAndMessages limit(bytesText(0.4 * all));
    leaves = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse, /*preserveNull=*/true);
    again = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse, true);
    refusals = limit.Count("none of the partitions not held is decoded");
    messages = limit.Messages();
  }
  ASSERT_EQ(leaves.size(), sparse->GetNumberOfPartitions());
  for (std::size_t i = 0; i < leaves.size(); ++i)
  {
    ASSERT_NE(leaves[i], nullptr) << "an undecoded partition is an image without points, not a null leaf";
    EXPECT_EQ(leaves[i]->GetNumberOfPoints(), 0) << "partition " << i << ": all or none";
  }
  EXPECT_EQ(sparse->GetHeldPartitionBytes(), 0.0);
  EXPECT_EQ(refusals, 1u) << messages;
  EXPECT_NE(messages.find("more than the limit"), std::string::npos) << messages;
  EXPECT_NE(messages.find("LVDIF_RELEASE_PARTITIONS=1"), std::string::npos) << messages;
  // vtkArrayCalculator asks to skip empty nodes and calls NewInstance on every leaf it gets
  {
    LimitAndMessages limit(bytesText(0.4 * all));
    const auto calculator = twiceTheSdf(sparse);
    std::size_t withPoints = 0;
    for (vtkDataSet* leaf : vtkCompositeDataSet::GetDataSets<vtkDataSet>(calculator->GetOutputDataObject(0)))
      withPoints += leaf->GetNumberOfPoints() > 0;
    EXPECT_EQ(withPoints, 0u) << "the calculator ran on no partition";
    EXPECT_EQ(limit.Count("none of the partitions not held is decoded"), 0u) << "reported once, not per consumer";
  }
  sparse->ReleaseDecodedPartitions();
  const auto whole = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse, true);
  ASSERT_EQ(whole.size(), leaves.size());
  for (std::size_t i = 0; i < whole.size(); ++i)
    EXPECT_EQ(mismatches(*volume, whole[i], "sdf", 1.0), 0) << "partition " << i;
}

// Non-virtual paths of vtkPartitionedDataSet read the tree itself, not this
// class's overrides: held partitions are the tree's leaves, decoded, once the
// volume's partitions are built. Until session 27 they were empty leaves
// (null through a base-class pointer, DeepCopy gave a plain dataset of null
// leaves, a consumer's own iterator skipped every one).
TEST(SparseVolumeConsumers, NonVirtualPathsSeeTheDecodedPartitions)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  const unsigned int n = sparse->GetNumberOfPartitions();
  ASSERT_GT(n, 10u);
  vtkPartitionedDataSet* base = sparse;
  ASSERT_EQ(base->GetNumberOfPartitions(), n);
  vtkIdType points = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    // vtkPartitionedDataSet::GetPartition is not virtual: the base class's, on the tree
    EXPECT_EQ(mismatches(*volume, base->vtkPartitionedDataSet::GetPartition(i), "sdf", 1.0), 0) << "partition " << i;
    if (base->vtkPartitionedDataSet::GetPartition(i)) points += base->vtkPartitionedDataSet::GetPartition(i)->GetNumberOfPoints();
  }
  EXPECT_EQ(points, sparse->GetNumberOfPoints()) << "the partitions' extents";

  vtkNew<vtkPartitionedDataSet> plain;
  plain->DeepCopy(sparse);
  ASSERT_EQ(plain->GetNumberOfPartitions(), n);
  for (unsigned int i = 0; i < n; ++i)
  {
    EXPECT_EQ(mismatches(*volume, plain->GetPartition(i), "sdf", 1.0), 0) << "deep copy, partition " << i;
    EXPECT_NE(plain->GetPartition(i), sparse->GetPartition(i)) << "a deep copy";
  }

  vtkNew<vtkDataObjectTreeIterator> it; // the consumer's own, not NewIterator's
  it->SetDataSet(sparse);
  it->SkipEmptyNodesOn();
  unsigned int visited = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem(), ++visited)
    EXPECT_EQ(mismatches(*volume, vtkDataSet::SafeDownCast(it->GetCurrentDataObject()), "sdf", 1.0), 0);
  EXPECT_EQ(visited, n);

  // a copy made as ParaView's post filter makes it (CopyStructure) gets the held leaves when asked
  vtkNew<vtkSparseDictionaryVolume> copy;
  copy->CopyStructure(sparse);
  ASSERT_EQ(copy->GetNumberOfPartitions(), n);
  vtkPartitionedDataSet* copyBase = copy;
  for (unsigned int i = 0; i < n; ++i)
    EXPECT_EQ(copyBase->vtkPartitionedDataSet::GetPartition(i), base->vtkPartitionedDataSet::GetPartition(i))
      << "shared, partition " << i;

  // released after use: the leaves stay empty (documented: unsafe for such
  // consumers) except a partition asked for by index, which is held
  vtkNew<vtkSparseDictionaryVolume> released;
  released->SetVolume(volume);
  released->ReleasePartitionsAfterUseOn();
  ASSERT_EQ(released->GetNumberOfPartitions(), n);
  vtkPartitionedDataSet* releasedBase = released;
  EXPECT_EQ(releasedBase->vtkPartitionedDataSet::GetPartition(1), nullptr);
  vtkDataSet* one = released->GetPartition(1);
  EXPECT_EQ(mismatches(*volume, one, "sdf", 1.0), 0);
  EXPECT_EQ(releasedBase->vtkPartitionedDataSet::GetPartition(1), one);
}

// One measure of held bytes: the images' own size (GetActualMemorySize), the
// one the memory limit is checked on. Until session 27 the check counted 8
// bytes a point (the point arrays only) while GetHeldPartitionBytes reported
// the images' size, so the held partitions went past the limit.
TEST(SparseVolumeConsumers, HeldBytesAreWhatTheLimitChecks)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  sparse->ReleasePartitionsAfterUseOn(); // GetPartition(i) decodes and holds one partition at a time
  const double all = sparse->GetPartitionBytes();
  const double cap = 0.4 * all;
  const unsigned int n = sparse->GetNumberOfPartitions();
  std::size_t decoded = 0, refused = 0;
  double sum = 0.0;
  {
    LimitAndMessages limit(bytesText(cap));
    for (unsigned int i = 0; i < n; ++i)
    {
      vtkDataSet* leaf = sparse->GetPartition(i);
      ASSERT_NE(leaf, nullptr);
      if (leaf->GetNumberOfPoints() == 0)
      {
        ++refused;
        continue;
      }
      ++decoded;
      sum += 1024.0 * leaf->GetActualMemorySize(); // the oracle: VTK's size of each image
      EXPECT_EQ(mismatches(*volume, leaf, "sdf", 1.0), 0) << "partition " << i;
    }
    EXPECT_EQ(limit.Count("holding the sparse volume's decoded partitions"), 1u) << limit.Messages();
  }
  EXPECT_GT(decoded, 0u);
  EXPECT_GT(refused, 0u);
  EXPECT_EQ(sparse->GetHeldPartitionBytes(), sum) << "reported: the images' own size";
  EXPECT_LE(sparse->GetHeldPartitionBytes(), cap) << "held within the limit, on the reported measure";
}

// A partition that cannot be decoded on its own (here: alone over the memory
// limit) is reported with that reason, under its own one-error flag; the
// limit of the partitions held together is still reported when it comes.
// Until session 27 both shared one flag and the first said "the partitions
// left are not decoded" (0 bytes held), hiding the later true limit error.
TEST(SparseVolumeConsumers, APartitionAloneOverTheLimitSaysSo)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  sparse->ReleasePartitionsAfterUseOn();
  const unsigned int n = sparse->GetNumberOfPartitions();
  LimitAndMessages limit("1000"); // bytes: less than any partition's image
  std::size_t decoded = 0;
  for (unsigned int i = 0; i < n; ++i) decoded += sparse->GetPartition(i)->GetNumberOfPoints() > 0;
  EXPECT_EQ(decoded, 0u);
  EXPECT_EQ(limit.Count("on its own"), 1u) << limit.Messages();
  EXPECT_EQ(limit.Count("partitions left are not decoded"), 0u) << limit.Messages();
  EXPECT_NE(limit.Messages().find("more than the limit of 1000 B"), std::string::npos) << limit.Messages();
  // then a limit the partitions reach together: its own error
  limit.Set(bytesText(0.4 * sparse->GetPartitionBytes()));
  for (unsigned int i = 0; i < n; ++i) decoded += sparse->GetPartition(i)->GetNumberOfPoints() > 0;
  EXPECT_GT(decoded, 0u);
  EXPECT_LT(decoded, n);
  EXPECT_EQ(limit.Count("holding the sparse volume's decoded partitions"), 1u) << limit.Messages();
  EXPECT_EQ(limit.Count("on its own"), 1u) << limit.Messages();
}

// Sparse Volume To Image over the memory limit said only "set
// LVDIF_MEMORY_LIMIT to change it". It now names what fits: without colours
// (4 bytes a point) when that is within the limit, else a smaller extent,
// which a downstream vtkExtractVOI asks for.
// Oracle for both fixes named: they run within the same limit, and give the
// Core volume's own values.
TEST(SparseVolumeConsumers, DenseImageRefusalNamesWhatFits)
{
  lvdif::VolumeOptions o;
  o.dims = { 64, 64, 64 };
  o.chunkEdge = 16;
  auto volume = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*volume, lvdif::sphereSdf(32, 32, 32, 20));
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  const double points = 64.0 * 64 * 64;
  {
    LimitAndMessages limit(bytesText(6 * points)); // sdf + rgba: 8 bytes a point; sdf alone: 4
    vtkNew<vtkSparseVolumeToImage> dense;
    dense->SetInputData(sparse);
    dense->Update();
    EXPECT_EQ(dense->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_NE(limit.Messages().find("more than the limit"), std::string::npos) << limit.Messages();
    EXPECT_NE(limit.Messages().find("without colours (WithColor off"), std::string::npos) << limit.Messages();
    EXPECT_NE(limit.Messages().find("1.00 MiB, within the limit"), std::string::npos) << limit.Messages();
    dense->WithColorOff();
    dense->Update();
    EXPECT_EQ(dense->GetOutput()->GetNumberOfPoints(), static_cast<vtkIdType>(points)) << "the fix named works";
  }
  {
    LimitAndMessages limit(bytesText(2 * points)); // not even the sdf alone
    vtkNew<vtkSparseVolumeToImage> dense;
    dense->SetInputData(sparse);
    dense->Update();
    EXPECT_EQ(dense->GetOutput()->GetNumberOfPoints(), 0);
    EXPECT_EQ(limit.Messages().find("without colours"), std::string::npos) << "it would not fit either";
    EXPECT_NE(limit.Messages().find("ask for a smaller extent"), std::string::npos) << limit.Messages();
    vtkNew<vtkSparseVolumeToImage> asked; // the fix named: only the box is asked for
    asked->SetInputData(sparse);
    vtkNew<vtkExtractVOI> voi;
    voi->SetInputConnection(asked->GetOutputPort());
    voi->SetVOI(10, 41, 5, 36, 20, 51);
    voi->Update();
    vtkImageData* box = voi->GetOutput();
    ASSERT_EQ(box->GetNumberOfPoints(), 32 * 32 * 32) << limit.Messages();
    vtkDataArray* sdf = box->GetPointData()->GetArray("sdf");
    ASSERT_NE(sdf, nullptr);
    vtkIdType wrong = 0;
    for (int z = 20; z <= 51; ++z)
      for (int y = 5; y <= 36; ++y)
        for (int x = 10; x <= 41; ++x)
        {
          int ijk[3] = { x, y, z };
          wrong += sdf->GetTuple1(box->ComputePointId(ijk)) == volume->sdf(x, y, z) ? 0 : 1;
        }
    EXPECT_EQ(wrong, 0);
  }
}
