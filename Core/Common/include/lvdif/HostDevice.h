#pragma once
// The one spelling for functions shared by the CPU and the CUDA code. The same source compiled for both is
// what makes the two paths compute the same function; on the host it is a plain inline function.
#if defined(__CUDACC__)
#define LVDIF_HD __host__ __device__ __forceinline__
#else
#define LVDIF_HD inline
#endif
