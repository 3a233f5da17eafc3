#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <utility>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <pc/core/error.h>
#include <pc/io/pcd.h>
#include <pc/io/ply.h>
#include <pc/io/read.h>
#include <pc/io/text.h>

#include "parse_util.h"

namespace pc::io {

namespace {

enum class Format { kPcd, kPly, kText };

constexpr std::string_view kPcdKeywords[] = {"VERSION", "FIELDS",    "COLUMNS", "SIZE",
                                             "TYPE",    "COUNT",     "WIDTH",   "HEIGHT",
                                             "POINTS",  "VIEWPOINT", "DATA"};

bool is_name(std::string_view tok) {
    return std::all_of(tok.begin(), tok.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '/';
    });
}

Format detect(std::string_view bytes) {
    if (bytes.empty()) {
        throw IoError("empty input");
    }
    if (bytes.starts_with("ply\n") || bytes.starts_with("ply\r\n")) {
        return Format::kPly;
    }
    // Look at the first line that is neither blank nor a comment, within the first 64 KiB.
    detail::LineCursor cur{bytes.substr(0, std::size_t{1} << 16)};
    std::string_view line;
    while (cur.next(line)) {
        detail::Tokens toks{line, 0, ',', ';'};
        std::string_view tok;
        if (!toks.next(tok) || tok.front() == '#' || tok.starts_with("//")) {
            continue;
        }
        if (std::find(std::begin(kPcdKeywords), std::end(kPcdKeywords), tok) !=
            std::end(kPcdKeywords)) {
            return Format::kPcd;
        }
        double v;
        bool names = true;
        if (detail::parse_real(tok, v)) {
            return Format::kText;
        }
        do {
            names = names && is_name(tok);
        } while (toks.next(tok));
        if (names && bytes.substr(0, 4096).find('\0') == std::string_view::npos) {
            return Format::kText;  // a line of column names, then numbers
        }
        break;
    }
    throw IoError("not a PCD, PLY or XYZ text file (starts with " + detail::quote(bytes, 16) + ")");
}

}  // namespace

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

namespace {

/// All bytes of one input, held without copying or zero-filling: a read-only mapping of a regular
/// file, or a heap buffer filled from a pipe.
class InputBytes {
public:
    InputBytes() = default;
    InputBytes(const InputBytes&) = delete;
    InputBytes& operator=(const InputBytes&) = delete;
    ~InputBytes();
    [[nodiscard]] std::string_view view() const { return {data_, size_}; }

private:
    friend struct InputReader;  // fills the buffer
    void release();
    char* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t capacity_ = 0;  // of a heap buffer
    bool mapped_ = false;
};

InputBytes::~InputBytes() { release(); }

void InputBytes::release() {
    if (mapped_) {
        ::munmap(data_, size_);
    } else {
        std::free(data_);
    }
    data_ = nullptr;
    size_ = 0;
    capacity_ = 0;
    mapped_ = false;
}

/// Faults in the whole pages of [p, p + n) in one call before read(2) fills them. Faults taken
/// inside read() while it copies from a pipe stall the writer too: `cat 80MB.pcd | pc_convert`
/// took 0.08-0.23 s (median 0.19) without this and 0.07 s in 7 runs of 8 with it. Memory that
/// is about to be written anyway; ignored where MADV_POPULATE_WRITE (Linux 5.14) is missing.
void prefault(void* p, std::size_t n) {
#ifdef MADV_POPULATE_WRITE
    constexpr std::uintptr_t kPage = 4096;
    const std::uintptr_t lo = (reinterpret_cast<std::uintptr_t>(p) + kPage - 1) & ~(kPage - 1);
    const std::uintptr_t hi = (reinterpret_cast<std::uintptr_t>(p) + n) & ~(kPage - 1);
    if (hi > lo) {
        (void)::madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_POPULATE_WRITE);
    }
#else
    (void)p;
    (void)n;
#endif
}

/// One opened input: the file descriptor (closed at the end unless stdin), its stat, and the
/// reading steps of read_cloud().
struct InputReader {
    int fd = -1;
    bool own = false;
    struct stat st {};
    std::uint64_t max_bytes = 0;

