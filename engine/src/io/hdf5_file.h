// Thin RAII wrappers over the HDF5 C API for the results directory and checkpoints: handles that
// close themselves, whole-array writes and reads of doubles and 64-bit integers, scalar and small
// vector attributes. Every failure throws dlmfd::Error naming the file and the object.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dlmfd {
namespace h5 {

// An HDF5 identifier closed by the given function when the handle goes.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer)
      : id_(id),
        closer_(closer) {}
  Handle(Handle&& other) noexcept
      : id_(other.id_),
        closer_(other.closer_) {
    other.id_ = -1;
  }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { Reset(); }
  void Reset();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// Creates (truncating) or opens a file. Readers open without HDF5's file lock so that a file still
// being appended by a running solver can be read.
Handle CreateFile(const std::string& path);
Handle OpenFile(const std::string& path, bool writable);

bool Exists(hid_t loc, const std::string& name);
void WriteDoubles(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                  const double* data);
void WriteInts(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
               const std::int64_t* data);
// Reads a whole dataset; `dims` receives its shape.
std::vector<double> ReadDoubles(hid_t loc, const std::string& name,
                                std::vector<hsize_t>* dims = nullptr);
std::vector<std::int64_t> ReadInts(hid_t loc, const std::string& name,
                                   std::vector<hsize_t>* dims = nullptr);

void WriteAttribute(hid_t loc, const std::string& name, double value);
void WriteAttribute(hid_t loc, const std::string& name, std::int64_t value);
void WriteAttribute(hid_t loc, const std::string& name, const std::string& value);
// A scalar string dataset (texts too long for an attribute's 64 KiB: the scene of many particles).
void WriteText(hid_t loc, const std::string& name, const std::string& text);
std::string ReadText(hid_t loc, const std::string& name);
// Opens a group or dataset by its path relative to `loc` (attributes are written on it).
Handle OpenObject(hid_t loc, const std::string& name);
Handle CreateGroup(hid_t loc, const std::string& name);
bool HasAttribute(hid_t loc, const std::string& name);

double ReadDoubleAttribute(hid_t loc, const std::string& name);
std::int64_t ReadIntAttribute(hid_t loc, const std::string& name);
std::string ReadStringAttribute(hid_t loc, const std::string& name);

// Throws dlmfd::Error("what") when status < 0.
void Check(herr_t status, const std::string& what);
hid_t CheckId(hid_t id, const std::string& what);

}  // namespace h5
}  // namespace dlmfd
