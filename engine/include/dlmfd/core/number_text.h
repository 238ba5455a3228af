// Numbers as text in InvalidParameter messages, so that every rule of every module writes the value
// of a key the way the scene file reads it back (scene/scene_file.h, core/errors.h).
#pragma once

#include <Eigen/Core>
#include <string>

namespace dlmfd {

// The shortest decimal text that reads back as exactly x ("0.1", "2.0", "1e-300").
std::string ExactText(double x);
// Four significant digits, for derived numbers in messages (a gap, a node count).
std::string ShortText(double x);
// A point or a vector of the scene ("[0.5, 1.0]"), each number as ExactText.
std::string VecText(const Eigen::Vector2d& v);

}  // namespace dlmfd
