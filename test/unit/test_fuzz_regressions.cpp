// Inputs that crashed the libFuzzer targets (fuzz/, scripts/fuzz.sh), replayed
// through the same entry points. The crashing files themselves are kept under
// fuzz/regressions/<target>/ and replayed by scripts/fuzz.sh.
//
// The contract under test: the core refuses bad input with InputError or
// ConfigError, the only exceptions the nodelets catch. Anything else that
// escapes (cv::Exception from OpenCV above all) terminates the nodelet
// manager, and with it the camera driver sharing it.

#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/roi/front_end.h"

namespace brick_pose
{
namespace
{
/// Runs `call`; success and InputError are fine, any other exception fails.
void expectNothingButInputError(const std::function<void()>& call)
{
  try
  {
    call();
  }
  catch (const InputError&)
  {
  }
  catch (const std::exception& e)
  {
    ADD_FAILURE() << "an exception the nodelets do not catch escaped: " << e.what();
  }
}

/// Runs `call`, which must throw ConfigError and nothing else.
void expectConfigErrorOnly(const std::function<void()>& call)
{
  try
  {
    call();
    ADD_FAILURE() << "accepted";
  }
  catch (const ConfigError&)
  {
  }
  catch (const std::exception& e)
  {
    ADD_FAILURE() << "expected ConfigError, got another exception: " << e.what();
  }
}

/// A well-formed grey frame at 1 m with intrinsics f = 100 px, centred.
RgbdFrame flatFrame(int width_px, int height_px)
{
  PinholeCamera camera;
  camera.width_px = width_px;
  camera.height_px = height_px;
  camera.fx_px = camera.fy_px = 100.0;
  camera.cx_px = 0.5 * width_px;
  camera.cy_px = 0.5 * height_px;
  const cv::Mat rgb(height_px, width_px, CV_8UC3, cv::Scalar(128, 128, 128));
  const cv::Mat depth_mm(height_px, width_px, CV_16UC1, cv::Scalar(1000));
  return makeRgbdFrame(rgb, depth_mm, camera, FrameHeader());
}

// fuzz_catalogue_yaml, fuzz/regressions/fuzz_catalogue_yaml/top_level_sequence.yaml:
// cv::FileStorage::operator[] asserts isMap() on a document whose root is a
// list (brick_catalogue.cpp, fromYamlString: storage["bricks"]).
TEST(FuzzRegressions, CatalogueWhoseRootIsAListIsAConfigError)
{
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("[1, 2]\n"); });
}

// fuzz_catalogue_yaml, fuzz/regressions/fuzz_catalogue_yaml/brick_not_a_map.yaml:
// a `bricks:` entry that is a number, not a map (parseBrick: node["name"]).
TEST(FuzzRegressions, BrickEntryThatIsNotAMapIsAConfigError)
{
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("bricks:\n  - 5\n"); });
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("bricks:\n  - [red, 0.3]\n"); });
}

// fuzz_front_end, fuzz/regressions/fuzz_front_end/one_pixel_frame (also seen
// killing the manager in the hostile_frames rostest): the HSV segmenter's
// coarse pass resizes by 1/coarse_factor, which gives an empty image when the
// frame is narrower or lower than the factor, and cv::resize throws.
TEST(FuzzRegressions, FrontEndOnFramesOnePixelWideOrHigh)
{
  const FrontEnd front_end(BrickCatalogue::mbzirc2020());
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(1, 64), cv::Size(64, 1)})
  {
    SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height));
    const RgbdFrame frame = flatFrame(size.width, size.height);
    expectNothingButInputError([&] { front_end.process(frame); });
  }
}

TEST(FuzzRegressions, RegionGrowingFrontEndOnFramesOnePixelWideOrHigh)
{
  FrontEndParams params;
  params.mode = SegmentationMode::kRegionGrowing;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), params);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(1, 64), cv::Size(64, 1)})
  {
    SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height));
    const RgbdFrame frame = flatFrame(size.width, size.height);
    expectNothingButInputError([&] { front_end.process(frame); });
  }
}
}  // namespace
}  // namespace brick_pose
