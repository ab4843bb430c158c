#pragma once
// The frames of an output HDF5 file as tests compare them: their count, and every dataset of a
// group as raw bytes (== is bitwise equality).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <string>
#include <utility>
#include <vector>

namespace scpdyn::test
{

/// The raw bytes of every dataset under `group` of `file`, by path.
inline std::vector<std::pair<std::string, std::vector<char>>> datasetBytes(const std::string &file,
                                                                           const std::string &group)
{
  std::vector<std::pair<std::string, std::vector<char>>> out;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  if (f < 0)
    return out;
  const hid_t g = H5Gopen2(f, group.c_str(), H5P_DEFAULT);
  EXPECT_GE(g, 0) << file << ":" << group;
  struct Visit
  {
    hid_t g;
    std::vector<std::pair<std::string, std::vector<char>>> *out;
  } visit{g, &out};
  H5Ovisit(
      g, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char *name, const H5O_info_t *info, void *data) -> herr_t {
        if (info->type != H5O_TYPE_DATASET)
          return 0;
        auto *v = static_cast<Visit *>(data);
        const hid_t d = H5Dopen2(v->g, name, H5P_DEFAULT);
        const hid_t type = H5Dget_type(d);
        const hid_t space = H5Dget_space(d);
        std::vector<char> bytes(size_t(H5Sget_simple_extent_npoints(space)) * H5Tget_size(type));
        if (!bytes.empty())
          H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data());
        v->out->push_back({name, bytes});
        H5Sclose(space);
        H5Tclose(type);
        H5Dclose(d);
        return 0;
      },
      &visit);
  H5Gclose(g);
  H5Fclose(f);
  return out;
}

inline hsize_t frameCount(const std::string &file)
{
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t g = H5Gopen2(f, "frames", H5P_DEFAULT);
  H5G_info_t info;
  H5Gget_info(g, &info);
  H5Gclose(g);
  H5Fclose(f);
  return info.nlinks;
}

} // namespace scpdyn::test
