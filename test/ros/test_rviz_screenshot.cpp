// The demo as a person sees it: rviz under Xvfb shows the cable, in its tension colours, in the 3D view.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace
{
struct Image
{
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

// Reads a binary PPM (P6, 8 bit).
Image readPpm(const std::string& path)
{
  Image img;
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int max_value = 0;
  in >> magic >> img.width >> img.height >> max_value;
  in.get();
  if (magic != "P6" || max_value != 255)
    return Image();
  img.rgb.resize(static_cast<size_t>(img.width) * img.height * 3);
  in.read(reinterpret_cast<char*>(img.rgb.data()), static_cast<std::streamsize>(img.rgb.size()));
  return img;
}

TEST(RvizScreenshot, TheCableIsDrawnInItsTensionColours)
{
  const std::string png = "/tmp/tow_sim_test_screenshot.png", ppm = "/tmp/tow_sim_test_screenshot.ppm";
  std::remove(png.c_str());
  const std::string command = std::string("WS=") + TOW_SIM_WS + " " + TOW_SIM_SOURCE_DIR +
                              "/scripts/rviz_screenshot.sh " + png + " markers straight";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  ASSERT_EQ(std::system(("convert " + png + " -depth 8 " + ppm).c_str()), 0);
  const Image img = readPpm(ppm);
  ASSERT_GT(img.width, 0);
  // The 3D view is right of the displays panel; the cable is drawn blue through green (its colour
  // scale) over a dark blue background, grey grid and white labels.
  int cable_pixels = 0, view_pixels = 0;
  for (int y = img.height / 10; y < img.height * 9 / 10; ++y)
    for (int x = img.width * 3 / 10; x < img.width; ++x)
    {
      const unsigned char* p = &img.rgb[(static_cast<size_t>(y) * img.width + x) * 3];
      ++view_pixels;
      const int r = p[0], g = p[1], b = p[2];
      if ((b - r > 90 || g - r > 90) && (b > 110 || g > 110))  // saturated blue to green, not the sea
        ++cable_pixels;
    }
  std::printf("rviz screenshot %dx%d: %d cable-coloured pixels in the 3D view\n", img.width, img.height, cable_pixels);
  EXPECT_GT(cable_pixels, 100);
  EXPECT_LT(cable_pixels, view_pixels / 5);  // a line, not a blue screen
}

}  // namespace
