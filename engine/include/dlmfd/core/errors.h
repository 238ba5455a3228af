// Typed errors of the engine. The engine throws, never exits; dlmfd-solve maps them to exit status
// and summary.json (design.md 5): InvalidParameter -> status 2 before the run; the others -> the
// run ends FAILED with what() as the reason and every result written so far kept.
#pragma once

#include <stdexcept>
#include <string>

namespace dlmfd {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A scene or argument value that is not allowed. key is the dotted scene key
// ("fluid.viscosity", "particles.1.center"), value its text, allowed a phrase such as "> 0".
class InvalidParameter : public Error {
 public:
  InvalidParameter(std::string key, std::string value, std::string allowed)
      : Error(key + " = " + value + " is not allowed: expected " + allowed),
        key_(std::move(key)),
        value_(std::move(value)),
        allowed_(std::move(allowed)) {}
  const std::string& key() const { return key_; }
  const std::string& value() const { return value_; }
  const std::string& allowed() const { return allowed_; }

 private:
  std::string key_, value_, allowed_;
};

// Everything that ends a running simulation as FAILED.
class RunFailure : public Error {
 public:
  using Error::Error;
};

class SolverNotConverged : public RunFailure {
 public:
  using RunFailure::RunFailure;
};

class ConformationNotPositiveDefinite : public RunFailure {
 public:
  using RunFailure::RunFailure;
};

class ParticlesOverlap : public RunFailure {
 public:
  using RunFailure::RunFailure;
};

// NaN or Inf in a field, or a quantity beyond any physical bound.
class NumericalBlowUp : public RunFailure {
 public:
  using RunFailure::RunFailure;
};

}  // namespace dlmfd
