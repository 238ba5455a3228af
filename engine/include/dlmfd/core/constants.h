// Mathematical constants shared by the engine, its tests and its benchmarks (one definition).
#pragma once

namespace dlmfd {

// pi to double precision (std::numbers::pi is C++20; the engine is C++17).
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace dlmfd
