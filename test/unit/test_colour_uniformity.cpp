// Whether a face is of one plain colour (a plate) or printed (a box).
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "brick_pose/roi/colour_uniformity.h"
#include "brick_pose/roi/face_grey.h"

namespace brick_pose
{
namespace
{
/// A 640x480 frame of one colour with grey noise of `noise_sigma` levels,
/// and the mask of the face (a 300 x 200 px rectangle at (100, 100)).
struct Face
{
  RgbdFrame frame;
  cv::Mat mask;
  cv::Rect box{100, 100, 300, 200};
};

Face plainFace(double noise_sigma, unsigned seed = 7)
{
  Face face;
  face.frame.camera.width_px = 640;
  face.frame.camera.height_px = 480;
  face.frame.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar(200, 60, 50));
  face.frame.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.5f));
  std::mt19937 generator(seed);
  std::normal_distribution<double> noise(0.0, noise_sigma);
  for (int v = 0; v < 480; ++v)
    for (int u = 0; u < 640; ++u)
    {
      const double n = noise(generator);
      cv::Vec3b& px = face.frame.rgb.at<cv::Vec3b>(v, u);
      for (int c = 0; c < 3; ++c) px[c] = cv::saturate_cast<unsigned char>(px[c] + n);
    }
  face.mask = cv::Mat(face.box.size(), CV_8UC1, cv::Scalar(255));
  return face;
}

ColourUniformity measure(const Face& face) { return measureColourUniformity(face.frame, face.mask, face.box); }

TEST(ColourUniformity, APlateIsPlainUnderSensorNoiseUpToLowLight)
{
  for (const double sigma : {0.0, 2.0, 5.0})
  {
    const ColourUniformity plain = measure(plainFace(sigma));
    EXPECT_TRUE(plain.uniform) << "noise " << sigma << ": scatter " << plain.sigma_grey << ", outliers "
                               << plain.outlier_fraction;
    EXPECT_LT(plain.sigma_grey, 10.0);
  }
}

TEST(ColourUniformity, ASeamLineThroughThePlateKeepsItPlain)
{
  Face face = plainFace(2.0);
  cv::line(face.frame.rgb, {250, 110}, {250, 290}, cv::Scalar(100, 30, 25), 2);
  EXPECT_TRUE(measure(face).uniform) << measure(face).outlier_fraction;
}

TEST(ColourUniformity, ALabelOrStripesOrTextureArePrint)
{
  Face label = plainFace(2.0);
  cv::rectangle(label.frame.rgb, {150, 150}, {230, 220}, cv::Scalar(250, 250, 250), cv::FILLED);
  EXPECT_FALSE(measure(label).uniform) << measure(label).outlier_fraction;

  Face stripes = plainFace(2.0);
  for (int u = 140; u < 380; u += 40) cv::line(stripes.frame.rgb, {u, 110}, {u, 290}, cv::Scalar(20, 20, 20), 3);
  EXPECT_FALSE(measure(stripes).uniform) << measure(stripes).outlier_fraction;

  // Busy print everywhere (patches of 8 px in random shades): a large
  // scatter and no outliers beyond it.
  Face busy = plainFace(2.0);
  std::mt19937 generator(3);
  std::uniform_int_distribution<int> shade(-40, 40);
  for (int v = 100; v < 300; v += 8)
    for (int u = 100; u < 400; u += 8)
    {
      const int s = shade(generator);
      cv::rectangle(busy.frame.rgb, {u, v}, {u + 7, v + 7}, cv::Scalar(200 + s / 4, 60 + s, 50 + s), cv::FILLED);
    }
  EXPECT_FALSE(measure(busy).uniform) << measure(busy).sigma_grey;

  // Pixel noise alone, however strong, is no print: the blocks average it.
  EXPECT_LT(measure(plainFace(20.0)).sigma_grey, 8.0);
}

TEST(ColourUniformity, TooSmallAFaceSaysNothing)
{
  Face face = plainFace(1.0);
  face.box = cv::Rect(100, 100, 10, 10);
  face.mask = cv::Mat(face.box.size(), CV_8UC1, cv::Scalar(255));
  const ColourUniformity tiny = measure(face);
  EXPECT_FALSE(tiny.uniform);
  EXPECT_EQ(tiny.samples, 0);
  EXPECT_FALSE(measureColourUniformity(face.frame, cv::Mat(), face.box).uniform);
}

