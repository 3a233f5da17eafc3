#pragma once
// `--plot FILE.png` for the report tools: the numbers as FILE.csv, drawn into FILE.png by pc_plot
// in a process of its own, so that the tool itself does not load OpenCV (50 MB resident).

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <pc/charts/panel.h>
#include <pc/cli/tool.h>
#include <pc/core/error.h>

extern char** environ;

namespace pc::tools {

/// A usage error unless `path` names a PNG (checked before any work).
inline void check_plot_path(const std::string& path) {
    const std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
    if (!path.empty() && ext != ".png" && ext != ".PNG") {
        throw InvalidArgument("--plot: the plot is a PNG, name it FILE.png, got '" + path + "'");
    }
}

/// pc_plot beside this program (build/bin, an install's bin), else the one on PATH.
inline std::string pc_plot_program() {
    char self[4096];
    const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        self[n] = '\0';
        const auto beside = std::filesystem::path(self).parent_path() / "pc_plot";
        if (std::filesystem::exists(beside)) {
            return beside.string();
        }
    }
    return "pc_plot";
}

/// Writes the panels' numbers at charts::csv_path(path) and has pc_plot draw them at `path`.
inline void write_plot(const std::string& path, const std::vector<charts::Panel>& panels) {
    const std::string csv = charts::csv_path(path);
    cli::write_text_file(csv, charts::panels_csv(panels));
    std::string program = pc_plot_program(), o = "-o", q = "-q";
    std::string in = csv, out = path;
    char* argv[] = {program.data(), in.data(), o.data(), out.data(), q.data(), nullptr};
    pid_t pid = 0;
    const int e = ::posix_spawnp(&pid, program.c_str(), nullptr, nullptr, argv, environ);
    if (e != 0) {
        throw IoError(path + ": cannot run pc_plot to draw the plot: " + std::strerror(e) +
                      " (its numbers are in " + csv + ")");
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        throw IoError(path + ": pc_plot could not draw the plot (its numbers are in " + csv + ")");
    }
}

}  // namespace pc::tools
