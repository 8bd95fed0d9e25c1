// A dense float grid: what the VTK layer hands to the core (vtkImageData's
// "sdf" array) and what core algorithms accept besides the dictionary volume.
// Geometry follows vtkImageData: point (i,j,k) sits at origin + (i,j,k)*spacing;
// the linear index is i + nx*(j + ny*k), 64-bit.
#pragma once

#include <array>
#include <cstdint>

namespace lvdif
{

struct GridGeometry
{
  std::array<std::int64_t, 3> dims{ 0, 0, 0 };
  std::array<double, 3> origin{ 0, 0, 0 };
  std::array<double, 3> spacing{ 1, 1, 1 };
  std::int64_t count() const { return dims[0] * dims[1] * dims[2]; }
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const { return i + dims[0] * (j + dims[1] * k); }
};

/// A non-owning view of a dense float grid (e.g. a vtkFloatArray's storage).
struct FloatGridView
{
  float* data = nullptr;
  GridGeometry geometry;
  float& at(std::int64_t i, std::int64_t j, std::int64_t k) const { return data[geometry.index(i, j, k)]; }
};

} // namespace lvdif
