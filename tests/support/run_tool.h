#pragma once
// Runs built tools and shell pipelines for the CLI tests. Output is captured through temp files,
// so large outputs cannot dead-lock on a full pipe.

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace pc::test {

struct RunResult {
    int code = -1;
    std::string out, err;
};

inline std::string tool_path(const std::string& name) {
    return std::string(PC_TOOLS_DIR) + "/" + name;
}

inline std::string slurp(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

inline void spit(const std::string& path, const std::string& bytes) {
    std::ofstream f(path, std::ios::binary);
    f << bytes;
}

/// A private temporary directory, removed with its contents at scope exit.
struct TempDir {
    std::string path;
    TempDir() {
        char tmpl[] = "/tmp/pc_test_XXXXXX";
        path = ::mkdtemp(tmpl);
    }
    ~TempDir() { (void)std::system(("rm -rf '" + path + "'").c_str()); }
    [[nodiscard]] std::string file(const std::string& name) const { return path + "/" + name; }
};

/// Runs `command` with /bin/sh (pipes allowed; `set -o pipefail` is not set) with `stdin_bytes`
/// on standard input. Tool names written as `@pc_x` are replaced by their build path.
inline RunResult run_shell(std::string command, const std::string& stdin_bytes = "") {
    for (std::size_t at; (at = command.find('@')) != std::string::npos;) {
        command.replace(at, 1, std::string(PC_TOOLS_DIR) + "/");
    }
    TempDir dir;
    spit(dir.file("in"), stdin_bytes);
    const std::string full = "( " + command + " ) <'" + dir.file("in") + "' >'" + dir.file("out") +
                             "' 2>'" + dir.file("err") + "'";
    const int status = std::system(full.c_str());
    RunResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(dir.file("out"));
    r.err = slurp(dir.file("err"));
    return r;
}

/// A shell prefix capping the virtual memory of what follows at `kib` KiB. Empty in sanitizer
/// builds, whose shadow memory needs terabytes of address space.
inline std::string memory_cap(long kib) {
#ifdef PC_SANITIZE
    (void)kib;
    return "";
#else
    return "ulimit -v " + std::to_string(kib) + "; ";
#endif
}

/// Number of lines in `s` (a final line without '\n' counts).
inline int line_count(const std::string& s) {
    int n = 0;
    for (char c : s) {
        n += c == '\n';
    }
    return n + (!s.empty() && s.back() != '\n');
}

}  // namespace pc::test
