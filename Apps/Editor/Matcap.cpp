#include "Matcap.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkTexture.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace
{
double clamp01(double v)
{
  return std::min(1.0, std::max(0.0, v));
}
} // namespace

QImage makeClayMatcap(int size)
{
  QImage image(size, size, QImage::Format_RGB888);
  // light directions in view space (x right, y up, z toward the viewer)
  auto unit = [](double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return std::array<double, 3>{ x / l, y / l, z / l };
  };
  const auto key = unit(-0.55, 0.65, 0.55), fill = unit(0.8, -0.1, 0.6);
  const double albedo[3] = { 0.86, 0.80, 0.74 }; // warm clay
  for (int y = 0; y < size; ++y)
  {
    uchar* row = image.scanLine(y);
    for (int x = 0; x < size; ++x)
    {
      double nx = 2.0 * (x + 0.5) / size - 1, ny = 1 - 2.0 * (y + 0.5) / size;
      const double r2 = nx * nx + ny * ny;
      if (r2 > 1)
      {
        const double r = std::sqrt(r2);
        nx /= r, ny /= r;
      }
      const double nz = std::sqrt(std::max(0.0, 1 - nx * nx - ny * ny));
      const double k = std::max(0.0, nx * key[0] + ny * key[1] + nz * key[2]);
      const double f = std::max(0.0, nx * fill[0] + ny * fill[1] + nz * fill[2]);
      // half-Lambert wrap on the key keeps the shadow side soft, as clay looks
      const double wrap = 0.5 * k + 0.5 * k * k;
      const double rim = std::pow(1 - nz, 3);
      // a broad, weak highlight of the key seen from the viewer (0, 0, 1)
      const double hz = key[2] + 1, hl = std::sqrt(key[0] * key[0] + key[1] * key[1] + hz * hz);
      const double spec = std::pow(std::max(0.0, (nx * key[0] + ny * key[1] + nz * hz) / hl), 24) * 0.18;
      for (int c = 0; c < 3; ++c)
      {
        const double v = albedo[c] * (0.16 + 0.78 * wrap + 0.22 * f) + 0.25 * rim + spec;
        row[3 * x + c] = static_cast<uchar>(std::lround(255 * clamp01(v)));
      }
    }
  }
  return image;
}

vtkSmartPointer<vtkTexture> matcapTexture(const QImage& source)
{
  const QImage image = source.convertToFormat(QImage::Format_RGB888);
  vtkNew<vtkImageData> data;
  data->SetDimensions(image.width(), image.height(), 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < image.height(); ++y)
  {
    const uchar* row = image.constScanLine(image.height() - 1 - y);
    std::copy(row, row + 3 * image.width(), static_cast<unsigned char*>(data->GetScalarPointer(0, y, 0)));
  }
  auto texture = vtkSmartPointer<vtkTexture>::New();
  texture->SetInputData(data);
  texture->InterpolateOn();
  texture->RepeatOff();
  texture->EdgeClampOn();
  return texture;
}
