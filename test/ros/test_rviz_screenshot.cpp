// The demo as a person sees it: rviz under Xvfb shows the cable, in its tension colours, in the 3D view.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
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

// Pixels in the 3D view (right of the displays panel) drawn in the cable's colour scale, blue through
// green, over a dark blue background, grey grid and white labels; and the view's pixel count.
std::pair<int, int> cablePixels(const Image& img)
{
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
  return { cable_pixels, view_pixels };
}

TEST(RvizScreenshot, TheCableIsDrawnInItsTensionColours)
{
  // Software GL on a loaded machine may take seconds to draw the first frame with the markers in it:
  // shots 2 s apart, and the cable must appear in one of them (as a line, not a blue screen).
  constexpr int kShots = 8;
  const std::string png = "/tmp/tow_sim_test_screenshot.png", ppm = "/tmp/tow_sim_test_screenshot.ppm";
  std::remove(png.c_str());
  const std::string command = std::string("SHOTS=") + std::to_string(kShots) + " WS=" + TOW_SIM_WS + " " +
                              TOW_SIM_SOURCE_DIR + "/scripts/rviz_screenshot.sh " + png + " markers straight";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  bool drawn = false;
  for (int k = 1; k <= kShots && !drawn; ++k)
  {
    const std::string shot = "/tmp/tow_sim_test_screenshot-" + std::to_string(k) + ".png";
    ASSERT_EQ(std::system(("convert " + shot + " -depth 8 " + ppm).c_str()), 0) << shot;
    const Image img = readPpm(ppm);
    ASSERT_GT(img.width, 0) << shot;
    const auto [cable, view] = cablePixels(img);
    std::printf("rviz screenshot %d (%dx%d): %d cable-coloured pixels in the 3D view\n", k, img.width, img.height,
                cable);
    EXPECT_LT(cable, view / 5) << shot << ": a line, not a blue screen";
    drawn = cable > 100;
  }
  EXPECT_TRUE(drawn) << "no screenshot shows the cable";
}

}  // namespace
