#pragma once
// The plots of `vplkit bench gi`, `bench direct` and `sequence`: drawn by scripts/plot.py
// (matplotlib) from the CSV/JSON the command has written, when a Python 3 with matplotlib is
// there (Debian: python3-matplotlib). Without one the plots are skipped with one line saying so;
// the CSV/JSON stay, and scripts/plot.py draws them later.

#include <filesystem>
#include <string>
#include <vector>

namespace vplkit::cli {

// Runs `scripts/plot.py KIND FOLDER EXTRA...`, which prints "wrote PATH" for each picture.
// The interpreter is $VPLKIT_PYTHON, else the first of `python3` on the PATH and
// /usr/bin/python3 that imports matplotlib (looked up once). A failure of the script (its
// message on stderr) throws vplkit::Error naming the command that failed.
void draw_plots(const std::string& kind, const std::filesystem::path& folder,
                const std::vector<std::string>& extra = {});

}  // namespace vplkit::cli
