// vtkSignVoxelFilter on a sparse volume: the input is left exactly as it was,
// the output equals the filter's image path on the decoded volume (the dense
// filter, an independent route through the pipeline), and the output shares
// every chunk it did not change with the input (copy-on-write: no second volume).
#include "vtkSignVoxelFilter.h"

#include "vtkMeshToSDF.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkSparseVolumeToImage.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTrivialProducer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace
{
std::vector<lvdif::Voxel> voxels(const lvdif::DictionaryVolume& v)
{
  std::vector<lvdif::Voxel> out;
  for (std::int64_t z = 0; z < v.dims()[2]; ++z)
    for (std::int64_t y = 0; y < v.dims()[1]; ++y)
      for (std::int64_t x = 0; x < v.dims()[0]; ++x) out.push_back(v.get(x, y, z));
  return out;
}

/// A sphere's sparse SDF with wrong signs: a box crossing chunks and, with
/// `scattered`, isolated voxels everywhere (then every chunk changes).
std::shared_ptr<lvdif::DictionaryVolume> corruptedSphere(bool scattered = true)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(32);
  vtkNew<vtkMeshToSDF> sdf;
  sdf->SetInputConnection(sphere->GetOutputPort());
  sdf->SetMaxDimension(72);
  sdf->SetChunkEdge(16);
  sdf->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  sdf->Update();
  auto* out = vtkSparseDictionaryVolume::SafeDownCast(sdf->GetOutputDataObject(0));
  std::shared_ptr<lvdif::DictionaryVolume> v = out->GetVolume()->clone();
  const lvdif::Index3 d = v->dims();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        const float s = v->sdf(x, y, z);
        const bool box = x > 20 && x < 40 && y > 25 && y < 35 && z > 10 && z < 50;
        if (std::fabs(s) > 3.0f && (box || (scattered && (x * 7 + y * 13 + z * 29) % 97 == 0)))
        {
          v->setSdf(x, y, z, -s);
        }
      }
  v->collapseUniformChunks();
  return v;
}
/// The sign filters (CPU) run on `in` as a sparse input; the filter, updated
/// (its pipeline keeps the input alive).
vtkSmartPointer<vtkSignVoxelFilter> filterOnCpu(const std::shared_ptr<lvdif::DictionaryVolume>& in)
{
  vtkNew<vtkSparseDictionaryVolume> input;
  input->SetVolume(in);
  vtkNew<vtkTrivialProducer> tp;
  tp->SetOutput(input);
  auto svf = vtkSmartPointer<vtkSignVoxelFilter>::New();
  svf->SetInputConnection(tp->GetOutputPort());
  svf->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  svf->Update();
  return svf;
}
} // namespace

