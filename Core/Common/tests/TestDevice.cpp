#include "lvdif/Cuda.h"

#include <gtest/gtest.h>

using namespace lvdif;

// A CUDA build on a machine without a GPU must resolve every request to the CPU.
TEST(Device, ResolvesToCpuWithoutAGpuAndToCudaWithOne)
{
  EXPECT_EQ(resolveDevice(Device::Cpu), Device::Cpu);
  const Device expected = cuda::available() ? Device::Cuda : Device::Cpu;
  EXPECT_EQ(resolveDevice(Device::Auto), expected);
  EXPECT_EQ(resolveDevice(Device::Cuda), expected);
  if (!cuda::compiled())
  {
    EXPECT_FALSE(cuda::available());
    EXPECT_EQ(cuda::deviceName(), "none");
  }
  if (!cuda::available())
  {
    EXPECT_EQ(cuda::freeMemory(), 0u);
  }
}