    InputReader(const std::string& path, std::uint64_t max) : max_bytes(max) {
        const bool is_stdin = path == "-";
        fd = is_stdin ? 0 : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) {
            throw IoError(std::string("cannot open: ") + std::strerror(errno));
        }
        own = !is_stdin;
        if (::fstat(fd, &st) != 0) {
            throw IoError(std::string("cannot stat: ") + std::strerror(errno));
        }
        if (S_ISDIR(st.st_mode)) {
            throw IoError("is a directory");
        }
        if (S_ISBLK(st.st_mode)) {
            throw IoError("is a block device");
        }
        if (S_ISFIFO(st.st_mode)) {
            (void)::fcntl(fd, F_SETPIPE_SZ, 1 << 20);  // fewer wake-ups on large pipes
        }
    }
    InputReader(const InputReader&) = delete;
    InputReader& operator=(const InputReader&) = delete;
    ~InputReader() {
        if (own) {
            ::close(fd);
        }
    }

    [[nodiscard]] bool regular() const { return S_ISREG(st.st_mode) && st.st_size > 0; }

    [[noreturn]] void over_limit() const {
        throw IoError("input exceeds the limit of " + std::to_string(max_bytes) +
                      " B (--max-input-bytes)");
    }

    /// One read(2) into `to` (at most `n` bytes), retried on EINTR; 0 at the end of the input.
    std::size_t read_some(void* to, std::size_t n) const {
        while (true) {
            const ssize_t got = ::read(fd, to, n);
            if (got >= 0) {
                return static_cast<std::size_t>(got);
            }
            if (errno != EINTR) {
                throw IoError(std::string("read failed: ") + std::strerror(errno));
            }
        }
    }

    /// A read-only mapping of a regular file (no copy, no zero-fill; MAP_POPULATE faults it in
    /// with read-ahead), or false when the file system cannot map.
    bool map(InputBytes& in) const {
        const auto size = static_cast<std::uint64_t>(st.st_size);
        if (size > max_bytes) {
            throw IoError("input is " + std::to_string(size) + " B, above the limit of " +
                          std::to_string(max_bytes) + " B (--max-input-bytes)");
        }
        void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (p == MAP_FAILED) {
            return false;
        }
        in.data_ = static_cast<char*>(p);
        in.size_ = size;
        in.mapped_ = true;
        return true;
    }

    /// One more read into the heap buffer `in` (started by start_small), doubled when full;
    /// false at the end of the input. (A binary PCD's body never comes here: finish_binary.)
    bool read_more(InputBytes& in) const {
        if (in.size_ == in.capacity_) {
            if (in.size_ >= max_bytes) {
                over_limit();
            }
            const auto capacity =
                static_cast<std::size_t>(std::min<std::uint64_t>(in.capacity_ * 2, max_bytes + 1));
            char* grown = static_cast<char*>(std::realloc(in.data_, capacity));
            if (grown == nullptr) {
                throw std::bad_alloc();
            }
            in.data_ = grown;
            in.capacity_ = capacity;
        }
        const std::size_t n = read_some(in.data_ + in.size_, in.capacity_ - in.size_);
        if (n == 0) {
            return false;
        }
        in.size_ += n;
        return true;
    }

    /// A first buffer of 64 KiB: enough for nearly every header, small enough not to read a
    /// whole file before its header is seen.
    void start_small(InputBytes& in) const {
        in.data_ = static_cast<char*>(std::malloc(std::size_t{1} << 16));
        if (in.data_ == nullptr) {
            throw std::bad_alloc();
        }
        in.capacity_ = std::size_t{1} << 16;
    }

    void read_to_end(InputBytes& in) const {
        while (read_more(in)) {
        }
        if (in.size_ > max_bytes) {
            over_limit();
        }
    }

    /// The body of a binary PCD read straight into the cloud's memory (one copy of the cloud, not
    /// two), after the beginning of the input in `prefix`. The memory is reserved for what the
    /// header declares (address space only) and filled as the bytes arrive, so a header that lies
    /// costs only the bytes present. nullopt, with nothing more read, when that reservation fails.
    std::optional<ReadResult> finish_binary(PcdStart& start, std::string_view prefix) const {
        Blob& blob = start.result.blob;
        const std::uint64_t points = std::uint64_t{blob.cloud.width} * blob.cloud.height;
        auto& data = blob.cloud.data;
        try {
            reserve_points(blob, points);  // the body (points x point_step) and room for a label
        } catch (const std::bad_alloc&) {
            return std::nullopt;
        }
        prefault(data.data(), start.body_bytes);
        const std::size_t in_prefix =
            std::min<std::uint64_t>(prefix.size() - start.body_offset, start.body_bytes);
        data.assign(prefix.data() + start.body_offset,
                    prefix.data() + start.body_offset + in_prefix);
        constexpr std::size_t kStep = std::size_t{8} << 20;
        while (data.size() < start.body_bytes) {
            const std::size_t filled = data.size();
            data.resize(std::min<std::uint64_t>(start.body_bytes, filled + kStep));
            for (std::size_t at = filled; at < data.size();) {
                const std::size_t n = read_some(data.data() + at, data.size() - at);
                if (n == 0) {
                    throw IoError("truncated binary body: header declares " +
                                  std::to_string(points) + " points x " +
                                  std::to_string(blob.cloud.point_step) +
                                  " B = " + std::to_string(start.body_bytes) + " B, " +
                                  std::to_string(at) + " B present");
                }
                at += n;
            }
        }
        std::uint64_t trailing = prefix.size() - start.body_offset - in_prefix;
        char sink[1 << 16];
        for (std::size_t n; (n = read_some(sink, sizeof sink)) > 0;) {
            trailing += n;
            if (start.body_offset + start.body_bytes + trailing > max_bytes) {
                over_limit();
            }
        }
        if (trailing > 0) {
            start.result.notes.push_back(std::to_string(trailing) +
                                         " trailing bytes after the binary body");
        }
        update_is_dense(blob);
        return std::move(start.result);
    }
};

}  // namespace

