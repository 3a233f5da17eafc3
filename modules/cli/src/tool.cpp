#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <numeric>
#include <sstream>

#include <fcntl.h>
#include <malloc.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <boost/program_options.hpp>
#include <pcl/console/print.h>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/io/pcd.h>
#include <pc/io/ply.h>
#include <pc/io/text.h>

namespace po = boost::program_options;

namespace pc::cli {

namespace {

struct Binding {
    std::string name;
    bool is_flag = false;
    std::function<void(const std::string&)> assign;  // called only for options given explicitly
    std::function<std::string()> show;               // the value as used, for reports
};

template <class T>
T parse_number(const std::string& option, const std::string& text) {
    T v{};
    const char* b = text.data();
    const char* e = b + text.size();
    if (b != e && *b == '+') {
        ++b;
    }
    const auto r = std::from_chars(b, e, v);
    if (b == e || r.ec != std::errc{} || r.ptr != e) {
        throw InvalidArgument("--" + option + ": '" + text + "' is not a valid " +
                              (std::is_floating_point_v<T> ? "number" : "whole number") +
                              (std::is_unsigned_v<T> ? " >= 0" : ""));
    }
    return v;
}

template <class T>
std::string number_text(T v) {
    if constexpr (std::is_floating_point_v<T>) {
        return format_number(static_cast<double>(v));
    } else {
        return std::to_string(v);
    }
}

bool ends_with(const std::string& s, std::string_view suffix) {
    if (s.size() < suffix.size()) {
        return false;
    }
    std::string tail = s.substr(s.size() - suffix.size());
    for (char& c : tail) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return tail == suffix;
}

/// An output written so that a failure never leaves a partial file: a regular file (or a new
/// one) is written next to its destination and renamed into place only after success, keeping
/// an existing file's permission bits; through a symbolic link, next to and onto the link's
/// target (the link stays). Anything else that exists (/dev/null, a FIFO, a terminal, a
/// socket) is written directly: renaming over it would replace the device or pipe with a file.
class AtomicFile {
public:
    explicit AtomicFile(const std::string& path) : path_(path) {
        struct stat st {};
        const bool exists = ::stat(path.c_str(), &st) == 0;
        if (exists && !S_ISREG(st.st_mode)) {
            if (S_ISDIR(st.st_mode)) {
                throw IoError(path + ": is a directory");
            }
            fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
            if (fd_ < 0) {
                throw IoError(path + ": cannot open output: " + std::strerror(errno));
            }
            direct_ = true;
            return;
        }
        mode_t mode = 0;
        if (exists) {
            mode = st.st_mode & 07777;  // an existing file keeps its permission bits
            struct stat link {};
            if (::lstat(path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {
                char* real = ::realpath(path.c_str(), nullptr);
                if (real == nullptr) {
                    throw IoError(path + ": cannot resolve the link: " + std::strerror(errno));
                }
                target_ = real;
                std::free(real);
            }
        } else {
            const mode_t mask = ::umask(0);
            ::umask(mask);
            mode = 0666 & ~mask;
        }
        if (target_.empty()) {
            target_ = path;
        }
        tmp_ = target_ + ".tmp.XXXXXX";
        fd_ = ::mkstemp(tmp_.data());
        if (fd_ < 0) {
            throw IoError(path + ": cannot create output: " + std::strerror(errno));
        }
        (void)::fchmod(fd_, mode);
    }
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    ~AtomicFile() {
        if (fd_ >= 0) {
            ::close(fd_);
            if (!direct_) {
                ::unlink(tmp_.c_str());
            }
        }
    }
    [[nodiscard]] int fd() const { return fd_; }
    void commit() {
        if (direct_) {
            const int fd = fd_;
            fd_ = -1;
            if (::close(fd) != 0) {
                throw IoError(path_ + ": write failed: " + std::strerror(errno));
            }
            return;
        }
        if (::fsync(fd_) != 0 || ::close(fd_) != 0) {
            fd_ = -1;
            ::unlink(tmp_.c_str());
            throw IoError(path_ + ": write failed: " + std::strerror(errno));
        }
        fd_ = -1;
        if (::rename(tmp_.c_str(), target_.c_str()) != 0) {
            const int err = errno;
            ::unlink(tmp_.c_str());
            throw IoError(path_ + ": cannot rename into place: " + std::strerror(err));
        }
    }

private:
    std::string path_, target_, tmp_;
    int fd_ = -1;
    bool direct_ = false;  // an existing device, FIFO or socket: written where it is
};

}  // namespace

const char* version() { return PC_VERSION; }

std::string naming_input(const std::string& input, const std::string& what) {
    return what.rfind(input + ":", 0) == 0 ? what : input + ": " + what;
}

std::string read_text_file(const std::string& path, const std::string& what) {
    std::ifstream f(path, std::ios::binary);
    if (!f || std::filesystem::is_directory(path)) {
        throw IoError(path + ": cannot read the " + what + ": " +
                      (f ? std::string("is a directory") : std::strerror(errno)));
    }
    std::stringstream text;
    text << f.rdbuf();
    return text.str();
}

double parse_double(const std::string& option, const std::string& text) {
    return parse_number<double>(option, text);
}

std::array<double, 3> parse_triple(const std::string& option, const std::string& text) {
    std::array<double, 3> out{};
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = text.find(',', start);
        if ((k < 2) == (comma == std::string::npos)) {
            throw InvalidArgument("--" + option + ": expected x,y,z, got '" + text + "'");
        }
        out[k] = parse_number<double>(option, text.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

Container container_for(const std::string& path, const std::string& to) {
    if (to == "pcd" || to == "ply" || to == "xyz") {
        return to == "pcd" ? Container::kPcd : to == "ply" ? Container::kPly : Container::kText;
    }
    if (to != "auto") {
        throw InvalidArgument("--to must be pcd, ply, xyz or auto, got '" + to + "'");
    }
    if (ends_with(path, ".ply")) {
        return Container::kPly;
    }
    for (const char* ext : {".xyz", ".txt", ".asc"}) {
        if (ends_with(path, ext)) {
            return Container::kText;
        }
    }
    for (const char* ext : {".las", ".laz", ".e57", ".obj", ".stl", ".off", ".vtk", ".ptx", ".pts",
                            ".csv", ".bin", ".npy", ".npz", ".h5", ".splat", ".glb", ".gltf"}) {
        if (ends_with(path, ext)) {
            throw InvalidArgument(path +
                                  ": this toolkit writes PCD, PLY and XYZ text (.pcd, .ply, "
                                  ".xyz), not " +
                                  std::string(ext) +
                                  "; convert the PCD with another tool (PDAL: pdal translate), "
                                  "or give --to pcd to write PCD under this name");
        }
    }
    return Container::kPcd;
}

namespace {

void write_container(Container c,
                     io::PcdEncoding pcd,
                     bool binary,
                     bool ply_scalars,
                     const io::Blob& blob,
                     io::ByteSink& sink) {
    switch (c) {
        case Container::kPly:
            io::write_ply(blob, binary, sink, ply_scalars);
            break;
        case Container::kText:
            io::write_text(blob, sink);
            break;
        case Container::kPcd:
            io::write_pcd(blob, pcd, sink);
            break;
    }
}

}  // namespace

void write_cloud_file(const std::string& path, const io::Blob& blob) {
    const Container c = container_for(path);
    AtomicFile file(path);
    io::FdSink sink(file.fd(), path);
    write_container(c, io::PcdEncoding::kBinary, true, false, blob, sink);
    file.commit();
}

void write_text_file(const std::string& path, std::string_view text) {
    AtomicFile file(path);
    io::FdSink sink(file.fd(), path);
    sink.write(text.data(), text.size());
    file.commit();
}

// ---------------------------------------------------------------------------------------------

io::Blob Streams::read() { return read(input_); }

io::Blob Streams::read(const std::string& path) {
    io::ReadResult r = io::read_cloud(path, max_input_bytes_);
    input_format_ = r.format;
    input_name_ = io::display_name(path);
    for (const auto& n : r.notes) {
        note(input_name_ + ": " + n);
    }
    note(input_name_ + ": " + std::to_string(r.blob.size()) + " points, " + r.format);
    return std::move(r.blob);
}

void Streams::note(const std::string& message) const {
    // Elapsed time since the tool started: progress and cost of each step on large clouds.
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (!quiet_ && (verbose_ || progress_ || (stderr_terminal_ && t >= 1.0))) {
        char stamp[32];
        std::snprintf(stamp, sizeof stamp, " [%.3f s]", t);
        std::cerr << tool_ << ": " << message << stamp << std::endl;
    }
}

void Streams::fail(const std::string& message) {
    failed_ = true;
    std::cerr << tool_ << ": error: " << message << std::endl;
}

std::vector<std::pair<std::string, std::string>> Streams::parameters() const {
    return parameters_ ? parameters_() : std::vector<std::pair<std::string, std::string>>{};
}

void Streams::warn(const std::string& message) const {
    if (!quiet_) {
        std::cerr << tool_ << ": warning: " << message << std::endl;
    }
}

void Streams::write_bytes(const std::function<void(io::ByteSink&)>& producer) {
    if (written_) {
        throw Error("internal: a tool wrote its output twice");
    }
    written_ = true;
    if (output_ == "-") {
        io::FdSink sink(1, "<stdout>");
        producer(sink);
        return;
    }
    AtomicFile file(output_);
    io::FdSink sink(file.fd(), output_);
    producer(sink);
    file.commit();
    note("wrote " + output_);
}

void Streams::write(const io::Blob& blob) {
    const Container c = container_for(output_, container_);
    const io::PcdEncoding e = encoding_ == "ascii"    ? io::PcdEncoding::kAscii
                              : encoding_ == "binary" ? io::PcdEncoding::kBinary
                                                      : io::PcdEncoding::kBinaryCompressed;
    write_bytes([&](io::ByteSink& sink) {
        write_container(c, e, encoding_ != "ascii", ply_scalars_, blob, sink);
    });
}

void Streams::write_text(std::string_view text) {
    write_bytes([&](io::ByteSink& sink) { sink.write(text.data(), text.size()); });
}

// ---------------------------------------------------------------------------------------------

struct Tool::Impl {
    std::string name, summary, epilog;
    Output output;
    po::options_description own{"Options"};
    std::vector<Binding> bindings;
    std::function<void(const std::string&)> apply_preset;
    std::string preset;
    std::vector<std::string>* inputs = nullptr;
    std::string inputs_help;
    std::size_t min_inputs = 1;
    bool reads = true;

    /// The options every tool has (help, version, -i, -o, -v, -q, and the output encoding for
    /// tools that write clouds), bound to `io`.
    po::options_description common_options(Streams& io) const;
    /// The usage text --help prints.
    void print_help(const po::options_description& all) const;
    /// The preset first, then every option given on the command line (a defaulted one does not
    /// override the preset).
    void apply_bindings(const po::variables_map& vm) const;
    /// Usage errors of the output options (encoding, container, binary to a terminal).
    void check_output(const Streams& io) const;
};

po::options_description Tool::Impl::common_options(Streams& io) const {
    const bool cloud_out = output == Output::kCloud;
    po::options_description common("Common options");
    common.add_options()("help,h", "print this help and exit")("version", "print the version");
    if (reads) {
        common.add_options()("input,i", po::value<std::string>(&io.input_)->default_value("-"),
                             "input cloud: PCD, PLY or XYZ text, by content ('-' = stdin)");
    }
    common.add_options()("output,o", po::value<std::string>(&io.output_)->default_value("-"),
                         cloud_out ? "output cloud ('-' = stdout); a file is written to a "
                                     "temporary file and renamed, a device or FIFO directly"
                         : output == Output::kImage ? "output image ('-' = stdout)"
                                                    : "output report ('-' = stdout)");
    if (reads) {
        common.add_options()(
            "max-input-bytes",
            po::value<std::uint64_t>(&io.max_input_bytes_)->default_value(io.max_input_bytes_),
            "refuse inputs larger than this");
    }
    common.add_options()("verbose,v", po::bool_switch(&io.verbose_), "notes and timings on stderr")(
        "progress", po::bool_switch(&io.progress_),
        "the notes of work in progress on stderr (by itself on a terminal once a run has taken "
        "a second)")("quiet,q", po::bool_switch(&io.quiet_), "no notes at all");
    if (cloud_out) {
        common.add_options()("format",
                             po::value<std::string>(&io.encoding_)->default_value("binary"),
                             "PCD encoding: binary, ascii or compressed (PLY: binary or ascii)")(
            "to", po::value<std::string>(&io.container_)->default_value("auto"),
            "output container: pcd, ply, xyz (text: a //X Y Z ... line, then a point a line), or "
            "auto (by -o's extension: .ply PLY, .xyz .txt .asc text, else PCD; .las and other "
            "formats refused)")(
            "ply-scalars", po::bool_switch(&io.ply_scalars_),
            "PLY: write every field but x y z, normals, colour and intensity as scalar_NAME, "
            "which CloudCompare loads as scalar fields by itself");
    }
    return common;
}

void Tool::Impl::print_help(const po::options_description& all) const {
    std::cout << name << " - " << summary << "\n\nUsage: " << name
              << (inputs  ? " [options] [IN ...] [-o OUT]\n  IN ...: " + inputs_help
                  : reads ? std::string(" [options] [-i IN] [-o OUT]")
                          : std::string(" [options] [-o OUT]"))
              << "\n"
              << all << "\nExit status: 0 success, 1 bad data or I/O error, 2 usage error.\n"
              << epilog;
}

void Tool::Impl::apply_bindings(const po::variables_map& vm) const {
    if (apply_preset && !preset.empty()) {
        apply_preset(preset);
    }
    for (const Binding& b : bindings) {
        const auto it = vm.find(b.name);
        if (it == vm.end() || it->second.defaulted()) {
            continue;
        }
        if (b.is_flag) {
            if (it->second.as<bool>()) {
                b.assign("");
            }
        } else {
            b.assign(it->second.as<std::string>());
        }
    }
}

void Tool::Impl::check_output(const Streams& io) const {
    if (output == Output::kCloud) {
        if (io.encoding_ != "binary" && io.encoding_ != "ascii" && io.encoding_ != "compressed") {
            throw InvalidArgument("--format must be binary, ascii or compressed, got '" +
                                  io.encoding_ + "'");
        }
        const Container c = container_for(io.output_, io.container_);  // before any work
        if (c != Container::kPcd && io.encoding_ == "compressed") {
            throw InvalidArgument("--format compressed exists for PCD only");
        }
        if (io.output_ == "-" && io.encoding_ != "ascii" && c != Container::kText && ::isatty(1)) {
            throw InvalidArgument(
                "refusing to write a binary cloud to a terminal; use -o FILE, "
                "a pipe, or --format ascii");
        }
    }
    if (output == Output::kImage && io.output_ == "-" && ::isatty(1)) {
        throw InvalidArgument(
            "refusing to write an image to a terminal; use -o FILE.png or a pipe");
    }
}

Tool::Tool(std::string name, std::string summary, Output output) : impl_(std::make_unique<Impl>()) {
    impl_->name = std::move(name);
    impl_->summary = std::move(summary);
    impl_->output = output;
}

Tool::~Tool() = default;

void Tool::option(const std::string& name,
                  const std::string& default_text,
                  std::function<void(const std::string&)> parse,
                  const std::string& help,
                  std::function<std::string()> show) {
    impl_->own.add_options()(name.c_str(),
                             po::value<std::string>()->default_value(default_text, default_text),
                             help.c_str());
    if (!show) {
        // The text given, or the default: what reproduces the run.
        auto given = std::make_shared<std::string>(default_text);
        parse = [given, parse = std::move(parse)](const std::string& s) {
            parse(s);
            *given = s;
        };
        show = [given] { return *given; };
    }
    impl_->bindings.push_back({name, false, std::move(parse), std::move(show)});
}

namespace {
template <class T>
void bind_number(Tool& tool, const std::string& name, T* field, const std::string& help) {
    tool.option(
        name, number_text(*field),
        [field, name](const std::string& s) { *field = parse_number<T>(name, s); }, help,
        [field] { return number_text(*field); });
}
}  // namespace

void Tool::option(const std::string& name, double* field, const std::string& help) {
    bind_number(*this, name, field, help);
}
void Tool::option(const std::string& name, float* field, const std::string& help) {
    bind_number(*this, name, field, help);
}
void Tool::option(const std::string& name, int* field, const std::string& help) {
    bind_number(*this, name, field, help);
}
void Tool::option(const std::string& name, std::uint32_t* field, const std::string& help) {
    bind_number(*this, name, field, help);
}
void Tool::option(const std::string& name, std::uint64_t* field, const std::string& help) {
    bind_number(*this, name, field, help);
}

void Tool::option(const std::string& name, std::optional<double>* field, const std::string& help) {
    option(
        name, *field ? number_text(**field) : "off",
        [field, name](const std::string& s) {
            if (s == "off") {
                field->reset();
            } else {
                *field = parse_number<double>(name, s);
            }
        },
        help, [field] { return *field ? number_text(**field) : std::string("off"); });
}

void Tool::option(const std::string& name, std::string* field, const std::string& help) {
    option(
        name, *field, [field](const std::string& s) { *field = s; }, help,
        [field] { return *field; });
}

void Tool::option(const std::string& name, std::array<double, 3>* field, const std::string& help) {
    const auto show = [field] {
        const auto& w = *field;
        return number_text(w[0]) + "," + number_text(w[1]) + "," + number_text(w[2]);
    };
    option(
        name, show(), [field, name](const std::string& s) { *field = parse_triple(name, s); }, help,
        show);
}

void Tool::flag(const std::string& name, bool* field, const std::string& help) {
    impl_->own.add_options()(name.c_str(), po::bool_switch(), help.c_str());
    impl_->bindings.push_back({name, true, [field](const std::string&) { *field = true; },
                               [field] { return std::string(*field ? "true" : "false"); }});
}

void Tool::presets(const std::vector<std::string>& names,
                   std::function<void(const std::string&)> apply) {
    std::string list;
    for (const auto& n : names) {
        list += (list.empty() ? "" : ", ") + n;
    }
    impl_->own.add_options()(
        "preset", po::value<std::string>(&impl_->preset),
        ("named parameter set, applied before explicit options: " + list).c_str());
    impl_->apply_preset = [names, list, apply = std::move(apply)](const std::string& p) {
        if (std::find(names.begin(), names.end(), p) == names.end()) {
            throw InvalidArgument("--preset: unknown preset '" + p + "' (known: " + list + ")");
        }
        apply(p);
    };
}

void Tool::no_input() { impl_->reads = false; }

void Tool::epilog(const std::string& text) { impl_->epilog = text; }

void Tool::inputs(std::vector<std::string>* paths, const std::string& help, std::size_t min_count) {
    impl_->inputs = paths;
    impl_->inputs_help = help;
    impl_->min_inputs = min_count;
}

namespace {

/// Page faults are the largest single cost of a tool on a large cloud (a fault per 4 KiB page
/// touched for the first time, ~10 us each on a virtual machine): 33k of them were 40 % of
/// pc_dbscan's wall time on 1M points. So every block comes from the heap (reused after free
/// without new faults, never trimmed mid-run), the heap grows in one 1 GiB virtual reservation,
/// and that range asks for transparent huge pages (one fault per 2 MiB; honoured when the system
/// allows THP on madvise, the Debian default). Memory that is never touched costs nothing.
/// Not under the sanitizers, which bring their own allocator.
void tune_allocator_once() {
#ifndef PC_SANITIZE
    constexpr int kReserve = 1 << 30;
    if (mallopt(M_MMAP_MAX, 0) == 0 || mallopt(M_TRIM_THRESHOLD, INT_MAX) == 0 ||
        mallopt(M_TOP_PAD, kReserve) == 0) {
        return;  // a non-glibc allocator: leave it as it is
    }
    // Larger than what is left of the heap: forces the extension, with the reservation.
    void* first = std::malloc(std::size_t{4} << 20);
    if (first == nullptr) {
        // No room for the reservation (ulimit -v, strict overcommit): glibc's defaults.
        (void)mallopt(M_TOP_PAD, 128 << 10);
        (void)mallopt(M_MMAP_MAX, 65536);
        return;
    }
    const auto lo = reinterpret_cast<std::uintptr_t>(first);
    const auto hi = reinterpret_cast<std::uintptr_t>(::sbrk(0));
    constexpr std::uintptr_t kPage = 4096;
    const std::uintptr_t from = (lo + kPage - 1) & ~(kPage - 1);
    if (hi > from) {
        (void)::madvise(reinterpret_cast<void*>(from), hi - from, MADV_HUGEPAGE);
    }
    std::free(first);
    // Later growth (clouds needing more than the reservation) asks for modest steps, so that a
    // strict memory limit is met by the allocation that needs it, not by a 1 GiB pad.
    (void)mallopt(M_TOP_PAD, 64 << 20);
#endif
}

}  // namespace

void tune_allocator() {
    static std::once_flag once;
    std::call_once(once, tune_allocator_once);
}

namespace {

/// "; did you mean --eps?" when one option's name is within two edits of `given` (`--esp`).
std::string did_you_mean(std::string given, const po::options_description& options) {
    given.erase(0, given.find_first_not_of('-'));
    const auto distance = [](const std::string& a, const std::string& b) {
        std::vector<std::size_t> row(b.size() + 1);
        std::iota(row.begin(), row.end(), std::size_t{0});
        for (std::size_t i = 1; i <= a.size(); ++i) {
            std::size_t diagonal = row[0];
            row[0] = i;
            for (std::size_t j = 1; j <= b.size(); ++j) {
                const std::size_t up = row[j];
                row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
                diagonal = up;
            }
        }
        return row[b.size()];
    };
    std::string best;
    std::size_t best_distance = 3;
    for (const auto& o : options.options()) {
        const std::string name = o->long_name();
        const std::size_t d = name.empty() || name == "inputs" ? 3 : distance(given, name);
        if (d < best_distance) {
            best_distance = d;
            best = name;
        }
    }
    return best.empty() ? "" : "; did you mean --" + best + "?";
}

}  // namespace

int Tool::run(int argc, char** argv, const std::function<void(Streams&)>& body) {
    tune_allocator();
    std::signal(SIGPIPE, SIG_IGN);  // a closed pipe becomes EPIPE, handled quietly below
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // PCL's info level writes to stdout
    Impl& im = *impl_;
    Streams io;
    io.tool_ = im.name;
    const po::options_description common = im.common_options(io);
    po::options_description all;
    all.add(im.own).add(common);
    po::options_description parse_set;
    parse_set.add(all);
    po::positional_options_description positional;
    if (im.inputs != nullptr) {
        parse_set.add_options()("inputs", po::value<std::vector<std::string>>(im.inputs),
                                im.inputs_help.c_str());
        positional.add("inputs", -1);
    }
    const auto report = [&](const std::string& what) {
        std::cerr << im.name << ": error: " << what << '\n';
    };
    try {
        po::variables_map vm;
        po::store(
            po::command_line_parser(argc, argv).options(parse_set).positional(positional).run(),
            vm);
        if (vm.count("help")) {
            im.print_help(all);
            return kOk;
        }
        if (vm.count("version")) {
            std::cout << im.name << " " << version() << '\n';
            return kOk;
        }
        po::notify(vm);
        im.apply_bindings(vm);
        im.check_output(io);
        if (im.inputs != nullptr && im.reads &&
            (!vm["input"].defaulted() || im.inputs->size() < im.min_inputs)) {
            im.inputs->insert(im.inputs->begin(), io.input_);  // -i, or stdin by default
        }
        const bool reads_stdin =
            im.inputs ? std::find(im.inputs->begin(), im.inputs->end(), "-") != im.inputs->end()
                      : im.reads && io.input_ == "-";
        if (reads_stdin && ::isatty(0)) {
            throw InvalidArgument("no input: standard input is a terminal; use -i FILE or a pipe");
        }
        io.input_name_ = io::display_name(io.input_);
        io.stderr_terminal_ = ::isatty(2) != 0;
        if (io.output_ == "-") {
            struct stat st {};
            if (::fstat(1, &st) == 0 && S_ISFIFO(st.st_mode)) {
                (void)::fcntl(1, F_SETPIPE_SZ, 1 << 20);
            }
        }
        io.parameters_ = [&im] {
            std::vector<std::pair<std::string, std::string>> out;
            if (im.apply_preset) {
                out.emplace_back("preset", im.preset);
            }
            for (const Binding& b : im.bindings) {
                out.emplace_back(b.name, b.show());
            }
            return out;
        };
        body(io);
        return io.failed_ ? kFailure : kOk;
    } catch (const po::unknown_option& e) {
        report(std::string(e.what()) + did_you_mean(e.get_option_name(), parse_set) + " (try '" +
               im.name + " --help')");
        return kUsage;
    } catch (const po::error& e) {
        report(std::string(e.what()) + " (try '" + im.name + " --help')");
        return kUsage;
    } catch (const InvalidArgument& e) {
        report(std::string(e.what()) + " (try '" + im.name + " --help')");
        return kUsage;
    } catch (const io::BrokenPipe&) {
        return kFailure;  // the reader went away (`| head`): nothing to say
    } catch (const std::bad_alloc&) {
        report(io.input_name_ + ": out of memory");
        return kFailure;
    } catch (const std::exception& e) {
        report(e.what());
        return kFailure;
    } catch (...) {
        report("unknown internal error");
        return kFailure;
    }
}

}  // namespace pc::cli
