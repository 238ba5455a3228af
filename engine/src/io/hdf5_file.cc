#include "hdf5_file.h"

#include "dlmfd/core/errors.h"

namespace dlmfd {
namespace h5 {
namespace {

// HDF5 prints its own error stack by default; our exceptions carry the message instead.
void SilenceHdf5() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

std::string Name(hid_t loc, const std::string& name) {
  char file[1024] = {0};
  H5Fget_name(loc, file, sizeof file);
  return std::string(file) + ":" + name;
}

Handle Space(const std::vector<hsize_t>& dims) {
  if (dims.empty()) return Handle(CheckId(H5Screate(H5S_SCALAR), "dataspace"), H5Sclose);
  return Handle(
      CheckId(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "dataspace"),
      H5Sclose);
}

template <typename T>
void WriteArray(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims, const T* data,
                hid_t type) {
  Handle space = Space(dims);
  Handle set(CheckId(H5Dcreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                H5P_DEFAULT),
                     "create " + Name(loc, name)),
             H5Dclose);
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count > 0)
    Check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
          "write " + Name(loc, name));
}

template <typename T>
std::vector<T> ReadArray(hid_t loc, const std::string& name, std::vector<hsize_t>* dims,
                         hid_t type) {
  Handle set(CheckId(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open " + Name(loc, name)),
             H5Dclose);
  Handle space(CheckId(H5Dget_space(set.get()), "dataspace of " + Name(loc, name)), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> shape(static_cast<std::size_t>(rank > 0 ? rank : 0));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), shape.data(), nullptr);
  hsize_t count = 1;
  for (hsize_t d : shape) count *= d;
  std::vector<T> out(count);
  if (count > 0)
    Check(H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
          "read " + Name(loc, name));
  if (dims != nullptr) *dims = shape;
  return out;
}

Handle OpenAttribute(hid_t loc, const std::string& name) {
  return Handle(
      CheckId(H5Aopen(loc, name.c_str(), H5P_DEFAULT), "open attribute " + Name(loc, name)),
      H5Aclose);
}

template <typename T>
void WriteScalarAttribute(hid_t loc, const std::string& name, T value, hid_t type) {
  if (H5Aexists(loc, name.c_str()) > 0) H5Adelete(loc, name.c_str());
  Handle space = Space({});
  Handle attr(CheckId(H5Acreate2(loc, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      "create attribute " + Name(loc, name)),
              H5Aclose);
  Check(H5Awrite(attr.get(), type, &value), "write attribute " + Name(loc, name));
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    Reset();
    id_ = other.id_;
    closer_ = other.closer_;
    other.id_ = -1;
  }
  return *this;
}

void Handle::Reset() {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);
  id_ = -1;
}

void Check(herr_t status, const std::string& what) {
  if (status < 0) throw Error("HDF5: cannot " + what);
}

hid_t CheckId(hid_t id, const std::string& what) {
  if (id < 0) throw Error("HDF5: cannot " + what);
  return id;
}

Handle CreateFile(const std::string& path) {
  SilenceHdf5();
  return Handle(
      CheckId(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create " + path),
      H5Fclose);
}

Handle OpenFile(const std::string& path, bool writable) {
  SilenceHdf5();
  Handle fapl(CheckId(H5Pcreate(H5P_FILE_ACCESS), "file access list"), H5Pclose);
  if (!writable) H5Pset_file_locking(fapl.get(), false, true);
  return Handle(CheckId(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, fapl.get()),
                        "open " + path),
                H5Fclose);
}

bool Exists(hid_t loc, const std::string& name) {
  return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
}

void WriteDoubles(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                  const double* data) {
  WriteArray(loc, name, dims, data, H5T_NATIVE_DOUBLE);
}

void WriteInts(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
               const std::int64_t* data) {
  WriteArray(loc, name, dims, data, H5T_NATIVE_INT64);
}

std::vector<double> ReadDoubles(hid_t loc, const std::string& name, std::vector<hsize_t>* dims) {
  return ReadArray<double>(loc, name, dims, H5T_NATIVE_DOUBLE);
}

