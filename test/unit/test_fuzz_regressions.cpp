// Inputs that crashed the libFuzzer targets (fuzz/, scripts/fuzz.sh), replayed
// through the same entry points. The crashing files themselves are kept under
// fuzz/regressions/<target>/ and replayed by scripts/fuzz.sh.
//
// The contract under test: the core refuses bad input with InputError or
// ConfigError, the only exceptions the nodelets catch. Anything else that
// escapes (cv::Exception from OpenCV above all) terminates the nodelet
// manager, and with it the camera driver sharing it.

#include <cstdlib>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/correction/pose_correction.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"

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

// fuzz_catalogue_yaml, fuzz/regressions/fuzz_catalogue_yaml/unterminated_flow_map.yaml
// (minimised from a 400-byte input): OpenCV's YAML reader throws
// std::length_error ("basic_string::_M_create"), not cv::Exception, from the
// cv::FileStorage constructor in openYamlText (brick_catalogue.cpp).
TEST(FuzzRegressions, UnterminatedFlowMapIsAConfigError)
{
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("{ :"); });
}

// fuzz_catalogue_yaml, fuzz/regressions/fuzz_catalogue_yaml/indented_root_sequence.yaml
// (minimised from a 117-byte input that timed out): OpenCV 4.6's YAML reader
// never returns from the cv::FileStorage constructor on an indented root
// sequence followed by a root scalar with punctuation. A catalogue's root is
// a map, so such text is now rejected before OpenCV sees it (requireMapRoot
// in brick_catalogue.cpp). Without the check this test never returns.
TEST(FuzzRegressions, IndentedRootSequenceIsAConfigErrorNotAHang)
{
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString(" - 0\nb%\n-"); });
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("# comment\n\n - 0\nb:\n-\n"); });
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("%YAML:1.0\n---\n- a\n"); });
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("\n# only a comment\n"); });
  // Five more timeouts of a 3-minute run, all a root line of dashes ("----t").
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("----t\n*\n\n"); });
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("#-\n----\xb9w\nn\n"); });
  expectConfigErrorOnly([] { BrickCatalogue::fromYamlString("---\n!- -\xe4\n-\n "); });
}

// The check must not reject what real catalogues look like.
TEST(FuzzRegressions, MapRootCheckAcceptsCommentsDirectivesAndMarkers)
{
  const std::string bricks = "bricks:\n  - name: red\n    length_m: 0.3\n    width_m: 0.2\n    height_m: 0.2\n"
                             "    plate_rgb: [200, 25, 25]\n    body_rgb: [215, 150, 150]\n"
                             "    hsv_min: [170, 120, 25]\n    hsv_max: [7, 255, 255]\n";
  EXPECT_EQ(BrickCatalogue::fromYamlString(bricks).types().size(), 1u);
  EXPECT_EQ(BrickCatalogue::fromYamlString("# catalogue\n\n" + bricks).types().size(), 1u);
  EXPECT_EQ(BrickCatalogue::fromYamlString("%YAML:1.0\n---\n" + bricks).types().size(), 1u);
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
// fuzz_front_end, region-growing mode, every crash of a 30 s run: frames up
// to 96x44 px thin (stride 6) to block clouds smaller than the integral-image
// normal window (8 strided px). PCL's IntegralImageNormalEstimation then reads
// outside the cloud (SEGV in computeFeatureFull, called from
// region_growing_segmenter.cpp:142), or leaves the normals empty, and
// `(*normals)[i]` (region_growing_segmenter.cpp:146) binds a reference to
// nothing (UBSan; a SEGV in Release too).
// The call runs in a child process (a death test that expects a clean exit),
// so that the SEGV fails this test only, not every test linked with it.
TEST(FuzzRegressionsDeathTest, RegionGrowingOnFramesSmallerThanTheNormalWindow)
{
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  FrontEndParams params;
  params.mode = SegmentationMode::kRegionGrowing;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), params);
  for (const cv::Size size : {cv::Size(18, 42), cv::Size(64, 40), cv::Size(96, 44), cv::Size(6, 6)})
  {
    SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height));
    const RgbdFrame frame = flatFrame(size.width, size.height);
    EXPECT_EXIT(
        {
          try
          {
            front_end.process(frame);
          }
          catch (const InputError&)
          {
          }
          std::exit(0);
        },
        testing::ExitedWithCode(0), "")
        << "the region-growing front end crashed (or threw something other than InputError)";
  }
}

