// Writes every feature file of feature_files.hpp into the folder given: the command-line tests'
// inputs (a ctest fixture), so no glTF binary is committed.

#include "feature_files.hpp"

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: write_gltf_features DIR\n");
        return 2;
    }
    try {
        for (const auto& path : gltf_features::write_all(argv[1])) std::printf("wrote %s\n", path.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "write_gltf_features: %s\n", e.what());
        return 1;
    }
    return 0;
}
