#pragma once
// The whole-cuboid view cases (view_cases.h): our Super4PCS in whole-view
// mode against PCL 1.13's FPCS and KFPCS. Success: the pose is right
// (rotation < 5 deg, translation < 10 mm modulo the cuboid's true
// symmetries) and the method claimed it; a false success is a claimed wrong
// pose.

#include <string>

#include "bench_registration/options.h"

namespace bench_registration
{
/// Runs the view cases, prints their tables and returns their part of the
/// JSON line (keys and values, without braces).
std::string runViewBench(const Options& options);
}  // namespace bench_registration
