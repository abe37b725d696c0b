// Where handlab's data files are: the study protocols and published values (studies/), the
// example protocols (studies/examples/) and the real recordings (data/leap/). A build reads
// them from the source tree, named as the docs name them; the package installs the same tree
// under /usr/share/handlab, where the same names find them from any folder.
#pragma once

#include <string>

namespace handlab::util {

// The folder the package installs the data into (CMake's DATADIR/handlab: /usr/share/handlab).
std::string installed_data_directory();

// A data file as the docs name it: `path` itself where it exists; else, for a relative path,
// the same path under the installed data directory where it exists there; else `path`
// unchanged, so that the reader's error names what was asked for.
std::string find_data_file(const std::string& path);

}  // namespace handlab::util