TEST(ColourUniformity, MeanGreyLevelReadsTheMaskedPixelsInsideTheImage)
{
  RgbdFrame frame;
  frame.rgb = cv::Mat(100, 100, CV_8UC3, cv::Scalar(30, 60, 90));  // grey 60
  frame.rgb(cv::Rect(0, 0, 50, 100)).setTo(cv::Scalar(200, 200, 200));
  // A 40 x 40 box reaching 20 px past the right border; its mask covers
  // its left half only (on the image: columns 60-79, grey 60).
  cv::Mat mask = cv::Mat::zeros(40, 40, CV_8UC1);
  mask(cv::Rect(0, 0, 20, 40)).setTo(255);
  EXPECT_NEAR(meanGreyLevel(frame, mask, cv::Rect(60, 10, 40, 40)), 60.0, 1e-9);
  // Moved left over the bright half: columns 40-59, half of it bright.
  EXPECT_NEAR(meanGreyLevel(frame, mask, cv::Rect(40, 10, 40, 40)), 130.0, 1e-9);
  // Nothing of it in the image, or no mask: 0.
  EXPECT_EQ(meanGreyLevel(frame, mask, cv::Rect(120, 10, 40, 40)), 0.0);
  EXPECT_EQ(meanGreyLevel(frame, cv::Mat(), cv::Rect(60, 10, 40, 40)), 0.0);
}

TEST(FaceGrey, WeighsTheChannelsByTheFacesColour)
{
  // A grey face: the mean of the three channels.
  const FaceGrey grey = FaceGrey::ofColour(cv::Vec3d(80, 80, 80));
  EXPECT_NEAR(grey(cv::Vec3b(30, 60, 90)), 60.0, 1e-9);
  // A red face (B, G, R = 10, 10, 80): a line that shades its red by 20 reads
  // about 20 deep, not the 6.7 of the mean; a grey pixel reads its level.
  const FaceGrey red = FaceGrey::ofColour(cv::Vec3d(10, 10, 80));
  EXPECT_NEAR(red(cv::Vec3b(10, 10, 80)) - red(cv::Vec3b(10, 10, 60)), 20.0 * 0.8, 1e-9);
  EXPECT_NEAR(red(cv::Vec3b(50, 50, 50)), 50.0, 1e-9);
  // A black face has no colour to weigh by; nor has a sum of no pixels.
  EXPECT_NEAR(FaceGrey::ofColour(cv::Vec3d(0, 0, 0))(cv::Vec3b(30, 60, 90)), 60.0, 1e-9);
  EXPECT_NEAR(FaceColourSum().grey()(cv::Vec3b(30, 60, 90)), 60.0, 1e-9);
  FaceColourSum sum;
  sum.add(cv::Vec3b(0, 0, 100));
  sum.add(cv::Vec3b(0, 0, 60));
  EXPECT_NEAR(sum.grey().weights()[2], 1.0, 1e-12);
}

TEST(ColourUniformity, FaceGreyLevelIsTheMeanColourReadInItsOwnWeights)
{
  RgbdFrame frame;
  frame.rgb = cv::Mat(100, 100, CV_8UC3, cv::Scalar(10, 10, 80));
  const cv::Mat mask(40, 40, CV_8UC1, cv::Scalar(255));
  // (10*10 + 10*10 + 80*80) / 100 = 66, where the mean grey level is 33.3.
  EXPECT_NEAR(faceGreyLevel(frame, mask, cv::Rect(10, 10, 40, 40)), 66.0, 1e-9);
  EXPECT_NEAR(meanGreyLevel(frame, mask, cv::Rect(10, 10, 40, 40)), 100.0 / 3.0, 1e-9);
  EXPECT_EQ(faceGreyLevel(frame, mask, cv::Rect(120, 10, 40, 40)), 0.0);
}
}  // namespace
}  // namespace brick_pose
