#include <pc/io/read.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <pc/core/error.h>
#include <pc/io/pcd.h>
#include <pc/io/ply.h>
#include <pc/io/text.h>

#include "parse_util.h"

namespace pc::io {

namespace {

enum class Format { kPcd, kPly, kText };

constexpr std::string_view kPcdKeywords[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE",   "TYPE",
                                             "COUNT",   "WIDTH",  "HEIGHT",  "POINTS", "VIEWPOINT",
                                             "DATA"};

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
    throw IoError("not a PCD, PLY or XYZ text file (starts with " + detail::quote(bytes, 16) +
                  ")");
}

}  // namespace

std::string display_name(const std::string& path) { return path == "-" ? "<stdin>" : path; }

std::string read_all(const std::string& path, std::uint64_t max_bytes) {
    const bool is_stdin = path == "-";
    const int fd = is_stdin ? 0 : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        throw IoError(std::string("cannot open: ") + std::strerror(errno));
    }
    struct Closer {
        int fd;
        bool own;
        ~Closer() {
            if (own) {
                ::close(fd);
            }
        }
    } closer{fd, !is_stdin};
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        throw IoError(std::string("cannot stat: ") + std::strerror(errno));
    }
    if (S_ISDIR(st.st_mode)) {
        throw IoError("is a directory");
    }
    if (S_ISBLK(st.st_mode)) {
        throw IoError("is a block device");
    }
    std::string buf;
    std::size_t capacity = 1 << 20;
    if (S_ISREG(st.st_mode)) {
        if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
            throw IoError("input is " + std::to_string(st.st_size) + " B, above the limit of " +
                          std::to_string(max_bytes) + " B (--max-input-bytes)");
        }
        capacity = static_cast<std::size_t>(st.st_size) + 1;  // +1 to see EOF in one read
    } else if (S_ISFIFO(st.st_mode)) {
        (void)::fcntl(fd, F_SETPIPE_SZ, 1 << 20);  // fewer wake-ups on large pipes
    }
    buf.resize(capacity);
    std::size_t used = 0;
    while (true) {
        if (used == buf.size()) {
            if (used >= max_bytes) {
                throw IoError("input exceeds the limit of " + std::to_string(max_bytes) +
                              " B (--max-input-bytes)");
            }
            buf.resize(std::min<std::uint64_t>(buf.size() * 2, max_bytes + 1));
        }
        const ssize_t n = ::read(fd, buf.data() + used, buf.size() - used);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            throw IoError(std::string("read failed: ") + std::strerror(errno));
        }
        if (n == 0) {
            break;
        }
        used += static_cast<std::size_t>(n);
    }
    if (used > max_bytes) {
        throw IoError("input exceeds the limit of " + std::to_string(max_bytes) +
                      " B (--max-input-bytes)");
    }
    buf.resize(used);
    return buf;
}

ReadResult parse_cloud(std::string_view bytes) {
    switch (detect(bytes)) {
        case Format::kPcd: return parse_pcd(bytes);
        case Format::kPly: return parse_ply(bytes);
        case Format::kText: return parse_text(bytes);
    }
    throw IoError("unreachable");
}

ReadResult read_cloud(const std::string& path, std::uint64_t max_bytes) {
    try {
        const std::string bytes = read_all(path, max_bytes);
        return parse_cloud(bytes);
    } catch (const IoError& e) {
        throw IoError(display_name(path) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw IoError(display_name(path) + ": out of memory while reading");
    }
}

}  // namespace pc::io
