// Image to volume against a brute-force union of pixel boxes.
#include "EditTestUtil.h"
#include "lvdif/Error.h"
#include "lvdif/ImageToVolume.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace lvdif;

TEST(ImageToVolume, SlabWithDepthIsTheUnionOfPixelColumns)
{
  const int w = 7, h = 5;
  std::vector<std::uint8_t> rgba(w * h * 4);
  std::vector<float> depth(w * h);
  for (int r = 0; r < h; ++r)
    for (int u = 0; u < w; ++u)
    {
      std::uint8_t* p = &rgba[4 * (r * w + u)];
      p[0] = static_cast<std::uint8_t>(30 * u);
      p[1] = static_cast<std::uint8_t>(40 * r);
      p[2] = 7;
      p[3] = (u == 3 && r == 2) ? 0 : 255; // one transparent hole
      depth[r * w + u] = static_cast<float>((u + r) % 4) / 3.3f + 0.04f; // tops off the voxel grid
    }
  DictionaryVolume v(edittest::options(24, 8));
  ImageToVolumeOptions o;
  o.origin = { 5, 6, 4 };
  o.thickness = 2;
  o.depthScale = 6;
  ImageView img{ w, h, rgba.data(), depth.data() };
  const std::int64_t solid = imageToVolume(v, img, o);
  std::int64_t expectSolid = 0;
  double worstOutside = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    // brute force over every pixel box, in double
    double best = 1e30;
    for (int r = 0; r < h; ++r)
      for (int u = 0; u < w; ++u)
      {
        if (u == 3 && r == 2)
          continue;
        const double top = 2 + 6 * double(depth[r * w + u]);
        const double cx = 5 + u, cy = 6 + (h - 1 - r);
        const double q[3] = { std::fabs(x - cx) - 0.5, std::fabs(y - cy) - 0.5, std::fabs(z - (4 + top / 2)) - top / 2 };
        double out = 0, in = -1e30;
        for (double a : q)
        {
          out += a > 0 ? a * a : 0;
          in = std::max(in, a);
        }
        const double d = std::sqrt(out) + std::min(in, 0.0);
        best = std::min(best, d);
      }
    const float got = v.sdf(x, y, z);
    ASSERT_EQ(got < 0, best < 0) << x << " " << y << " " << z;
    expectSolid += best < 0;
    if (best >= 0 && best <= 2)
      worstOutside = std::max(worstOutside, std::fabs(double(got) - best));
    if (best < 0)
    {
      // a voxel inside the solid lies in its own pixel's column: it carries that pixel's colour
      const int u = int(x) - 5, r = h - 1 - (int(y) - 6);
      const std::uint8_t* own = &rgba[4 * (r * w + u)];
      ASSERT_EQ(v.colors()[v.get(x, y, z).color], (Rgba{ own[0], own[1], own[2], own[3] }));
    }
  });
  EXPECT_EQ(solid, expectSolid);
  EXPECT_GT(solid, w * h * 2 - 10);
  EXPECT_LE(worstOutside, v.sdfDictionary().maxErrorInRange() + 1e-4);
  // the hole is empty
  EXPECT_GT(v.sdf(5 + 3, 6 + 2, 5), 0.0f);
}

TEST(ImageToVolume, BadInputIsRefused)
{
  DictionaryVolume v(edittest::options(16));
  ImageToVolumeOptions o;
  EXPECT_THROW(imageToVolume(v, ImageView{}, o), Error);
  std::uint8_t px[4] = { 1, 2, 3, 255 };
  o.thickness = 0;
  EXPECT_THROW(imageToVolume(v, ImageView{ 1, 1, px, nullptr }, o), Error);
}