TEST(vtkSignVoxelFilterSparse, InputUnchangedOutputEqualsTheImagePathAndSharesChunks)
{
  const std::shared_ptr<lvdif::DictionaryVolume> in = corruptedSphere();
  const std::vector<lvdif::Voxel> before = voxels(*in);
  vtkSmartPointer<vtkSignVoxelFilter> svf = filterOnCpu(in);
  auto* output = vtkSparseDictionaryVolume::SafeDownCast(svf->GetOutputDataObject(0));
  ASSERT_NE(output, nullptr);
  ASSERT_TRUE(output->HasVolume());
  const lvdif::DictionaryVolume& out = *output->GetVolume();

  // the input is exactly as it was
  EXPECT_EQ(voxels(*in), before);

  // the oracle: the same filter's image path on the dense decoded input
  vtkNew<vtkSparseVolumeToImage> toImage;
  toImage->SetInputConnection(svf->GetInputConnection(0, 0)); // the same sparse input
  vtkNew<vtkSignVoxelFilter> dense;
  dense->SetInputConnection(toImage->GetOutputPort());
  dense->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  dense->Update();
  vtkDataArray* want = vtkImageData::SafeDownCast(dense->GetOutputDataObject(0))->GetPointData()->GetArray("sdf");
  ASSERT_NE(want, nullptr);
  std::int64_t flipped = 0, wrong = 0;
  vtkIdType i = 0;
  for (std::int64_t z = 0; z < out.dims()[2]; ++z)
    for (std::int64_t y = 0; y < out.dims()[1]; ++y)
      for (std::int64_t x = 0; x < out.dims()[0]; ++x, ++i)
      {
        const float w = static_cast<float>(want->GetTuple1(i));
        const lvdif::Voxel o = out.get(x, y, z), b = in->get(x, y, z);
        if ((w < 0) != (in->sdf(x, y, z) < 0))
        {
          ++flipped; // a flip stores the key of the negated value
          wrong += o.sdf != out.encode(-in->sdf(x, y, z)) || o.color != b.color ? 1 : 0;
        }
        else
        {
          wrong += o != b ? 1 : 0;
        }
      }
  EXPECT_GT(flipped, 500);
  EXPECT_EQ(wrong, 0);
  auto* flips = vtkIdTypeArray::SafeDownCast(output->GetFieldData()->GetArray("svf_flips"));
  auto* wantFlips =
    vtkIdTypeArray::SafeDownCast(dense->GetOutputDataObject(0)->GetFieldData()->GetArray("svf_flips"));
  ASSERT_NE(flips, nullptr);
  ASSERT_NE(wantFlips, nullptr);
  for (int f = 0; f < 4; ++f)
  {
    EXPECT_EQ(flips->GetValue(f), wantFlips->GetValue(f)) << "SVF" << f + 1;
  }

  // memory: the output shares every expanded chunk it did not write with the input
  std::int64_t changedChunks = 0, sharedWithInput = 0;
  for (std::int64_t id = 0; id < out.chunkCount(); ++id)
  {
    const lvdif::VoxelBox b = out.chunkBox(id);
    bool changed = false;
    for (std::int64_t z = b.lo[2]; z <= b.hi[2] && !changed; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1] && !changed; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0] && !changed; ++x) changed = out.get(x, y, z) != in->get(x, y, z);
    changedChunks += changed ? 1 : 0;
    sharedWithInput += out.chunkData(id) && out.chunkData(id) == in->chunkData(id) ? 1 : 0;
    if (!changed && !in->isUniform(id) && !out.isUniform(id))
    {
      EXPECT_EQ(out.chunkData(id), in->chunkData(id)) << "chunk " << id;
    }
  }
  EXPECT_GT(changedChunks, 5);
  EXPECT_GT(sharedWithInput, in->expandedChunkCount() - changedChunks - 1);
  EXPECT_EQ(out.sharedChunkCount(), sharedWithInput);

}

TEST(vtkSignVoxelFilterSparse, OutputSharesUnchangedChunksAndEditsStaySeparate)
{
  // wrong signs in one box only: the chunks away from it are unchanged
  const std::shared_ptr<lvdif::DictionaryVolume> in = corruptedSphere(false);
  const std::vector<lvdif::Voxel> before = voxels(*in);
  vtkSmartPointer<vtkSignVoxelFilter> svf = filterOnCpu(in);
  auto* output = vtkSparseDictionaryVolume::SafeDownCast(svf->GetOutputDataObject(0));
  ASSERT_NE(output, nullptr);
  ASSERT_TRUE(output->HasVolume());
  lvdif::DictionaryVolume& out = *output->GetVolume();
  EXPECT_EQ(voxels(*in), before);

  // every expanded chunk whose voxels the filters left as they were is the
  // input's buffer itself; a changed one is the output's own
  std::int64_t unchanged = 0, changed = 0;
  std::vector<std::int64_t> shared;
  for (std::int64_t id = 0; id < out.chunkCount(); ++id)
  {
    const lvdif::VoxelBox b = out.chunkBox(id);
    bool same = true;
    for (std::int64_t z = b.lo[2]; z <= b.hi[2] && same; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1] && same; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0] && same; ++x) same = out.get(x, y, z) == in->get(x, y, z);
    if (!in->chunkData(id)) continue;
    if (same)
    {
      ++unchanged;
      EXPECT_EQ(out.chunkData(id), in->chunkData(id)) << "unchanged chunk " << id << " is not shared";
      shared.push_back(id);
    }
    else
    {
      ++changed;
      EXPECT_NE(out.chunkData(id), in->chunkData(id)) << "changed chunk " << id;
    }
  }
  EXPECT_GT(changed, 0);
  ASSERT_GE(unchanged, 2);
  EXPECT_EQ(out.sharedChunkCount(), unchanged);
  EXPECT_EQ(in->sharedChunkCount(), unchanged);

  // a later edit of either volume in a shared chunk leaves the other alone:
  // the writer gets its own copy of that chunk, the others stay shared
  const auto editCorner = [](lvdif::DictionaryVolume& v, std::int64_t id) {
    const lvdif::VoxelBox b = v.chunkBox(id);
    lvdif::Voxel w = v.get(b.lo[0], b.lo[1], b.lo[2]);
    w.sdf = w.sdf == v.encode(1.5f) ? v.encode(-1.5f) : v.encode(1.5f);
    v.set(b.lo[0], b.lo[1], b.lo[2], w);
    return w;
  };
  const std::vector<lvdif::Voxel> outBefore = voxels(out);
  const lvdif::Voxel* inBuffer = in->chunkData(shared.front());
  const lvdif::Voxel w = editCorner(out, shared.front());
  output->VolumeModified();
  const lvdif::VoxelBox b0 = out.chunkBox(shared.front());
  EXPECT_EQ(out.get(b0.lo[0], b0.lo[1], b0.lo[2]), w);
  EXPECT_EQ(voxels(*in), before) << "an edit of the output changed the input";
  EXPECT_EQ(in->chunkData(shared.front()), inBuffer) << "the input keeps its buffer";
  EXPECT_NE(out.chunkData(shared.front()), inBuffer) << "the output wrote to a copy";
  EXPECT_EQ(out.sharedChunkCount(), unchanged - 1);
  const std::vector<lvdif::Voxel> outEdited = voxels(out);
  EXPECT_NE(outEdited, outBefore);
  editCorner(*in, shared.back());
  EXPECT_NE(voxels(*in), before);
  EXPECT_EQ(voxels(out), outEdited) << "an edit of the input changed the output";
  EXPECT_EQ(out.sharedChunkCount(), unchanged - 2);
  EXPECT_EQ(in->sharedChunkCount(), unchanged - 2);
}

