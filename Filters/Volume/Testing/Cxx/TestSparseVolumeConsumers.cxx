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
  vtkNew<vtkArrayCalculator> calculator;
  calculator->SetInputData(sparse);
  calculator->AddScalarArrayName("sdf");
  calculator->SetFunction("sdf*2");
  calculator->SetResultArrayName("twice");
  calculator->Update();
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

// The held partitions together stay within the memory limit (LVDIF_MEMORY_LIMIT):
// past it the partitions left are not decoded (null leaves) with one error for
// the volume, not one per partition; released, they all decode again.
TEST(SparseVolumeConsumers, HeldPartitionsStayWithinTheMemoryLimit)
{
  const auto volume = twoSpheres();
  vtkNew<vtkSparseDictionaryVolume> sparse;
  sparse->SetVolume(volume);
  const double all = sparse->GetPartitionBytes();
  const std::string limit = std::to_string(static_cast<long long>(0.4 * all));
  const char* old = std::getenv("LVDIF_MEMORY_LIMIT");
  const std::string kept = old ? old : "";
  ::setenv("LVDIF_MEMORY_LIMIT", limit.c_str(), 1);
  vtkNew<vtkStringOutputWindow> window;
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkOutputWindow::SetInstance(window);
  const auto leaves = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse, /*preserveNull=*/true);
  const auto again = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse, true);
  vtkOutputWindow::SetInstance(previous);
  if (old)
    ::setenv("LVDIF_MEMORY_LIMIT", kept.c_str(), 1);
  else
    ::unsetenv("LVDIF_MEMORY_LIMIT");
  ASSERT_EQ(leaves.size(), sparse->GetNumberOfPartitions());
  std::size_t decoded = 0;
  for (std::size_t i = 0; i < leaves.size(); ++i)
  {
    ASSERT_NE(leaves[i], nullptr) << "an undecoded partition is an image without points, not a null leaf";
    if (leaves[i]->GetNumberOfPoints() == 0) continue;
    ++decoded;
    EXPECT_EQ(mismatches(*volume, leaves[i], "sdf", 1.0), 0) << "partition " << i;
  }
  EXPECT_GT(decoded, 0u);
  EXPECT_LT(decoded, leaves.size());
  EXPECT_LE(sparse->GetHeldPartitionBytes(), 0.4 * all + 64 * 1024.0 * decoded); // arrays + image overhead
  const std::string messages = window->GetOutput();
  const std::string what = "holding the sparse volume's decoded partitions";
  std::size_t count = 0;
  for (std::size_t at = messages.find(what); at != std::string::npos; at = messages.find(what, at + 1)) ++count;
  EXPECT_EQ(count, 1u) << messages;
  EXPECT_NE(messages.find("LVDIF_RELEASE_PARTITIONS=1"), std::string::npos) << messages;
  // vtkArrayCalculator asks to skip empty nodes and calls NewInstance on every leaf it gets
  ::setenv("LVDIF_MEMORY_LIMIT", limit.c_str(), 1);
  sparse->ReleaseDecodedPartitions();
  vtkOutputWindow::SetInstance(window);
  vtkNew<vtkArrayCalculator> calculator;
  calculator->SetInputData(sparse);
  calculator->AddScalarArrayName("sdf");
  calculator->SetFunction("sdf*2");
  calculator->SetResultArrayName("twice");
  calculator->Update();
  vtkOutputWindow::SetInstance(previous);
  if (old)
    ::setenv("LVDIF_MEMORY_LIMIT", kept.c_str(), 1);
  else
    ::unsetenv("LVDIF_MEMORY_LIMIT");
  const auto computed = vtkCompositeDataSet::GetDataSets<vtkDataSet>(calculator->GetOutputDataObject(0));
  std::size_t withResult = 0;
  for (vtkDataSet* leaf : computed) withResult += leaf->GetPointData()->GetArray("twice") != nullptr;
  EXPECT_EQ(withResult, decoded) << "the calculator ran on the decoded partitions";
  sparse->ReleaseDecodedPartitions();
  const auto whole = vtkCompositeDataSet::GetDataSets<vtkDataSet>(sparse, true);
  for (std::size_t i = 0; i < whole.size(); ++i)
    EXPECT_EQ(mismatches(*volume, whole[i], "sdf", 1.0), 0) << "partition " << i;
}
