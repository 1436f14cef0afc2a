// The demo as a person sees it: rviz under Xvfb opens on the whole tow, the ship's hull, the cable in its
// tension colours and the vehicle in the 3D view.
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

// What the 3D view (right of the displays panel) shows, counted in pixels: the cable in its tension colours
// (saturated blue to green, not the dark blue sea), the ship's cream hull (no other marker is cream), the
// vehicle's orange hull (half transparent over the sea; the cable turns orange only at 3/4 of its colour
// scale), and the view's size.
struct ViewPixels
{
  int cable = 0, hull = 0, vehicle = 0, view = 0;
};

ViewPixels countPixels(const Image& img)
{
  ViewPixels n;
  for (int y = img.height / 10; y < img.height * 9 / 10; ++y)
    for (int x = img.width * 3 / 10; x < img.width; ++x)
    {
      const unsigned char* p = &img.rgb[(static_cast<size_t>(y) * img.width + x) * 3];
      ++n.view;
      const int r = p[0], g = p[1], b = p[2];
      if ((b - r > 90 || g - r > 90) && (b > 110 || g > 110))
        ++n.cable;
      if (r > 120 && g > 0.85 * r && g <= r && b > 0.6 * r && b < 0.9 * r)
        ++n.hull;
      if (r > 90 && g > 0.4 * r && g < 0.8 * r && b < 0.45 * r)
        ++n.vehicle;
    }
  return n;
}

// The default view shows the whole tow: the ship's hull on the surface, the cable and the vehicle (drawn
// enlarged, vehicle_marker_scale 10 in tow_sim.launch) are all in one picture. Measured on this machine:
// 1065 cable, 353 hull and 46 vehicle pixels; with the vehicle at its true size (vehicle_marker_scale 1 in
// the configuration) 0 vehicle pixels, which fails.
TEST(RvizScreenshot, TheDefaultViewShowsTheShipTheCableAndTheVehicle)
{
  // Software GL on a loaded machine may take seconds to draw the first frame with the markers in it:
  // shots 2 s apart, and one of them must show all three (as lines and shapes, not a blue screen).
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
    const ViewPixels n = countPixels(img);
    std::printf("rviz screenshot %d (%dx%d): %d cable-coloured, %d hull, %d vehicle pixels in the 3D view\n", k,
                img.width, img.height, n.cable, n.hull, n.vehicle);
    EXPECT_LT(n.cable, n.view / 5) << shot << ": a line, not a blue screen";
    drawn = n.cable > 100 && n.hull > 60 && n.vehicle > 15;
  }
  EXPECT_TRUE(drawn) << "no screenshot shows the ship's hull, the cable and the vehicle together";
}

}  // namespace
