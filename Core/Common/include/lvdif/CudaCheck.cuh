// Every CUDA call goes through LVDIF_CUDA_CHECK: a failure becomes
// lvdif::Error(DeviceFailure) naming the call, file and line.
#pragma once

#include "lvdif/Error.h"

#include <cuda_runtime.h>
#include <string>

#define LVDIF_CUDA_CHECK(call)                                                                     \
  do                                                                                               \
  {                                                                                                \
    const cudaError_t lvdifErr_ = (call);                                                          \
    if (lvdifErr_ != cudaSuccess)                                                                  \
    {                                                                                              \
      throw ::lvdif::Error(::lvdif::ErrorCode::DeviceFailure,                                      \
        std::string("CUDA: ") + #call + " failed: " + cudaGetErrorString(lvdifErr_) + " (" +      \
          __FILE__ + ":" + std::to_string(__LINE__) + ")");                                        \
    }                                                                                              \
  } while (0)
