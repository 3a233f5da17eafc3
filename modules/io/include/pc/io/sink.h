#pragma once

#include <cstddef>
#include <string>

namespace pc::io {

/// Where writers put bytes. Writers call write() in large chunks.
class ByteSink {
public:
    virtual ~ByteSink() = default;
    virtual void write(const void* data, std::size_t size) = 0;
    void write(const std::string& s) { write(s.data(), s.size()); }
};

/// Collects everything in memory (tests, small reports).
class StringSink final : public ByteSink {
public:
    using ByteSink::write;
    void write(const void* data, std::size_t size) override {
        out.append(static_cast<const char*>(data), size);
    }
    std::string out;
};

/// Thrown by FdSink when the reader of a pipe went away (EPIPE): not an error to report.
struct BrokenPipe {};

/// Writes to a file descriptor with write(2), retrying on EINTR and short writes.
/// Throws BrokenPipe on EPIPE and pc::IoError (naming `name`) on any other failure.
class FdSink final : public ByteSink {
public:
    FdSink(int fd, std::string name) : fd_(fd), name_(std::move(name)) {}
    using ByteSink::write;
    void write(const void* data, std::size_t size) override;

private:
    int fd_;
    std::string name_;
};

}  // namespace pc::io