// A volume of one slab (every volume below the 128 MiB slab budget, i.e. the
// usual case): the filter reported no progress between 0 and 1, so ParaView's
// progress bar stood still for the whole run, and a cancel was only seen at
// the start of a slab (so never, once begun). Now: progress at the slab's
// stages, each one a point where a cancel is honoured.
namespace
{
struct ProgressLog
{
  std::vector<double> values;
  double abortAbove = 2.0; // abort at the first value past this
};
void logProgress(vtkObject* caller, unsigned long, void* clientData, void* callData)
{
  auto* log = static_cast<ProgressLog*>(clientData);
  const double v = *static_cast<double*>(callData);
  log->values.push_back(v);
  if (v > log->abortAbove) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
}
vtkSmartPointer<vtkSignVoxelFilter> oneSlabFilter(ProgressLog& log)
{
  vtkNew<vtkSparseDictionaryVolume> input;
  input->SetVolume(corruptedSphere());
  auto tp = vtkSmartPointer<vtkTrivialProducer>::New();
  tp->SetOutput(input);
  auto svf = vtkSmartPointer<vtkSignVoxelFilter>::New();
  svf->SetInputConnection(tp->GetOutputPort());
  svf->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  vtkNew<vtkCallbackCommand> cb;
  cb->SetCallback(logProgress);
  cb->SetClientData(&log);
  svf->AddObserver(vtkCommand::ProgressEvent, cb);
  return svf;
}
} // namespace

TEST(vtkSignVoxelFilterSparse, AVolumeOfOneSlabReportsProgressAndHonoursACancel)
{
  ProgressLog log;
  vtkSmartPointer<vtkSignVoxelFilter> svf = oneSlabFilter(log);
  svf->Update();
  std::vector<double> within;
  for (const double v : log.values)
    if (v > 0.0 && v < 1.0) within.push_back(v);
  EXPECT_GE(within.size(), 3u) << "progress between 0 and 1";
  for (std::size_t i = 1; i < within.size(); ++i) EXPECT_LE(within[i - 1], within[i]) << "progress goes forward";
  ASSERT_TRUE(vtkSparseDictionaryVolume::SafeDownCast(svf->GetOutputDataObject(0))->HasVolume());

  // a cancel at the first progress past 0: no result, no statistics
  ProgressLog cancelled;
  cancelled.abortAbove = 0.0;
  vtkSmartPointer<vtkSignVoxelFilter> stopped = oneSlabFilter(cancelled);
  stopped->Update();
  auto* out = vtkSparseDictionaryVolume::SafeDownCast(stopped->GetOutputDataObject(0));
  EXPECT_FALSE(out->HasVolume()) << "the cancelled filter's output";
  EXPECT_EQ(out->GetFieldData()->GetArray("svf_flips"), nullptr);
  double last = 0;
  for (const double v : cancelled.values)
    if (v < 1.0) last = std::max(last, v);
  EXPECT_LT(last, 0.5) << "it stopped at the first stage past 0";
}
