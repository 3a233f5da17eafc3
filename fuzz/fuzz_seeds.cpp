// Writes the fuzzers' seed corpora: the malformed-input and edge-case corpus of the tests
// (tests/support/corpus.h) and the shipped sample clouds for fuzz_cloud, the shipped JSON files
// for fuzz_json.   fuzz_seeds OUT_DIR  ->  OUT_DIR/cloud/*, OUT_DIR/json/*
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "support/corpus.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: fuzz_seeds OUT_DIR\n";
        return 2;
    }
    const fs::path out = argv[1];
    fs::create_directories(out / "cloud");
    fs::create_directories(out / "json");
    int n = 0;
    const auto write = [&](const fs::path& path, const std::string& bytes) {
        std::ofstream(path, std::ios::binary) << bytes;
        ++n;
    };
    for (const auto& f : pc::test::malformed_corpus()) {
        write(out / "cloud" / ("malformed_" + std::to_string(n)), f.bytes);
    }
    for (const auto& f : pc::test::edge_corpus()) {
        write(out / "cloud" / ("edge_" + std::to_string(n)), f.bytes);
    }
    // every sample file, sub-folders (views/) included
    for (const auto& entry : fs::recursive_directory_iterator(PC_SAMPLE_CLOUDS_DIR)) {
        if (!entry.is_regular_file()) {
            continue;
        }
        const auto ext = entry.path().extension();
        const bool small = entry.file_size() <= 256 * 1024;
        if (small && (ext == ".pcd" || ext == ".ply" || ext == ".json")) {
            std::ifstream in(entry.path(), std::ios::binary);
            const std::string bytes((std::istreambuf_iterator<char>(in)), {});
            write(out / (ext == ".json" ? "json" : "cloud") / entry.path().filename(), bytes);
        }
    }
    std::cout << n << " seeds in " << out << "\n";
    return 0;
}
