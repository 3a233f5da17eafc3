#include <pc/io/read.h>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

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

InputBytes::InputBytes(InputBytes&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      mapped_(std::exchange(other.mapped_, false)) {}

InputBytes& InputBytes::operator=(InputBytes&& other) noexcept {
    if (this != &other) {
        release();
        data_ = std::exchange(other.data_, nullptr);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, false);
    }
    return *this;
}

InputBytes::~InputBytes() { release(); }

void InputBytes::release() {
    if (mapped_) {
        ::munmap(data_, size_);
    } else {
        std::free(data_);
    }
    data_ = nullptr;
    size_ = 0;
    mapped_ = false;
}

InputBytes read_all(const std::string& path, std::uint64_t max_bytes) {
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
    InputBytes in;
    if (S_ISREG(st.st_mode) && st.st_size > 0) {
        const auto size = static_cast<std::uint64_t>(st.st_size);
        if (size > max_bytes) {
            throw IoError("input is " + std::to_string(size) + " B, above the limit of " +
                          std::to_string(max_bytes) + " B (--max-input-bytes)");
        }
        // Map the file: no copy, no zero-fill. MAP_POPULATE faults it in with read-ahead.
        void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (p != MAP_FAILED) {
            in.data_ = static_cast<char*>(p);
            in.size_ = size;
            in.mapped_ = true;
            return in;
        }
        // Some file systems cannot map: read it instead, below.
    }
    if (S_ISFIFO(st.st_mode)) {
        (void)::fcntl(fd, F_SETPIPE_SZ, 1 << 20);  // fewer wake-ups on large pipes
    }
    std::size_t capacity = S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) + 1 : 1 << 20;
    bool sized = false;
    while (true) {
        if (in.size_ == capacity || in.data_ == nullptr) {
            if (in.data_ != nullptr) {
                if (in.size_ >= max_bytes) {
                    throw IoError("input exceeds the limit of " + std::to_string(max_bytes) +
                                  " B (--max-input-bytes)");
                }
                capacity = static_cast<std::size_t>(std::min<std::uint64_t>(capacity * 2, max_bytes + 1));
            }
            char* grown = static_cast<char*>(std::realloc(in.data_, capacity));
            if (grown == nullptr) {
                throw std::bad_alloc();
            }
            in.data_ = grown;
        }
        const ssize_t n = ::read(fd, in.data_ + in.size_, capacity - in.size_);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            throw IoError(std::string("read failed: ") + std::strerror(errno));
        }
        if (n == 0) {
            break;
        }
        in.size_ += static_cast<std::size_t>(n);
        if (!sized && in.size_ <= detail::kMaxHeaderBytes) {
            // A binary PCD says its size in its header: one buffer of that size (plus one byte to
            // see the end) instead of doubling and copying. Only a hint: on failure, grow as usual.
            if (const auto total = pcd_binary_size({in.data_, in.size_});
                total && *total + 1 > capacity && *total < max_bytes) {
                sized = true;
                if (char* exact = static_cast<char*>(std::realloc(in.data_, *total + 1))) {
                    in.data_ = exact;
                    capacity = *total + 1;
                }
            }
        }
    }
    if (in.size_ > max_bytes) {
        throw IoError("input exceeds the limit of " + std::to_string(max_bytes) +
                      " B (--max-input-bytes)");
    }
    return in;
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
        const InputBytes bytes = read_all(path, max_bytes);
        return parse_cloud(bytes.view());
    } catch (const IoError& e) {
        throw IoError(display_name(path) + ": " + e.what());
    } catch (const std::bad_alloc&) {
        throw IoError(display_name(path) + ": out of memory while reading");
    }
}

}  // namespace pc::io
