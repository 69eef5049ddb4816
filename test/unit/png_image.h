#pragma once
// PNG files as cv::Mat for tests and benchmarks that use real recordings
// (test/data/mosd_learn). The core links only OpenCV's core and imgproc, so
// the files are read and written through VTK's PNG codec, which PCL's io
// library already brings in.

#include <string>

#include <opencv2/core.hpp>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>

namespace brick_pose
{
namespace test
{
/// The image as stored: CV_8UC1/3/4 or CV_16UC1 (colour in R, G, B order);
/// empty when the file cannot be read.
inline cv::Mat readPng(const std::string& path)
{
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str())) return cv::Mat();
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3] = {0, 0, 0};
  image->GetDimensions(dims);
  const int channels = image->GetNumberOfScalarComponents();
  const int depth = image->GetScalarType() == VTK_UNSIGNED_SHORT ? CV_16U : CV_8U;
  if (dims[0] <= 0 || dims[1] <= 0 || channels < 1 || channels > 4) return cv::Mat();
  const cv::Mat bottom_up(dims[1], dims[0], CV_MAKETYPE(depth, channels), image->GetScalarPointer());
  cv::Mat top_down;
  cv::flip(bottom_up, top_down, 0);  // VTK's rows start at the bottom
  return top_down;
}

/// Writes an 8-bit image (R, G, B order for colour).
inline void writePng(const std::string& path, const cv::Mat& image)
{
  cv::Mat bottom_up;
  cv::flip(image, bottom_up, 0);
  vtkNew<vtkImageData> data;
  data->SetDimensions(bottom_up.cols, bottom_up.rows, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, bottom_up.channels());
  const cv::Mat target(bottom_up.rows, bottom_up.cols, bottom_up.type(), data->GetScalarPointer());
  bottom_up.copyTo(target);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(data);
  writer->Write();
}
}  // namespace test
}  // namespace brick_pose