std::vector<std::int64_t> ReadInts(hid_t loc, const std::string& name, std::vector<hsize_t>* dims) {
  return ReadArray<std::int64_t>(loc, name, dims, H5T_NATIVE_INT64);
}

void WriteAttribute(hid_t loc, const std::string& name, double value) {
  WriteScalarAttribute(loc, name, value, H5T_NATIVE_DOUBLE);
}

void WriteAttribute(hid_t loc, const std::string& name, std::int64_t value) {
  WriteScalarAttribute(loc, name, value, H5T_NATIVE_INT64);
}

// A variable-length UTF-8 string: h5py reads it as a Python str (a fixed-length one as bytes).
void WriteAttribute(hid_t loc, const std::string& name, const std::string& value) {
  if (H5Aexists(loc, name.c_str()) > 0) H5Adelete(loc, name.c_str());
  Handle type(CheckId(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  Handle space = Space({});
  Handle attr(
      CheckId(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              "create attribute " + Name(loc, name)),
      H5Aclose);
  const char* text = value.c_str();
  Check(H5Awrite(attr.get(), type.get(), &text), "write attribute " + Name(loc, name));
}

void WriteText(hid_t loc, const std::string& name, const std::string& text) {
  Handle type(CheckId(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
  H5Tset_size(type.get(), text.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  Handle space = Space({});
  Handle set(CheckId(H5Dcreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                H5P_DEFAULT, H5P_DEFAULT),
                     "create " + Name(loc, name)),
             H5Dclose);
  Check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()),
        "write " + Name(loc, name));
}

std::string ReadText(hid_t loc, const std::string& name) {
  Handle set(CheckId(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), "open " + Name(loc, name)),
             H5Dclose);
  Handle type(CheckId(H5Dget_type(set.get()), "type of " + Name(loc, name)), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    throw Error("HDF5: " + Name(loc, name) + " is not a fixed-length string");
  const std::size_t size = H5Tget_size(type.get());
  std::string text(size, '\0');
  Check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()),
        "read " + Name(loc, name));
  text.resize(text.find('\0') == std::string::npos ? size : text.find('\0'));
  return text;
}

Handle OpenObject(hid_t loc, const std::string& name) {
  return Handle(CheckId(H5Oopen(loc, name.c_str(), H5P_DEFAULT), "open " + Name(loc, name)),
                H5Oclose);
}

Handle CreateGroup(hid_t loc, const std::string& name) {
  return Handle(CheckId(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                        "create group " + Name(loc, name)),
                H5Gclose);
}

bool HasAttribute(hid_t loc, const std::string& name) { return H5Aexists(loc, name.c_str()) > 0; }

double ReadDoubleAttribute(hid_t loc, const std::string& name) {
  Handle attr = OpenAttribute(loc, name);
  double value = 0.0;
  Check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value), "read attribute " + Name(loc, name));
  return value;
}

std::int64_t ReadIntAttribute(hid_t loc, const std::string& name) {
  Handle attr = OpenAttribute(loc, name);
  std::int64_t value = 0;
  Check(H5Aread(attr.get(), H5T_NATIVE_INT64, &value), "read attribute " + Name(loc, name));
  return value;
}

std::string ReadStringAttribute(hid_t loc, const std::string& name) {
  Handle attr = OpenAttribute(loc, name);
  Handle type(CheckId(H5Aget_type(attr.get()), "type of attribute " + Name(loc, name)), H5Tclose);
  if (H5Tis_variable_str(type.get()) > 0) {  // written since results format 2
    Handle memory(CheckId(H5Tcopy(H5T_C_S1), "string type"), H5Tclose);
    H5Tset_size(memory.get(), H5T_VARIABLE);
    H5Tset_cset(memory.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    Check(H5Aread(attr.get(), memory.get(), &text), "read attribute " + Name(loc, name));
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  Check(H5Aread(attr.get(), type.get(), value.data()), "read attribute " + Name(loc, name));
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

}  // namespace h5
}  // namespace dlmfd