// fuzz_pose_correction (crash-470bef76...): a finite but absurd registration
// pose (translation 1.8e308 m) passes the finiteness and rigidity checks, and
// the correction overflows to an Inf translation that it returns as a
// success. Replayed with the decoded values (paper mode, blue brick).
TEST(FuzzRegressions, CorrectionOfAnAbsurdlyFarPoseIsRefusedOrFinite)
{
  const double far_m = std::numeric_limits<double>::max();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << 0.33334249078224332, -0.66667135383088671, 0.66665740063422563,  //
      0.66667135383088671, -0.33331480126846902, -0.6666712452451008,                 //
      0.66665740063422563, 0.6666712452451008, 0.33334270794928766;
  pose.translation() = Eigen::Vector3d(far_m, far_m, 0.0);
  MeasuredFace face;
  face.t1_m = Eigen::Vector3d(1.1882352941176464, 1.1882352938272938, -1.7228860294117647);
  face.t2_m = Eigen::Vector3d(0.91376977060355324, 0.33506978041403035, -1.7228860294117647);
  face.centroid_m = Eigen::Vector3d(0.0, 2.9999999991784794, -1.5358524711473946);
  face.normal = Eigen::Vector3d(-0.20750505036965661, 0.0, 0.99999993498787965);
  PoseCorrectionParams parameters;
  parameters.mode = CorrectionMode::kPaper;
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const BrickType& blue = catalogue.at("blue");
  try
  {
    const PoseCorrection correction = correctPose(pose, blue, face, parameters);
    EXPECT_TRUE(correction.corrected_pose.matrix().allFinite()) << "accepted, with a non-finite corrected pose:\n"
                                                               << correction.corrected_pose.matrix();
  }
  catch (const InputError&)
  {
  }
}
// fuzz/regressions/fuzz_pose_correction/rotation_of_huge_entries_passes_rigidity:
// a "rotation" whose entries are 1.8e308 makes R^T R - I overflow to NaN, and
// requireRigid (pose_correction.cpp:46) compares `orthogonality_error >
// kRigidTolerance || determinant < 0`, both false for NaN, so the matrix
// passes as rigid and the correction returns NaN everywhere (here with the
// decoded brick of 1.8e308 m; with a catalogue brick the input is refused).
TEST(FuzzRegressions, RotationWithHugeEntriesIsNotRigid)
{
  const double huge = std::numeric_limits<double>::max();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << huge, huge, huge, huge, 0.0, -1.7333333333333334, -1.7333333333333334, huge, huge;
  pose.translation() = Eigen::Vector3d(huge, 0.0, -2.6);
  MeasuredFace face;
  face.t1_m = Eigen::Vector3d(-2.6, -2.6, 3.0);
  face.t2_m = Eigen::Vector3d(-0.6, -0.6, 1.0);
  face.centroid_m = face.midpoint_m();
  face.normal = Eigen::Vector3d(1.0, 1.0, 1.0);
  PoseCorrectionParams parameters;
  parameters.mode = CorrectionMode::kPaper;
  BrickType brick = BrickCatalogue::mbzirc2020().at("orange");
  brick.length_m = brick.width_m = huge;  // as decoded; correctPose checks only that the length is positive
  try
  {
    const PoseCorrection correction = correctPose(pose, brick, face, parameters);
    ADD_FAILURE() << "accepted as rigid, corrected pose:\n" << correction.corrected_pose.matrix();
  }
  catch (const InputError&)
  {
  }
  catch (const ConfigError&)
  {
  }
}
}  // namespace
}  // namespace brick_pose
