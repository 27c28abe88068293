#pragma once
// data.xdmf: an XDMF 2 description of data.h5's 3-D datasets on their uniform grid, so that ParaView
// and VisIt open the fields (the stored half z >= 0 under equatorial symmetry).
#include <string>

#include "data_file.hpp"

namespace bhnsid::io_hdf5 {

/// The array name a viewer shows for a dataset: "alp" for /ADMBase/alp, "bhnsid_chi" for /variables/chi.
std::string viewer_name(const std::string& dataset_path);

std::string xdmf_text(const DataFile& file, const std::string& h5_name);

}  // namespace bhnsid::io_hdf5
