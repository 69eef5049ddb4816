#pragma once
// The face cases: our Super4PCS against PCL 1.13's FPCS, KFPCS and
// ICP-from-identity on segmented brick top faces (see face_cases.h).

#include <string>

#include "bench_registration/options.h"

namespace bench_registration
{
/// Runs the face cases, prints their tables and returns their part of the
/// JSON line (keys and values, without braces).
std::string runFaceBench(const Options& options);
}  // namespace bench_registration