ReadResult parse_cloud(std::string_view bytes) {
    switch (detect(bytes)) {
        case Format::kPcd:
            return parse_pcd(bytes);
        case Format::kPly:
            return parse_ply(bytes);
        case Format::kText:
            return parse_text(bytes);
    }
    throw IoError("unreachable");
}

ReadResult read_cloud(const std::string& path, std::uint64_t max_bytes) {
    try {
        const InputReader reader(path, max_bytes);
        // Read from the beginning in small steps: once it holds a binary PCD header, the body
        // goes straight into the cloud (one copy of the cloud in memory, not two: a mapped file
        // or a pipe buffer and then the cloud). Anything else is read whole and parsed.
        InputBytes bytes;
        reader.start_small(bytes);
        while (bytes.view().size() <= detail::kMaxHeaderBytes && reader.read_more(bytes)) {
            if (auto start = start_binary_pcd(bytes.view())) {
                // Declared sizes beyond the limit or beyond a file's end go the general way, which
                // reports them from the bytes actually present.
                const std::uint64_t total = start->body_offset + start->body_bytes;
                if (total <= max_bytes &&
                    (!reader.regular() || total <= static_cast<std::uint64_t>(reader.st.st_size))) {
                    if (auto r = reader.finish_binary(*start, bytes.view())) {
                        return std::move(*r);
                    }
                }
                break;
            }
        }
        if (reader.regular() &&
            bytes.view().size() < static_cast<std::uint64_t>(reader.st.st_size)) {
            InputBytes mapped;
            if (reader.map(mapped)) {  // the rest of a large text or PLY file: mapped, not copied
                return parse_cloud(mapped.view());
            }
        }
        reader.read_to_end(bytes);
        return parse_cloud(bytes.view());
    } catch (const IoError& e) {
        throw IoError(display_name(path) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw IoError(display_name(path) + ": out of memory while reading");
    }
}

}  // namespace pc::io
