#include <cerrno>
#include <cstring>

#include <unistd.h>

#include <pc/core/error.h>
#include <pc/io/sink.h>

namespace pc::io {

void FdSink::write(const void* data, std::size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd_, p, size);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            if (errno == EPIPE) {
                throw BrokenPipe{};
            }
            throw IoError(name_ + ": write failed: " + std::strerror(errno));
        }
        p += n;
        size -= static_cast<std::size_t>(n);
    }
}

}  // namespace pc::io
