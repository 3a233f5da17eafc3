#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <pc/core/error.h>
#include <pc/io/read.h>
#include <pc/io/sink.h>

namespace pc::cli {

inline constexpr int kOk = 0;       ///< success
inline constexpr int kFailure = 1;  ///< bad data, I/O, algorithm failure
inline constexpr int kUsage = 2;    ///< unknown option, bad value, validate() said no

/// What a tool writes to its output: a cloud (PCD or PLY), a text report, or an image (bytes
/// written with write_text, never to a terminal).
enum class Output { kCloud, kText, kImage };

/// The standard streams of one run, as chosen by -i/-o. Created by Tool::run.
class Streams {
public:
    /// Reads the whole input (stdin by default). Reader notes are printed with -v.
    [[nodiscard]] io::Blob read();
    /// Reads `path` ("-" = stdin), as read() does.
    [[nodiscard]] io::Blob read(const std::string& path);
    /// Writes a cloud: PCD (or PLY when `--to ply` or `-o x.ply`), atomically for -o FILE.
    void write(const io::Blob& blob);
    /// Writes a text report, atomically for -o FILE.
    void write_text(std::string_view text);
    /// Prints `<tool>: <message> [elapsed]` on stderr with -v or --progress, and by itself once
    /// the run has taken a second when stderr is a terminal (work in progress); never with -q.
    void note(const std::string& message) const;
    /// Prints `<tool>: warning: <message>` on stderr unless -q was given: a valid input whose
    /// result is doubtful (a filter that dropped nearly everything, a count of 0).
    void warn(const std::string& message) const;
    /// Prints `<tool>: error: <message>` on stderr and makes the run exit 1 when the body returns:
    /// one input of several failed, the others go on (report_each).
    void fail(const std::string& message);
    /// Every option of the tool as used (the preset first, then each option's value as text).
    [[nodiscard]] std::vector<std::pair<std::string, std::string>> parameters() const;
    [[nodiscard]] const std::string& tool() const { return tool_; }
    [[nodiscard]] bool verbose() const { return verbose_; }
    [[nodiscard]] const std::string& input_name() const { return input_name_; }
    /// The format the last read() recognised ("pcd binary", "ply ascii", ...).
    [[nodiscard]] const std::string& input_format() const { return input_format_; }

private:
    friend class Tool;
    void write_bytes(const std::function<void(io::ByteSink&)>& producer);

    std::string tool_;
    std::function<std::vector<std::pair<std::string, std::string>>()> parameters_;
    std::string input_ = "-", output_ = "-", input_name_;
    std::string encoding_ = "binary", container_ = "auto", input_format_;
    std::uint64_t max_input_bytes_ = io::kDefaultMaxInputBytes;
    bool verbose_ = false, quiet_ = false, written_ = false, failed_ = false;
    bool ply_scalars_ = false, progress_ = false, stderr_terminal_ = false;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// `what` with `input` in front ("tree.ply: no field 'opacity'") unless it starts with it, as
/// a reader's errors do.
[[nodiscard]] std::string naming_input(const std::string& input, const std::string& what);

/// Runs `f` and returns what it returns; a pc::IoError gets naming_input(input, ...), so that an
/// algorithm's error names the file as a reader's does.
template <class F>
auto naming(const std::string& input, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const IoError& e) {
        throw IoError(naming_input(input, e.what()));
    }
}

/// The whole text of a small file (camera, truth, matrix, plot data); pc::IoError
/// "<path>: cannot read the <what>: <reason>" when it cannot be read (a directory included).
[[nodiscard]] std::string read_text_file(const std::string& path, const std::string& what);

/// The toolkit's version ("0.1.0"), as --version prints it and reports carry it.
[[nodiscard]] const char* version();
/// A real number for option `--option`; throws pc::InvalidArgument naming it.
[[nodiscard]] double parse_double(const std::string& option, const std::string& text);
/// "x,y,z" for option `--option`; throws pc::InvalidArgument naming it.
[[nodiscard]] std::array<double, 3> parse_triple(const std::string& option,
                                                 const std::string& text);
/// The cloud formats a tool writes.
enum class Container { kPcd, kPly, kText };
/// The container `--to` names (pcd, ply, xyz), or for `auto` the one `path`'s extension names:
/// .ply PLY; .xyz, .txt, .asc XYZ text; anything else PCD, except extensions of formats this
/// toolkit does not write (.las, .laz, .e57, .obj, .csv, ...): pc::InvalidArgument saying so,
/// rather than PCD bytes under a name that promises something else.
[[nodiscard]] Container container_for(const std::string& path, const std::string& to = "auto");
/// Writes a cloud to `path` (binary PCD, binary PLY or XYZ text as container_for says) through a
/// temporary file renamed into place, so a failure never leaves a partial file.
void write_cloud_file(const std::string& path, const io::Blob& blob);
/// Writes text to `path` the same way (temporary file, fsync, rename).
void write_text_file(const std::string& path, std::string_view text);

/// Tunes glibc's malloc for large clouds (see CONTRIBUTING, "Speed and memory"): Tool::run()
/// calls it first; a program without a Tool (bench/dbscan_loop) calls it itself. Once per process.
void tune_allocator();

/// Command-line front end shared by every tool: option binding with generated --help, the common
/// options (-i -o -v -q --format --version), exit codes and error lines. See docs/architecture.md.
class Tool {
public:
    Tool(std::string name, std::string summary, Output output = Output::kCloud);
    ~Tool();

    // Bind `--name` to a Params field. The default shown in --help is the field's current value.
    void option(const std::string& name, double* field, const std::string& help);
    void option(const std::string& name, float* field, const std::string& help);
    void option(const std::string& name, int* field, const std::string& help);
    void option(const std::string& name, std::uint32_t* field, const std::string& help);
    void option(const std::string& name, std::uint64_t* field, const std::string& help);
    void option(const std::string& name, std::string* field, const std::string& help);
    /// An optional number: "off" (the default text when unset) leaves it empty.
    void option(const std::string& name, std::optional<double>* field, const std::string& help);
    /// A comma-separated triple such as `--min -1,-1,0`.
    void option(const std::string& name, std::array<double, 3>* field, const std::string& help);
    /// A switch without a value.
    void flag(const std::string& name, bool* field, const std::string& help);
    /// An option whose text is parsed by `parse` (which throws pc::InvalidArgument on bad text).
    /// `show`, when given, says the value as used for reports (after a preset changed it);
    /// without it, reports show the text given or the default text.
    void option(const std::string& name,
                const std::string& default_text,
                std::function<void(const std::string&)> parse,
                const std::string& help,
                std::function<std::string()> show = {});
    /// `--preset NAME`: `apply` runs before every explicitly given option, so flags override it.
    void presets(const std::vector<std::string>& names,
                 std::function<void(const std::string&)> apply);
    /// Positional input paths (`pc_extent a.ply b.pcd`). An explicit -i is the first input; when
    /// fewer than `min_count` paths are given, stdin ("-") comes first (`pc_compare B < A`).
    void inputs(std::vector<std::string>* paths,
                const std::string& help,
                std::size_t min_count = 1);
    /// The tool makes its cloud instead of reading one (pc_synth): no -i, no --max-input-bytes.
    /// With inputs(), the positional paths are not clouds (pc_maskeval's folders): no stdin.
    void no_input();
    /// Extra text printed at the end of --help.
    void epilog(const std::string& text);

    /// Parses argv, runs `body` and maps every outcome to an exit code and at most one stderr line.
    int run(int argc, char** argv, const std::function<void(Streams&)>& body);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace pc::cli
